#pragma once
// The Box2D backend's joint peer: one Box2D 2.4 joint in the XY plane, and what the layer asks of
// it that Box2D does differently.
//
//   fixed     b2WeldJoint (stiffness 0: rigid)
//   hinge     b2RevoluteJoint about Z (frame X is +Z or -Z: angles, limits and motor speeds are
//             turned to Box2D's +Z when it is -Z); a planar ball arrives as a hinge about +Z.
//             Spring: impulses applied here with the pin acting (the revolute has none).
//   slider    b2PrismaticJoint along frame X (in the plane). Spring: a b2WheelJoint on the same
//             anchors and axis (the prismatic has none).
//   distance  b2DistanceJoint: rigid rod (min = max = length), rope or range (minLength /
//             maxLength), spring toward `length` (Box2D's own soft spring)
//   wheel     b2WheelJoint: suspension along frame X with Box2D's spring and limits, free spin
//             about the axle (frame Y, +Z or -Z), motor on the spin
//   ball      (received directly, not through the layer) as the hinge about Z.
// Position and speed are computed here from the bodies' poses and velocities (not from Box2D's
// joint getters), so they mean what joint_peer.hpp says on every backend. Reactions are Box2D's
// joint impulses (the spring's joint's included, and a soft spring's explicit pull) summed over
// the step's substeps, divided by dt.
//
// Springs: Box2D's soft springs (wheel, distance) are implicit over the whole step, which
// damps a free oscillation by about (omega h)^2 / 4 of its swing per step (an undamped 0.7 Hz
// slider spring kept 23 % of its swing after 10 s at 60 Hz). So a soft spring's stiffness is
// applied here instead, as the impulse -h k C from the substep's start before each Box2D step
// (symplectic Euler: a free spring keeps its energy), while its damping stays Box2D's, implicit
// (the Box2D joint keeps stiffness ~0 and damping c). A stiff spring, where that explicit step
// would lose its accuracy or diverge, stays wholly Box2D's. The rule is the native and ODE
// joints' (ode_joint_spring.hpp). A hinge's spring is all applied here, for the joint alone with
// its pin, explicit or implicit by the same rule (hingeSpringImpulse).
//
// The b2Joint exists only while the world simulates joints (Effect::Joints); the peer keeps what
// it needs to build it again (the definition with the setters' changes, the reference angle).
#include <box2d/box2d.h>

#include <cstddef>

#include "anyphys/peers/joint_peer.hpp"
#include "box2d_body.hpp"

namespace anyphys::box2d {

class Box2dWorld;

class Box2dJoint final : public JointPeer {
public:
    /// Validates the frames for the plane (throws anyphys::Error) and computes the joint's
    /// geometry on the Box2D bodies; `ground` is the world's static anchor body, used when
    /// def.bodyA is null. The b2Joint is built by enable().
    Box2dJoint(Box2dWorld& world, const JointPeerDef& def, b2Body* ground);
    /// Destroys the b2Joint too if the world still has it (a peer dropped without destroyJoint).
    ~Box2dJoint() override;
    Box2dJoint(const Box2dJoint&) = delete;
    Box2dJoint& operator=(const Box2dJoint&) = delete;

