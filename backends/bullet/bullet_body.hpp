#pragma once
// One body: a btRigidBody, its shapes, and what the layer gave it that Bullet has no place for
// (material index, layer and mask, user forces until the step, the exact kinematic path).
#include <memory>

#include <btBulletDynamicsCommon.h>

#include "anyphys/peers/rebound_from_depth.hpp"
#include "anyphys/peers/world_peer.hpp"
#include "bullet_shapes.hpp"

namespace anyphys::bullet {

class BulletWorld;

/// One shape's surface as the layer resolved it (a compound child's own, else the body's).
struct ChildSurface {
    std::uint32_t material = 0;
    std::uint32_t layer = 1;
    std::uint32_t mask = 0xFFFFFFFFu;
    bool trigger = false;
};

class BulletBodyPeer final : public BodyPeer {
public:
    BulletBodyPeer(BulletWorld& world, const BodyPeerDef& def);
    ~BulletBodyPeer() override;

    // ---- BodyPeer ------------------------------------------------------------------------
    BodyState state() const override;
    void setTransform(const Vec3& position, const Quat& orientation) override;
    void setLinearVelocity(const Vec3& v) override;
    void setAngularVelocity(const Vec3& w) override;
    void addForce(const Vec3& force) override;
    void addTorque(const Vec3& torque) override;
    void holdForStep(const Vec3& force, const Vec3& torque) override;
    void applyLinearImpulse(const Vec3& impulse) override;
    void applyAngularImpulse(const Vec3& impulse) override;
    MassProperties massProperties() const override { return mass_; }
    bool isAwake() const override;
    void setAwake(bool awake) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for the world -------------------------------------------------------------------
    BulletWorld& world() const { return world_; }
    btRigidBody& rigidBody() { return *body_; }
    const btRigidBody& rigidBody() const { return *body_; }
    BodyType type() const { return type_; }
    std::uint64_t userData() const { return userData_; }
    /// The union of its shapes' layers and masks: the broad phase's pre-filter.
    std::uint32_t layer() const { return layer_; }
    std::uint32_t mask() const { return mask_; }
    /// Every shape is a sensor: the whole body has no contact response.
    bool trigger() const { return trigger_; }
    /// Some shape is a sensor.
    bool anyTrigger() const { return anyTrigger_; }
    /// Its compound's children differ in material, filter or sensor flag: contact points are
    /// sorted per child (AnyphysDynamicsWorld::sortChildPoints).
    bool mixedSurfaces() const { return mixed_; }
    /// The surface of the child a contact point names (btManifoldPoint::m_index0 / m_index1 on
    /// this body's side; any index when the body has one surface).
    const ChildSurface& surface(int child) const {
        return mixed_ && child >= 0 && static_cast<std::size_t>(child) < surfaces_.size() ? surfaces_[static_cast<std::size_t>(child)]
                                                                                          : surfaces_.front();
    }
    std::uint32_t material(int child) const { return surface(child).material; }
    /// The child a point without a child index lies on (a continuous-collision contact, which
    /// Bullet makes against the whole compound): the one whose bounds are nearest, a solid child
    /// before a sensor where bounds overlap.
    int childNear(const btVector3& point) const;
    /// Has a compound of solid and sensor children: sweeps see only the solid ones.
    bool hasSolidPart() const { return shapes_->solidPart() != nullptr; }
    /// Gives the body its solid part (on) or its whole shape back (off) around Bullet's sweeps.
    void sweepSolidPartOnly(bool on) { body_->setCollisionShape(on ? shapes_->solidPart() : shapes_->root()); }
    /// Several shapes (a btCompoundShape): one manifold per touching child pair.
    bool compound() const { return compound_; }
    bool hasMesh() const { return shapes_->hasMesh(); }
    /// Its shape is a plane (and not a compound holding one).
    bool isPlane() const { return body_->getCollisionShape()->getShapeType() == STATIC_PLANE_PROXYTYPE; }
    /// See ShapeSet::setReaching; the world turns it on while it holds a mesh.
    void setReaching(bool on) { shapes_->setReaching(on); }
    bool moves() const { return type_ != BodyType::Static; }
    /// A dynamic or kinematic body: MotionLimits::admit on state(), read in place (the basis for the quaternion).
    bool admittedBy(const MotionLimits& limits) const;
    bool dynamic() const { return type_ == BodyType::Dynamic; }
    double linearDamping() const { return linearDamping_; }    // 1/s
    double angularDamping() const { return angularDamping_; }  // 1/s
    /// Dynamic or kinematic and awake: simulated this step.
    bool activeMover() const { return moves() && body_->isActive(); }

