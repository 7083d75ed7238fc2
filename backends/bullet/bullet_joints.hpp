#pragma once
// Joints of the Bullet backend. Each joint is one Bullet constraint:
//   fixed     btFixedConstraint (a 6-DOF spring 2 with every axis locked)
//   ball      btPoint2PointConstraint
//   hinge     btGeneric6DofSpring2Constraint, rotation about frame X free (Euler order XYZ, so
//             the free angle is the first one and has the full range), motor and spring on
//             that angle
//   slider    btGeneric6DofSpring2Constraint, translation along frame X free
//   wheel     btGeneric6DofSpring2Constraint, translation along X (suspension: spring)
//             and rotation about Y (the axle: motor) free, Euler order YXZ so the spin angle
//             has the full range; steering turns frame A about X (setFrames)
//             (hinge, slider and wheel: SlidingDofConstraint below, which moves A's lever where B travels)
//   cone      btConeTwistConstraint (twist axis = frame X); asymmetric twist limits by turning
//             B's frame about X to the middle of the range
//   distance  DistanceConstraint below: one row along the line between the anchors (rigid,
//             min / max as one-sided rows, or a spring's impulse, implicit when stiff)
// Each is wrapped in a DecoupledConstraint, which is what the Bullet world solves: it hands the
// rigid rows over decoupled and adds the stop rows of hinge, slider and wheel limits and their
// springs' rows (stable at any stiffness; Bullet's own 6-DOF spring is not used).
// Positions and speeds are computed here from the bodies' states (never from Bullet's angles),
// reactions from Bullet's joint feedback summed over the step's substeps.
#include <memory>
#include <optional>

#include <btBulletDynamicsCommon.h>

#include "anyphys/peers/joint_peer.hpp"

namespace anyphys::bullet {

class BulletWorld;
class BulletBodyPeer;

/// A rod, rope or spring between two anchors: one scalar row along the line through them.
class DistanceConstraint final : public btTypedConstraint {
public:
    DistanceConstraint(btRigidBody& a, btRigidBody& b, const btVector3& anchorA, const btVector3& anchorB, double length);

    void getInfo1(btConstraintInfo1* info) override;
    void getInfo2(btConstraintInfo2* info) override;
    void setParam(int num, btScalar value, int axis = -1) override;
    btScalar getParam(int num, int axis = -1) const override;

    std::optional<double> minLength, maxLength;
    std::optional<JointSpringSI> spring;
    bool softSpringRows = true;  ///< the solver honours a row's CFM (bullet_joint_spring.hpp)
    int springsOnBusierBody = 1;  ///< set by the world every step (bullet_joint_spring.hpp)

private:
    enum class Row { None, Rigid, Min, Max, Spring };
    // The rows of this substep (getInfo1 and getInfo2 see the same poses).
    void rows(Row out[2], int& count) const;

    btVector3 anchorA_, anchorB_;
    double length_;
    btScalar erp_ = -1, cfm_ = 0;  // erp < 0: the solver's
};

/// Bullet's 6-DOF spring 2 (hinge, slider, wheel) with, where B travels along a linear axis
/// (slider, wheel), A's side of each linear row acting at B's anchor. Bullet puts each body's side
/// at its own anchor, the Jacobian of keeping the two anchors together. Once B has slid along the
/// axis they are apart, and a row across the axis then pushes A and B along parallel lines that
/// do not meet: a torque on the pair from nowhere (a free pair turning while B slid out gained 90x
/// its angular momentum in 10 s). The rows measure B's offset along axes turning with A, whose
/// Jacobian acts on A at the point under B's anchor. A hinge's rows stay Bullet's: there the
/// anchors part only by the error the rows close (moving its lever too opened a landing ragdoll
/// pile's joints to 117 mm instead of 67).
class SlidingDofConstraint final : public btGeneric6DofSpring2Constraint {
public:
    using btGeneric6DofSpring2Constraint::btGeneric6DofSpring2Constraint;

    void getInfo1(btConstraintInfo1* info) override;
    void getInfo2(btConstraintInfo2* info) override;

private:
    bool travels() const;

    int rows_ = 0;  // this substep's, from getInfo1
};

/// Wraps a Bullet constraint and hands the solver its rigid rows (those without bounds) turned
/// into a basis where they do not interact: rows Q J with Q the eigenvectors of K = J M^-1 J^T,
/// errors Q c. The same constraint (Q is orthonormal), but sequential impulses then solve a
/// joint's rigid block in one pass instead of converging row by row, which takes hundreds of
/// passes where a lever is long against a small inertia (a near point mass on a 1 m arm of a ball
/// joint, m L^2 / I = 6250, opened its cone by 0.5 rad). Bounded rows (limits, motors, springs)
/// pass through unchanged; Bullet's joint feedback sums every row, so reactions are unchanged.
class DecoupledConstraint final : public btTypedConstraint {
public:
    explicit DecoupledConstraint(btTypedConstraint& inner);

    void buildJacobian() override { inner_.buildJacobian(); }
    void getInfo1(btConstraintInfo1* info) override;
    void getInfo2(btConstraintInfo2* info) override;
    void setParam(int num, btScalar value, int axis = -1) override { inner_.setParam(num, value, axis); }
    btScalar getParam(int num, int axis = -1) const override { return inner_.getParam(num, axis); }

