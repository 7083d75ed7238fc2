#pragma once
// Joints of the ODE backend. Each anyphys joint is one to four ODE joints ("parts") between the
// same bodies, always with B as ODE's body 1 and A (or the world) as body 2, so ODE's rates
// (w1 - w2, v1 - v2) are B's motion relative to A, the sign anyphys reports:
//   fixed     dJointFixed
//   ball      dJointBall
//   hinge     dJointBall plus AMotors (user mode): axis alignment (ODE's hinge rows, with the
//             joints' own ERP), motor and spring, lower and upper stop
//   slider    dJointSlider, plus an LMotor for motor and spring; limits are one-sided rows like
//             a distance's minLength / maxLength
//   distance  dJointDBall (rigid, or soft with the spring's ERP / CFM); minLength / maxLength are
//             one-sided speculative rows made as ODE contact joints along the line of the
//             anchors, remade every ODE step (see ropeRows)
//   cone      dJointBall, plus an AMotor whose rows are the swing cone and the twist limits
//   wheel     dJointHinge2 (ODE's car wheel: A is body 1 there, see ode_joints.cpp); travel
//             limits are one-sided rows like a distance's minLength / maxLength
// Springs are ODE constraint rows softened with ERP = h k / (h k + c), CFM = 1 / (h k + c)
// (ODE manual, "Joint error and the ERP"), recomputed every ODE step for its length h: an
// implicit spring-damper, stable at any stiffness. Where the row is a motor row (AMotor, LMotor)
// its target speed carries the position error: vel = -ERP / h x. A soft spring's stiffness is a
// force instead and its row only the damper (ode_joint_spring.hpp), so it keeps its swing.
// Angles, offsets and their rates are measured here from the bodies' poses, never read from ODE,
// so every backend reports the same numbers; the user-mode AMotor rows are fed those angles.
// Stops (hinge limits, cone swing and twist, slider and wheel travel, distance range) are
// one-sided rows present in every step, speculative like the native solver's: ahead of the stop
// the row lets the joint close exactly the remaining gap this step (ODE's own stops only start
// once past them, so a fast joint overshoots by a step's motion); past it, the row pushes back
// with the world's ERP. Angular ones are AMotor rows, or contact rows at B's centre where B
// swings on an arm (centreStop); linear ones are frictionless contact joints.
#include <ode/ode.h>

#include <array>
#include <cstddef>

#include "anyphys/peers/joint_peer.hpp"
#include "anyphys/peers/joint_push.hpp"
#include "ode_body.hpp"
#include "ode_joint_spring.hpp"
#include "ode_tuning.hpp"

namespace anyphys::ode {

class OdeWorld;

class OdeJoint final : public JointPeer {
public:
    OdeJoint(OdeWorld& world, const JointPeerDef& def);
    ~OdeJoint() override;
    OdeJoint(const OdeJoint&) = delete;
    OdeJoint& operator=(const OdeJoint&) = delete;