    double position() const override;
    double speed() const override;
    Vec3 reactionForce() const override { return reactionForce_; }
    Vec3 reactionTorque() const override { return reactionTorque_; }
    void setMotor(const std::optional<JointMotor>& motor) override;
    void setLimits(const std::optional<JointLimits>& limits) override;
    void setSpring(const std::optional<JointSpringSI>& spring) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for the world ----------------------------------------------------------------
    /// Builds (on) or destroys (off) the b2Joint in `world`.
    void enable(b2World& world, bool on);
    /// The world let go of the joint (destroyed its b2Joint, or is itself going away).
    void detach() {
        world_ = nullptr;
        joint_ = nullptr;
        reactionForce_.setZero();
        reactionTorque_.setZero();
    }
    b2Joint* b2() const { return joint_; }
    /// Still in the world (not let go with one of its bodies, nor after the world went away).
    bool attached() const { return world_ != nullptr; }
    /// The joint holds this body.
    bool holds(const Box2dBody& body) const { return &body == a_ || &body == b_; }
    /// The joint has a spring acting in Box2D (joints on; a distance range not closed).
    bool sprung() const;
    /// The Box2D bodies the joint holds (A: the ground body when held to the world).
    b2Body* bodyA() const;
    b2Body* bodyB() const { return b_->b2(); }
    /// Each step: begin with the substep h and the most sprung joints on either of its moving
    /// bodies (it chooses the spring's explicit or implicit stiffness for the step), then before
    /// and after every Box2D step, then end with the whole step's duration.
    void beginStep(double h, int springsOnBusierBody);
    /// A soft spring's pull of the substep's start, on both bodies' velocities.
    void beforeSubstep(double h);
    /// Adds the Box2D step's joint impulses to the step's sums.
    void afterSubstep();
    void endStep(double dt);
    /// Index in the world's joint list (kept by the world).
    std::size_t slot = 0;

private:
    /// World anchor points: B's, and for a distance joint A's.
    b2Vec2 anchorA() const { return bodyA()->GetWorldPoint(localAnchorA_); }
    b2Vec2 anchorB() const { return bodyB()->GetWorldPoint(localAnchorB_); }
    /// Frame X of A in the world (slider and wheel).
    b2Vec2 axis() const { return bodyA()->GetWorldVector(localAxisA_); }
    /// Sliders take their spring from a second Box2D joint (see makeSpring).
    bool springJoint() const { return def_.type == JointType::Slider; }
    b2Joint* makeSpring(b2World& world) const;
    /// The Box2D joint that holds the spring (the spring's own, or the joint itself), or null.
    b2Joint* springHolder() const;
    /// Sets the stiffness the Box2D joint steps implicitly (its damping stays the spring's).
    void setImplicitStiffness(float stiffness);
    /// The spring's direction, stretch and inverse mass now (see SpringAxis in the .cpp).
    struct SpringAxis;
    bool springAxis(SpringAxis& out, double h) const;
    /// A hinge's spring impulse on B for the substep of h seconds (about +Z, Box2D's sense).
    double hingeSpringImpulse(const SpringAxis& line, double h) const;
    void applyMotor();
    void applyLimits();
    void applySpring();
    void wake();

    Box2dWorld* world_;
    JointPeerDef def_;             // with the setters' changes
    Box2dBody* a_;                 // null: the world (ground_)
    Box2dBody* b_;
    b2Body* ground_;
    b2Joint* joint_ = nullptr;
    b2Joint* spring_ = nullptr;    // slider with a spring: a wheel joint
    b2Vec2 localAnchorA_{0.0f, 0.0f};  // in A's Box2D body frame (world frame for the world)
    b2Vec2 localAnchorB_{0.0f, 0.0f};
    b2Vec2 localAxisA_{1.0f, 0.0f};    // frame X in A's Box2D body frame (slider, wheel)
    float referenceAngle_ = 0.0f;      // Box2D angle of B minus A's at creation
    double sign_ = 1.0;                // hinge: frame X . Z; wheel: frame Y . Z (+1 or -1)
    double ballAxisZ_ = 1.0;           // ball: frame X . Z (1 for the layer's planar ball)
    bool explicitSpring_ = false;      // this step the spring's stiffness is applied here, not by Box2D
    double lastHingeImpulse_ = 0.0;    // hinge: the spring's impulse of the last stepped substep (N m s)
    // Sums over the current step's Box2D steps (N s, N m s; B's anchor, world frame).
    struct {
        double x = 0.0, y = 0.0;
    } impulse_;
    double angularImpulse_ = 0.0;
    Vec3 reactionForce_ = Vec3::Zero();
    Vec3 reactionTorque_ = Vec3::Zero();
};

}  // namespace anyphys::box2d