    /// Applies the world's effects to this body (gravity, damping, gyroscopic, CCD, sleeping).
    void applyEffects();
    /// How the world applies the layer's gyroscopic term (anyphys/peers/gyroscopic.hpp) to this
    /// body before each Bullet step: its mode if it is dynamic with unequal moments in a 3D world
    /// with the gyroscopic effect, else none.
    GyroscopicMode appliedGyroscopic() const { return appliedGyroscopic_; }
    /// Hands this step's accumulated force and torque to Bullet (again before every substep:
    /// Bullet clears its forces after each stepSimulation).
    void pushForces();
    void clearForces();
    /// Kinematic bodies follow their velocity exactly (double precision, exponential map for
    /// the rotation); Bullet sees the pose and velocity for contacts.
    void advanceKinematic(double h);
    /// Before each Bullet step while something bounces (`notedLastStep`: also before the last one):
    /// notes whether the body fell freely in the last step. A body resting on something does not,
    /// and its gravity does not count in a bounce's relative acceleration
    /// (AnyphysDynamicsWorld::judgeImpact).
    void noteStepStart(bool notedLastStep, const btVector3& velocity, const btVector3& gravity, btScalar h) {
        fall_.note(notedLastStep, velocity, gravity, h, [](const btVector3& x, const btVector3& y) { return x.dot(y); });
    }
    bool fellLastStep() const { return fall_.fellLastStep(); }

private:
    void markForced();
    void wake();
    void syncKinematicToBullet();

    BulletWorld& world_;
    BodyType type_;
    restitution::FreeFallWatch<btVector3> fall_{btVector3(0, 0, 0)};
    std::uint64_t userData_;
    std::vector<ChildSurface> surfaces_;  // per shape, in the compound's child order
    std::uint32_t layer_, mask_;
    bool trigger_, anyTrigger_, mixed_, allowSleep_;
    bool compound_;  // kept here: the contact report asks per manifold, the shape is two loads away
    MassProperties mass_;
    double linearDamping_, angularDamping_, gravityScale_;
    GyroscopicMode gyroscopic_;
    GyroscopicMode appliedGyroscopic_ = GyroscopicMode::None;  // set by applyEffects
    double coreExtent_;

    Vec3 force_ = Vec3::Zero(), torque_ = Vec3::Zero();  // this step, world frame
    bool forced_ = false;                                // listed in the world's forced bodies

    // The values the layer last set, and the floats they became: while Bullet still holds
    // those floats, the doubles are reported (exact round trip).
    Vec3 setPosition_ = Vec3::Zero(), setLinear_ = Vec3::Zero(), setAngular_ = Vec3::Zero();
    Quat setOrientation_ = Quat::Identity();
    btVector3 btPosition_, btLinear_, btAngular_;
    btMatrix3x3 btBasis_;
    // Kinematic bodies: their exact state (Bullet gets a copy).
    BodyState kinematic_;
    bool kinematicAwake_ = true;

    // Declared before the body: destroyed after it.
    std::unique_ptr<ShapeSet> shapes_;
    std::unique_ptr<btRigidBody> body_;
    bool inWorld_ = false;
    friend class BulletWorld;
};

}  // namespace anyphys::bullet