    bool decouple = true;  ///< false: the inner constraint's rows as they are
    bool softSpringRows = true;  ///< the solver honours a row's CFM (bullet_joint_spring.hpp)
    int springsOnBusierBody = 1;  ///< set by the world every step (bullet_joint_spring.hpp)

    /// The joint's axis (frame X of A): the offset of B's frame origin along it, or the angle of
    /// B about it (wrapped to (-pi, pi]).
    struct Axis {
        bool angular = false;
        btTransform frameA, frameB;  // the joint frames in A's and B's centre-of-mass frames
    };
    /// Stops on the axis: two one-sided rows added after the inner constraint's, which close the
    /// gap to a stop in the step they meet it (a speculative row, as contacts are) and push out of
    /// an overshoot at the solver's ERP. Bullet's 6-DOF ranges instead stop a body dead wherever it
    /// is when it would cross within the step (its bounce logic) and then let it creep on at ERP x
    /// gap / h: a slider 1 m down a 30 deg incline reached its stop at 0.97 s instead of 0.64.
    struct AxisStops : Axis {
        btScalar lower = 0, upper = 0;
    };
    std::optional<AxisStops> stops;
    /// A spring-damper on the axis toward position 0: one row after the stops applying the
    /// spring's impulse (bullet_joint_spring.hpp: implicit when stiff), solved with the inner
    /// constraint's rigid rows. Bullet's own 6-DOF spring diverged at 15 Hz with 60 Hz steps.
    struct AxisSpring : Axis {
        double stiffness = 0, damping = 0;  // N/m and N s/m, or N m/rad and N m s/rad
        double turns = 0;                   // rad: the hinge's whole turns (2 pi k), added to its wrapped angle
    };
    std::optional<AxisSpring> spring;

private:
    struct AxisRow {
        btScalar position;
        btVector3 l1, a1, l2, a2;  // J: d(position)/dt = l1 . vA + a1 . wA + l2 . vB + a2 . wB
    };
    AxisRow axisRow(const Axis& axis) const;
    int stopRows(btConstraintInfo2* info, int row);
    void innerRows(btConstraintInfo2* info);
    void springRow(btConstraintInfo2* info, int innerRows, int row);

    btTypedConstraint& inner_;
    int rows_ = 0;
    // Scratch rows of the inner constraint (row r at index 3 r), kept between steps.
    btAlignedObjectArray<btScalar> j1l_, j1a_, j2l_, j2a_, error_, cfm_, lower_, upper_;
};

class BulletJointPeer final : public JointPeer {
public:
    BulletJointPeer(BulletWorld& world, const JointPeerDef& def);
    ~BulletJointPeer() override;

    double position() const override { return position_; }
    double speed() const override { return speed_; }
    Vec3 reactionForce() const override { return reactionForce_; }
    Vec3 reactionTorque() const override { return reactionTorque_; }
    void setMotor(const std::optional<JointMotor>& motor) override;
    void setLimits(const std::optional<JointLimits>& limits) override;
    void setSpring(const std::optional<JointSpringSI>& spring) override;
    void setSteeringAngle(double angle) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for the world -------------------------------------------------------------------
    /// The constraint in the Bullet world (the decoupling wrapper around the engine's own).
    btTypedConstraint& constraint() { return *decoupled_; }
    bool collideConnected() const { return def_.collideConnected; }
    bool sprung() const { return def_.spring.has_value(); }
    /// The most sprung joints on either of its bodies (BulletWorld counts them every step).
    void setSpringsOnBusierBody(int count);
    /// Before the step's first substep.
    void beginStep();
    /// Before each substep of h seconds: clears Bullet's feedback.
    void beginSubstep();
    /// After each substep: adds its impulses to the step's.
    void endSubstep(double h);
    /// After the step: reactions (mean over dt), position and speed.
    void endStep(double dt);
    /// The world is going away (or the joint was destroyed): never touch it again.
    void detached() { world_ = nullptr; }

private:
    void applyMotor();
    void applyLimits();
    void applySpring();
    void wakeBodies();
    void measure();
    double hingeAngle() const;
    Transform steeredFrameA() const;
    Transform frameAWorld() const;
    Transform frameBWorld() const;
    BodyState stateA() const;
    BodyState stateB() const;

    BulletWorld* world_;
    JointPeerDef def_;
    double steeringAngle_ = 0.0;
    double twistOffset_ = 0.0;  // cone: B's Bullet frame turned about X by this (rad)
    std::unique_ptr<btTypedConstraint> constraint_;     // Bullet's constraint of this type
    std::unique_ptr<DecoupledConstraint> decoupled_;    // what the world solves
    SlidingDofConstraint* dof_ = nullptr;  // hinge, slider, wheel
    DistanceConstraint* distance_ = nullptr;
    btJointFeedback feedback_;
    Vec3 stepImpulse_ = Vec3::Zero(), stepAngularImpulse_ = Vec3::Zero();  // on B, about B's anchor
    bool solved_ = false;  // some substep of this step solved the joint
    double position_ = 0.0, speed_ = 0.0;
    Vec3 reactionForce_ = Vec3::Zero(), reactionTorque_ = Vec3::Zero();
};

}  // namespace anyphys::bullet
