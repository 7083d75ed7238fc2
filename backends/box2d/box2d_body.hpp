#pragma once
// The Box2D backend's body peer: one b2Body, its fixtures' extra data, and what the layer asked
// for that Box2D keeps differently (damping rate, pending forces, filter layers, material).
#include <box2d/box2d.h>

#include <memory>
#include <vector>

#include "anyphys/peers/body_peer.hpp"
#include "anyphys/peers/rebound_from_depth.hpp"
#include "anyphys/peers/world_peer.hpp"
#include "box2d_convert.hpp"
#include "box2d_shapes.hpp"

namespace anyphys::box2d {

class Box2dWorld;
class Box2dBody;

/// Reached from a fixture's user data: which body it belongs to and its exact geometry.
struct FixtureInfo {
    Box2dBody* body = nullptr;
    Piece piece;
    // The surface of the shape the fixture came from (a compound child's own, else the body's);
    // the sensor flag is the fixture's own (b2Fixture::IsSensor).
    std::uint32_t material = 0;
    std::uint32_t layer = 1;
    std::uint32_t mask = 0xFFFFFFFFu;
    std::uint32_t shape = 0;  // which of the body's shapes (BodyPeerDef::shapes) the piece is of
};

/// The info every fixture of this backend carries in its user data.
inline const FixtureInfo& fixtureInfo(const b2Fixture* fixture) {
    return *reinterpret_cast<const FixtureInfo*>(const_cast<b2Fixture*>(fixture)->GetUserData().pointer);
}

/// The layer's key, which rides on the b2Body (Box2D 2.4.1 has no const GetUserData).
inline std::uint64_t bodyKey(const b2Body* body) {
    return static_cast<std::uint64_t>(const_cast<b2Body*>(body)->GetUserData().pointer);
}

class Box2dBody final : public BodyPeer {
public:
    Box2dBody(Box2dWorld& world, b2Body* body, const BodyPeerDef& def, const Embedding& embedding);
    /// Destroys the b2Body too if the world still has it (a peer dropped without destroyBody).
    ~Box2dBody() override;
    Box2dBody(const Box2dBody&) = delete;
    Box2dBody& operator=(const Box2dBody&) = delete;

    BodyState state() const override;
    void setTransform(const Vec3& position, const Quat& orientation) override;
    void setLinearVelocity(const Vec3& v) override;
    void setAngularVelocity(const Vec3& w) override;
    void addForce(const Vec3& force) override;
    void addTorque(const Vec3& torque) override;
    void holdForStep(const Vec3& force, const Vec3& torque) override;
    void applyLinearImpulse(const Vec3& impulse) override;
    void applyAngularImpulse(const Vec3& impulse) override;
    MassProperties massProperties() const override;
    bool isAwake() const override;
    void setAwake(bool awake) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for the world ----------------------------------------------------------------
    b2Body* b2() const { return body_; }
    /// The world let go of the b2Body (destroyed it, or is itself going away).
    void detach() { world_ = nullptr; body_ = nullptr; }
    void addFixture(std::unique_ptr<FixtureInfo> info) { fixtures_.push_back(std::move(info)); }
    const std::vector<std::unique_ptr<FixtureInfo>>& fixtures() const { return fixtures_; }

    /// How the peer frame sits on the b2Body (joint frames are given in the peer frame).
    const Embedding& embedding() const { return embedding_; }
    std::uint64_t userData() const { return userData_; }
    bool isDynamic() const { return body_->GetType() == b2_dynamicBody; }