    double position() const override { return position_; }
    double speed() const override { return speed_; }
    Vec3 reactionForce() const override { return reactionForce_; }
    Vec3 reactionTorque() const override { return reactionTorque_; }
    void setMotor(const std::optional<JointMotor>& motor) override;
    void setLimits(const std::optional<JointLimits>& limits) override;
    void setSpring(const std::optional<JointSpringSI>& spring) override;
    void setSteeringAngle(double angle) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for the world ------------------------------------------------------------------
    OdeBody* bodyA() const { return a_; }
    OdeBody* bodyB() const { return b_; }
    bool collideConnected() const { return def_.collideConnected; }
    /// Effect::Joints on or off.
    void setEnabled(bool enabled);
    /// Before each ODE step of h seconds: the rows that follow the bodies (springs, cone axes,
    /// angles of the user-mode AMotor), and the feedback cleared.
    void beforeOdeStep(double h);
    /// After each ODE step: the force the step's rows applied to B, summed.
    void afterOdeStep();
    /// After the anyphys step of dt seconds in `substeps` ODE steps: reactions, position, speed.
    void finishStep(double dt, int substeps);
    /// kg: the heavier dynamic body's mass (0 if neither is dynamic).
    double pairMass() const;
    /// 1/kg: the bound on one of its rows' weight J M^-1 J^T (OdeBody::rowWeightBound, summed).
    double rowWeightBound() const;
    /// ODE gives the type's main rows no CFM of their own: they take the world's (slider, wheel).
    bool mainRowsTakeTheWorldsCfm() const { return def_.type == JointType::Slider || def_.type == JointType::Wheel; }
    /// Simulated with a spring.
    bool sprung() const { return def_.spring.has_value() && enabled_; }
    std::size_t slot = 0;  // index in the world's joint list (kept by the world)
    int springsOnBusierBody = 1;  // sprung joints on the busier of A and B (kept by the world)

private:
    struct Part {
        dJointID id = nullptr;
        dJointFeedback feedback{};
        bool bIsBody1 = true;
    };
    // The joint frame in the world, as fixed in A (steering applied) and in B.
    Transform frameInA() const;
    Transform frameInB() const;
    Vec3 anchorAWorld() const;  // distance: A's anchor in the world
    Vec3 anchorBWorld() const;  // B's anchor (distance: anchorB; otherwise frameB's origin)
    BodyState stateA() const;
    double hingeAngle(const Transform& fa, const Transform& fb) const;  // unwrapped near lastAngle_
    double twistAngle(const Transform& fa, const Transform& fb) const;
    double measurePosition() const;
    void addPart(dJointID id, bool bIsBody1);
    void attach(dJointID id) const;
    dBodyID standIn(const BodyState& pose) const;
    void configureMotors();   // the static parameters of the motor parts (after a setter)
    void wakeBodies() const;
    bool centreStop(const Vec3& axis, const Vec3& anchor, Vec3& t, double& lever) const;
    void ropeRows(double h);  // distance min / max: the contact rows of the next ODE step
    void addStopRow(const Vec3& at, const Vec3& normal, double gap, double h);
    /// The CFM of the joint's own rows: the world's, made stiffer for a heavy pair (pairCfm),
    /// never below the conditioning floor (conditionedCfm).
    double rowCfm() const;
    /// Gives every row whose CFM ODE lets a joint set (all but a slider's and a wheel's main
    /// rows, and the springs', which come from their stiffness) the CFM `cfm`.
    void applyRowCfm(double cfm);
    /// Lowers the main joint's ERP where its anchor gap would be pulled shut faster than
    /// kJointPushMaxVelocity this ODE step of h seconds (ball, hinge, cone, fixed).
    void capAnchorPull(const Transform& fa, const Transform& fb, double h);

    OdeWorld& world_;
    JointPeerDef def_;
    OdeBody* a_;
    OdeBody* b_;
    dBodyID anchorBody_ = nullptr;  // wheel held to the world / a static body: a kinematic stand-in for A
    dBodyID bStandIn_ = nullptr;    // static B: a kinematic stand-in
    dBodyID idB_ = nullptr;         // ODE's body 1: B's dBody or its stand-in
    std::array<Part, 4> parts_{};
    std::size_t partCount_ = 0;
    dJointID main_ = nullptr;    // the type's ODE joint
    dJointID amotor_ = nullptr;  // hinge (motor, spring), cone (swing and twist stops)
    dJointID stops_ = nullptr;   // hinge: the AMotor holding the lower and upper stops
    dJointID align_ = nullptr;   // hinge: the AMotor keeping B's axis on A's
    dJointID lmotor_ = nullptr;  // slider
    dJointGroupID stopGroup_ = nullptr;  // distance min / max, slider and wheel stops: this step's contact rows
    std::array<dJointFeedback, 2> stopFeedback_{};
    int stopRows_ = 0;
    bool enabled_ = true;        // Effect::Joints
    bool rod_ = true;            // distance: the double ball is on (no range, or a spring)
    double steering_ = 0.0;
    double lastAngle_ = 0.0;     // hinge: unwrapped angle at the last measurement
    double anchorErp_ = kJointErp;  // ball, hinge, cone, fixed: the main joint's ERP (capAnchorPull)

    double position_ = 0.0, speed_ = 0.0;
    Vec3 reactionForce_ = Vec3::Zero(), reactionTorque_ = Vec3::Zero();
    Vec3 sumForce_ = Vec3::Zero(), sumTorque_ = Vec3::Zero();  // on B (about its centre), this step
    SpringPush springPush_;  // the explicit spring's force on B, this ODE step
    int stepped_ = 0;  // ODE steps of this anyphys step that simulated the joint (awake, enabled)
};

}  // namespace anyphys::ode
