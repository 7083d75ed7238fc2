#pragma once
// The backend side of one joint. The layer validates a JointDef and resolves it into a
// JointPeerDef: frames in each body's peer frame (centre of mass, principal axes, as BodyPeer
// states are), springs in SI units, the rest length of a distance joint. A backend only applies it,
// and reports what every backend reports the same way (JointPeer).
//
// The joint frame: origin at the anchor; X along the joint's axis (hinge and slider axis, cone
// twist axis, wheel suspension direction); for a wheel, Y along the axle (spin axis); Z = X x Y.
// frameA is that frame fixed in A (in the world frame when A is the world), frameB the same frame
// fixed in B. They coincide at creation, so every position starts at 0.
#include <cstdint>
#include <memory>
#include <optional>
#include <typeinfo>

#include "anyphys/joint_types.hpp"
#include "anyphys/math.hpp"
#include "anyphys/peers/body_peer.hpp"

namespace anyphys {

struct JointPeerDef {
    JointType type = JointType::Ball;
    BodyPeer* bodyA = nullptr;            ///< null: the static world
    BodyPeer* bodyB = nullptr;            ///< never null
    std::uint64_t userData = 0;           ///< the layer's key for this joint
    Transform frameA;                     ///< the joint frame in A's peer frame (or the world)
    Transform frameB;                     ///< the joint frame in B's peer frame
    // ---- distance: anchors in each body's peer frame (A's in the world when A is the world) ----
    Vec3 anchorA = Vec3::Zero();
    Vec3 anchorB = Vec3::Zero();
    double length = 0.0;                  ///< m, rest length (> 0)
    std::optional<double> minLength;      ///< m: rope-like when only maxLength, a range with both
    std::optional<double> maxLength;
    // ---- cone ----
    double swingLimit = 3.141592653589793;  ///< rad, half-angle of the cone about frame X
    std::optional<JointLimits> twistLimits; ///< rad, about frame X
    // ---- wheel ----
    bool steering = false;                ///< the suspension frame may turn about X (setSteeringAngle)
    // ---- common ----
    std::optional<JointLimits> limits;    ///< hinge angle, slider offset, wheel suspension travel
    std::optional<JointMotor> motor;      ///< hinge and wheel spin (rad/s, N m), slider (m/s, N)
    std::optional<JointSpringSI> spring;  ///< toward position 0 (distance: toward `length`)
    bool collideConnected = false;        ///< A and B may collide with each other
};

/// What a joint reports, identically on every backend. "Position" and "speed" by type:
///   hinge       angle of B about frame X relative to A (rad), and its rate
///   slider      offset of B's frame origin from A's along frame X (m), and its rate
///   wheel       suspension offset along frame X (m); speed: spin of B about the axle (rad/s)
///   distance    current length minus `length` (m), and its rate
///   ball, cone  swing: the angle between A's and B's frame X axes (rad), and its rate
///   fixed       0
/// Reactions are what the joint applies to B over the last step, as a mean force (N) and a
/// torque about B's anchor (N m), world frame: impulse / dt on every backend, whatever the
/// engine's own unit.
class JointPeer {
public:
    virtual ~JointPeer() = default;

    virtual double position() const = 0;
    virtual double speed() const = 0;
    virtual Vec3 reactionForce() const = 0;
    virtual Vec3 reactionTorque() const = 0;

    /// Changes that take effect from the next step (the layer has validated them).
    virtual void setMotor(const std::optional<JointMotor>& motor) = 0;
    virtual void setLimits(const std::optional<JointLimits>& limits) = 0;
    virtual void setSpring(const std::optional<JointSpringSI>& spring) = 0;
    /// Wheels with `steering`: turns the suspension frame on A about its X axis to `angle` (rad).
    virtual void setSteeringAngle(double angle) { (void)angle; }

    /// Escape hatch: the engine's joint object if `pointerType` is typeid of a pointer to it.
    virtual void* nativeObject(const std::type_info& pointerType) { (void)pointerType; return nullptr; }
};

}  // namespace anyphys
