#pragma once
// One anyphys body over ODE: a dBody (dynamic and kinematic bodies; static bodies have none)
// and its geoms. The body frame is the layer's peer frame (centre of mass, principal axes), so
// ODE's own body frame is used as is.
#include <ode/ode.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "anyphys/peers/rebound_from_depth.hpp"
#include "anyphys/peers/world_peer.hpp"
#include "anyphys/world_settings.hpp"
#include "ode_shapes.hpp"

namespace anyphys::ode {

class OdeWorld;

class OdeBody final : public BodyPeer {
public:
    OdeBody(OdeWorld& world, const BodyPeerDef& def);
    ~OdeBody() override;
    OdeBody(const OdeBody&) = delete;
    OdeBody& operator=(const OdeBody&) = delete;

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

    // ---- for the world ------------------------------------------------------------------
    dBodyID id() const { return body_; }
    BodyType type() const { return type_; }
    bool isDynamic() const { return type_ == BodyType::Dynamic; }
    bool moves() const { return type_ != BodyType::Static; }
    /// Simulated now: moving and enabled (not asleep).
    bool isActive() const { return body_ && dBodyIsEnabled(body_); }
    /// Planar worlds: removes the drift the plane-2D joint leaves (z, z speed, off-axis spin).
    void projectToPlane() const;
    std::uint64_t userData() const { return userData_; }
    /// The union of its geoms' layers and masks (a pre-filter: a pair may touch only if these do).
    std::uint32_t layer() const { return layer_; }
    std::uint32_t mask() const { return mask_; }
    /// Every geom is a sensor: the body never responds to contact.
    bool isTrigger() const { return trigger_; }
    double gravityScale() const { return gravityScale_; }
    double mass() const { return mass_.mass; }
    double coreExtent() const { return coreExtent_; }
    /// 1/kg: an upper bound on the weight J M^-1 J^T of any unit constraint row acting on this
    /// body at a point of its shapes; 0 for static and kinematic bodies (conditionedCfm).
    double rowWeightBound() const { return rowWeightBound_; }
    std::size_t shapeCount() const { return shapes_.size(); }
    const OdeShape& shape(std::size_t i) const { return *shapes_[i]; }

    /// Applies the world's effects to this body: damping (as ODE's per-step scale for steps of
    /// `h` seconds), gyroscopic mode and auto-disable.
    void applyEffects(Effects effects, double h);
    /// Has the implicit gyroscopic term applied by the world (dynamic, anisotropic, implicit mode).
    bool needsGyroscopic(Effects effects) const;
    /// The gyroscopic term over an ODE step of h seconds (before ODE's step, which has it off).
    void applyGyroscopic(double h) const;
    /// Hands the held forces to ODE for one ODE step (ODE clears its accumulators after each).
    void feedForces() const;
    void clearForces();
    /// Index in the world's body list (kept by the world).
    std::size_t slot = 0;
    /// Order among the awake bodies in the world's current collide pass (kept by the world).
    std::size_t awakeRank = 0;
    /// isActive() when the world's current collide pass began: the pass asks it of every
    /// candidate pair, and nothing wakes or sleeps until the ODE step.
    bool activeInPass = false;
    /// Asleep at the pass's start and touched by an awake body in it: queued to have its own pairs
    /// collided in the same pass (OdeWorld::collideWokenBodies).
    bool wokenInPass = false;
    /// Queued in the world's list of bodies with forces this step.
    bool forceQueued = false;
    /// Whether it fell freely in the last ODE step: only then does its gravity count in a bounce's
    /// relative acceleration (OdeWorld::aimBounce). A body resting on something does not fall.
    /// Noted by the world's collide pass while some material bounces.
    restitution::FreeFallWatch<Vec3> fall{Vec3::Zero()};

private:
    void wake();
    double largestRowWeight() const;  // rowWeightBound_ of a dynamic body

    OdeWorld& world_;
    dBodyID body_ = nullptr;
    dJointID planeJoint_ = nullptr;  // planar worlds only
    Quat planeTilt_ = Quat::Identity();  // planar: orientation = (turn about Z) x planeTilt_
    double planeZ_ = 0.0;                // planar: the centre of mass's constant z
    BodyType type_;
    std::vector<std::unique_ptr<OdeShape>> shapes_;
    Transform staticPose_;  // static bodies: their frame's pose (they have no dBody)
    MassProperties mass_;
    std::uint64_t userData_;
    std::uint32_t layer_, mask_;
    bool trigger_;
    bool allowSleep_;
    double gravityScale_;
    double linearDamping_, angularDamping_;  // 1/s
    GyroscopicMode gyroscopic_;
    double coreExtent_ = 0.0;
    double rowWeightBound_ = 0.0;
    Vec3 force_ = Vec3::Zero(), torque_ = Vec3::Zero();          // user, this step
    Vec3 heldForce_ = Vec3::Zero(), heldTorque_ = Vec3::Zero();  // the layer's step forces (holdForStep), this step
};

/// kg: the mass of the heavier dynamic body of a pair (the mass kCfmReferenceMass compares); a
/// body that is null, static or kinematic counts as none.
inline double heavierDynamicMass(const OdeBody* a, const OdeBody* b) {
    const auto massOf = [](const OdeBody* body) { return body && body->isDynamic() ? body->mass() : 0.0; };
    return std::max(massOf(a), massOf(b));
}

}  // namespace anyphys::ode
