#pragma once
// Joints of the native backend: what the layer resolved (JointPeerDef), what a game changes at run
// time (motor, limits, spring, steering), the impulses the solver carries from step to step, and
// what the joint reports. Joints live in slots of one array, visited in slot order.
#include <array>
#include <cstdint>
#include <vector>

#include "anyphys/peers/joint_peer.hpp"

namespace anyphys::native {

class NativeWorld;

/// The world in a joint's body slot (JointPeerDef::bodyA == nullptr).
inline constexpr std::uint32_t kWorldBody = 0xFFFFFFFFu;

/// Impulse slots a joint's rows keep from pass to pass and step to step (warm starting). Each
/// joint type uses the slots of the rows it has.
enum JointRow : int {
    kPointX, kPointY, kPointZ,        // anchor coincidence (ball, hinge, cone, fixed)
    kAngle0, kAngle1, kAngle2,        // rotation locks (fixed, slider: 3; hinge, wheel: 2)
    kLinear0, kLinear1,               // sliding locks across the axis (slider, wheel)
    kLower, kUpper,                   // limits (hinge, slider, wheel travel, distance min, cone swing / twist)
    kTwistLower, kTwistUpper,         // cone twist limits
    kMotor, kSpring, kLength,         // motor, spring, rigid distance
    kRowCount
};

struct NativeJoint {
    bool alive = false;
    JointPeerDef def;                   // bodies as given by the layer (BodyPeer pointers)
    std::uint32_t bodyA = kWorldBody;   // body slots of the world, or kWorldBody
    std::uint32_t bodyB = kWorldBody;
    double steeringAngle = 0.0;         // rad, wheels with steering
    std::array<double, kRowCount> impulse{};  // accumulated per row (N s, N m s), kept between steps
    // PGS: the impulses as the substep's solve passes left them, kept by its position pass before
    // any relax pass adds to them; the next substep's warm start begins from these (joint_solver.hpp).
    std::array<double, kRowCount> solvedImpulse{};
    bool solvedImpulseFresh = false;
    /// Forgets a row's impulse (its motor, limit or spring changed).
    void releaseRow(int row) { impulse[static_cast<std::size_t>(row)] = solvedImpulse[static_cast<std::size_t>(row)] = 0.0; }
    // The spring's stiffness is explicit this substep: decided once, at its warm start, from the
    // substep's starting pose (the solver's springRow).
    bool springExplicit = false;
    // What the joint reports (JointPeer), updated at the end of each step.
    double position = 0.0;
    double speed = 0.0;
    Vec3 reactionForce = Vec3::Zero();
    Vec3 reactionTorque = Vec3::Zero();
    // Sums over the current step's substeps (reactions).
    Vec3 stepLinear = Vec3::Zero();
    Vec3 stepAngular = Vec3::Zero();    // about B's centre of mass
};

class NativeJointPeer final : public JointPeer {
public:
    NativeJointPeer(NativeWorld& world, std::uint32_t index) : world_(world), index_(index) {}
    std::uint32_t index() const { return index_; }

    double position() const override;
    double speed() const override;
    Vec3 reactionForce() const override;
    Vec3 reactionTorque() const override;
    void setMotor(const std::optional<JointMotor>& motor) override;
    void setLimits(const std::optional<JointLimits>& limits) override;
    void setSpring(const std::optional<JointSpringSI>& spring) override;
    void setSteeringAngle(double angle) override;

private:
    NativeJoint& joint() const;

    NativeWorld& world_;
    std::uint32_t index_;
};

}  // namespace anyphys::native