    /// Box2D damps v *= 1 / (1 + h c') per step; c' = (e^{c h} - 1) / h makes that e^{-c h},
    /// the exact decay of dv/dt = -c v over a step of h. Zero when damping is off.
    void applyDamping(bool on, double h);
    /// Pending forces and torques (world frame, in the plane): addForce's, then the layer's step
    /// forces (holdForStep), onto the b2Body at the step's start if it is awake and `apply`
    /// (the world keeps them there over every substep: SetAutoClearForces(false)).
    void flushForces(bool apply);
    /// What flushForces put on the b2Body for this step (N, N m; zero if nothing): Box2D keeps a
    /// body's pending force private, and a joint predicting the substep's velocities needs it.
    b2Vec2 stepForce() const { return stepForce_; }
    float stepTorque() const { return stepTorque_; }
    /// Marks the body a Box2D bullet (time of impact against other moving bodies too) when this
    /// step would carry it more than half its smallest inner radius.
    void updateBullet(bool continuous, double h);
    void setInnerRadius(double r) { innerRadius_ = r; }
    /// Velocity and position at the start of the current Box2D step (of `h`, under the world's
    /// `gravity`; `notedLastStep`: also marked at the last one): an unchanged velocity means its solve has not run yet; the position, how far
    /// time of impact let it travel. And whether it fell freely in the last step: a body resting on
    /// something does not, and its gravity does not count in a bounce's relative acceleration
    /// (ContactRules).
    void markStepStart(bool notedLastStep, const b2Vec2& gravity, float h) {
        const b2Vec2 fall = body_->GetType() == b2_dynamicBody ? body_->GetGravityScale() * gravity : b2Vec2(0.0f, 0.0f);
        fall_.note(notedLastStep, body_->GetLinearVelocity(), fall, h, [](const b2Vec2& x, const b2Vec2& y) { return b2Dot(x, y); });
        stepStartPosition_ = body_->GetPosition();
    }
    bool fellLastStep() const { return fall_.fellLastStep(); }
    bool movedSinceStepStart() const { return !(body_->GetLinearVelocity() == fall_.stepStartVelocity()); }
    b2Vec2 travelSinceStepStart() const { return body_->GetPosition() - stepStartPosition_; }
    /// Index in the world's body list (kept by the world).
    std::size_t slot = 0;

private:
    Box2dWorld* world_;
    b2Body* body_;
    Embedding embedding_;
    MassProperties mass_;
    std::vector<std::unique_ptr<FixtureInfo>> fixtures_;
    std::uint64_t userData_;
    double linearDamping_;   // 1/s, the layer's rate (dv/dt = -c v)
    double angularDamping_;  // 1/s
    double innerRadius_ = 0.0;
    b2Vec2 force_{0.0f, 0.0f};
    float torque_ = 0.0f;
    b2Vec2 heldForce_{0.0f, 0.0f};  // holdForStep's, kept apart so Box2D adds it after force_
    float heldTorque_ = 0.0f;
    b2Vec2 stepForce_{0.0f, 0.0f};  // flushForces' sums on the b2Body this step
    float stepTorque_ = 0.0f;
    restitution::FreeFallWatch<b2Vec2> fall_{b2Vec2(0.0f, 0.0f)};
    b2Vec2 stepStartPosition_{0.0f, 0.0f};
};

// Inline: the world runs both for every body every step.
inline void Box2dBody::flushForces(bool apply) {
    stepForce_.SetZero();
    stepTorque_ = 0.0f;
    if (apply && body_->IsAwake()) {
        stepForce_ = force_ + heldForce_;
        stepTorque_ = torque_ + heldTorque_;
        // addForce's first, then the step forces: the order Box2D summed them in when this
        // backend ran the force hook itself.
        if (force_.x != 0.0f || force_.y != 0.0f) body_->ApplyForceToCenter(force_, false);
        if (torque_ != 0.0f) body_->ApplyTorque(torque_, false);
        if (heldForce_.x != 0.0f || heldForce_.y != 0.0f) body_->ApplyForceToCenter(heldForce_, false);
        if (heldTorque_ != 0.0f) body_->ApplyTorque(heldTorque_, false);
    }
    force_.SetZero();
    torque_ = 0.0f;
    heldForce_.SetZero();
    heldTorque_ = 0.0f;
}

inline void Box2dBody::updateBullet(bool continuous, double h) {
    if (!isDynamic()) return;
    if (!body_->IsAwake()) {  // at rest (Box2D zeroes a sleeping body's velocity): not fast
        if (body_->IsBullet()) body_->SetBullet(false);
        return;
    }
    const double travel2 = static_cast<double>(body_->GetLinearVelocity().LengthSquared()) * h * h;
    // Not a body held by joints: Box2D's time-of-impact solve moves bullets without their joints,
    // which tore a falling ragdoll's limbs 87 cm from their sockets. Such a body keeps Box2D's
    // own time of impact against static geometry.
    const bool fast = continuous && travel2 > 0.25 * innerRadius_ * innerRadius_ && body_->GetJointList() == nullptr;
    if (fast != body_->IsBullet()) body_->SetBullet(fast);
}

}  // namespace anyphys::box2d
