#include "bullet_body.hpp"

#include <cmath>

#include "anyphys/peers/gyroscopic.hpp"
#include "bullet_convert.hpp"
#include "bullet_world.hpp"

namespace anyphys::bullet {

BulletBodyPeer::BulletBodyPeer(BulletWorld& world, const BodyPeerDef& def)
    : world_(world),
      type_(def.def.type),
      userData_(def.userData),
      layer_(summarize(def.shapes).anyLayer),
      mask_(summarize(def.shapes).anyMask),
      trigger_(summarize(def.shapes).allTriggers),
      anyTrigger_(summarize(def.shapes).anyTrigger),
      mixed_(!summarize(def.shapes).uniform),
      allowSleep_(def.def.allowSleep),
      mass_(def.mass),
      linearDamping_(def.def.linearDamping),
      angularDamping_(def.def.angularDamping),
      gravityScale_(def.def.gravityScale),
      gyroscopic_(def.def.gyroscopic),
      shapes_(std::make_unique<ShapeSet>(def.shapes)) {
    for (const PeerShape& s : def.shapes) surfaces_.push_back({s.material, s.layer, s.mask, s.isTrigger});
    coreExtent_ = shapes_->coreExtent();
    compound_ = shapes_->root()->isCompound();
    const bool dyn = type_ == BodyType::Dynamic;
    const btScalar m = dyn ? static_cast<btScalar>(mass_.mass) : btScalar(0);
    const btVector3 inertia = dyn ? toBt(mass_.inertia) : btVector3(0, 0, 0);
    btRigidBody::btRigidBodyConstructionInfo info(m, nullptr, shapes_->root(), inertia);
    const Quat q = def.def.orientation.normalized();
    info.m_startWorldTransform = toBt(def.def.position, q);
    info.m_friction = 0;     // per contact point from the material table instead
    info.m_restitution = 0;
    info.m_linearSleepingThreshold = static_cast<btScalar>(world.settings().sleepLinearVelocity);
    info.m_angularSleepingThreshold = static_cast<btScalar>(world.settings().sleepAngularVelocity);
    body_ = std::make_unique<btRigidBody>(info);
    body_->setUserPointer(this);
    int flags = body_->getCollisionFlags();
    if (type_ == BodyType::Kinematic) flags = (flags & ~btCollisionObject::CF_STATIC_OBJECT) | btCollisionObject::CF_KINEMATIC_OBJECT;
    if (trigger_) flags |= btCollisionObject::CF_NO_CONTACT_RESPONSE;
    flags |= btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK;  // points take the table's values as they are made
    body_->setCollisionFlags(flags);
    body_->setFlags(BT_DISABLE_WORLD_GRAVITY);  // gravity is per body: world gravity x gravity scale

    setPosition_ = def.def.position;
    setOrientation_ = q;
    btPosition_ = body_->getWorldTransform().getOrigin();
    btBasis_ = body_->getWorldTransform().getBasis();
    if (moves()) {
        setLinear_ = def.def.linearVelocity;
        setAngular_ = def.def.angularVelocity;
    }
    btLinear_ = toBt(setLinear_);
    btAngular_ = toBt(setAngular_);
    body_->setLinearVelocity(btLinear_);
    body_->setAngularVelocity(btAngular_);
    kinematic_ = {setPosition_, setOrientation_, setLinear_, setAngular_};
    // A planar world: Bullet's linear and angular factors hold the body in the XY plane, turning
    // about Z (they mask every velocity change, contacts' included).
    if (dyn && world.settings().planar) {
        body_->setLinearFactor(btVector3(1, 1, 0));
        body_->setAngularFactor(btVector3(0, 0, 1));
    }
    // Kinematic bodies are moved by anyphys and never put to sleep by Bullet.
    if (type_ == BodyType::Kinematic || (dyn && !allowSleep_)) body_->forceActivationState(DISABLE_DEACTIVATION);
}

int BulletBodyPeer::childNear(const btVector3& point) const {
    if (!shapes_->root()->isCompound()) return 0;
    const auto* compound = static_cast<const btCompoundShape*>(shapes_->root());
    int best = 0;
    btScalar bestDistance = BT_LARGE_FLOAT;
    bool bestSensor = true;
    for (int i = 0; i < compound->getNumChildShapes(); ++i) {
        btVector3 lo, hi;
        compound->getChildShape(i)->getAabb(body_->getWorldTransform() * compound->getChildTransform(i), lo, hi);
        btVector3 gap(0, 0, 0);
        for (int k = 0; k < 3; ++k) gap[k] = std::max({btScalar(0), lo[k] - point[k], point[k] - hi[k]});
        const btScalar distance = gap.length();
        const bool sensor = surface(i).trigger;
        if (distance < bestDistance || (distance == bestDistance && bestSensor && !sensor)) {
            best = i;
            bestDistance = distance;
            bestSensor = sensor;
        }
    }
    return best;
}

BulletBodyPeer::~BulletBodyPeer() {
    if (inWorld_) world_.detach(*this);
}

void BulletBodyPeer::applyEffects() {
    if (!dynamic()) return;
    const Effects e = world_.effects();
    const Vec3 g = e.has(Effect::Gravity) ? Vec3(gravityScale_ * world_.settings().gravity) : Vec3(Vec3::Zero());
    body_->setGravity(toBt(g));
    body_->setDamping(0, 0);  // the world applies the exact decay: AnyphysDynamicsWorld::predictUnconstraintMotion
    // Not Bullet's own gyroscopic flags: its implicit mode (one Newton step of backward Euler)
    // lands on the wrong root when a step turns the body far (the energy of a body spun at
    // 27 rad/s grew 12-fold in 10 s at 60 Hz), and both modes expand w x (I w), which on moments
    // 22 orders apart leaves rounding larger than the term (tests/contract/test_rotation.cpp).
    // The world applies the layer's terms instead (AnyphysDynamicsWorld::predictUnconstraintMotion).
    body_->setFlags(BT_DISABLE_WORLD_GRAVITY);
    // In a plane the gyroscopic term w x Iw has no part about Z: the plane absorbs it.
    const bool gyroscopic = e.has(Effect::Gyroscopic) && !world_.settings().planar && gyroscopic::isAnisotropic(mass_.inertia);
    appliedGyroscopic_ = gyroscopic ? gyroscopic_ : GyroscopicMode::None;
    if (e.has(Effect::ContinuousCollision) && std::isfinite(coreExtent_) && !trigger_) {
        // Moving more than half its inner radius in a step may tunnel: sweep a sphere a little
        // smaller than the body's core along the motion (Bullet's CCD and predictive contacts).
        body_->setCcdMotionThreshold(static_cast<btScalar>(0.5 * coreExtent_));
        body_->setCcdSweptSphereRadius(static_cast<btScalar>(0.9 * coreExtent_));
    } else {
        body_->setCcdMotionThreshold(0);
        body_->setCcdSweptSphereRadius(0);
    }
}

BodyState BulletBodyPeer::state() const {
    if (type_ == BodyType::Kinematic) return kinematic_;
    if (type_ == BodyType::Static) return {setPosition_, setOrientation_, Vec3::Zero(), Vec3::Zero()};
    const btTransform& xf = body_->getWorldTransform();
    BodyState s;
    s.position = sameBt(xf.getOrigin(), btPosition_) ? setPosition_ : fromBt(xf.getOrigin());
    if (xf.getBasis() == btBasis_) {
        s.orientation = setOrientation_;
    } else {
        btQuaternion q;
        xf.getBasis().getRotation(q);
        s.orientation = fromBt(q).normalized();
    }
    const btVector3& v = body_->getLinearVelocity();
    const btVector3& w = body_->getAngularVelocity();
    s.linearVelocity = sameBt(v, btLinear_) ? setLinear_ : fromBt(v);
    s.angularVelocity = sameBt(w, btAngular_) ? setAngular_ : fromBt(w);
    return s;
}

bool BulletBodyPeer::admittedBy(const MotionLimits& limits) const {
    if (type_ == BodyType::Kinematic) return limits.admit(kinematic_);
    const btTransform& xf = body_->getWorldTransform();
    const btMatrix3x3& basis = xf.getBasis();
    double basisSum = 0.0;  // finite exactly when the rotation state() builds from it is
    for (int r = 0; r < 3; ++r) basisSum += static_cast<double>(basis[r].x() + basis[r].y() + basis[r].z());
    const btVector3& v = body_->getLinearVelocity();
    const btVector3& w = body_->getAngularVelocity();
    return limits.admit(sameBt(xf.getOrigin(), btPosition_) ? setPosition_ : fromBt(xf.getOrigin()), basisSum,
                        sameBt(v, btLinear_) ? setLinear_ : fromBt(v), sameBt(w, btAngular_) ? setAngular_ : fromBt(w));
}

void BulletBodyPeer::setTransform(const Vec3& position, const Quat& orientation) {
    setPosition_ = position;
    setOrientation_ = orientation.normalized();
    kinematic_.position = setPosition_;
    kinematic_.orientation = setOrientation_;
    const btTransform xf = toBt(setPosition_, setOrientation_);
    body_->setWorldTransform(xf);
    body_->setInterpolationWorldTransform(xf);
    btPosition_ = xf.getOrigin();
    btBasis_ = xf.getBasis();
    if (moves()) wake();
    world_.teleported(*this);
}

void BulletBodyPeer::setLinearVelocity(const Vec3& v) {
    if (!moves()) return;
    setLinear_ = kinematic_.linearVelocity = v;
    btLinear_ = toBt(v);
    body_->setLinearVelocity(btLinear_);
    body_->setInterpolationLinearVelocity(btLinear_);
    wake();
}

void BulletBodyPeer::setAngularVelocity(const Vec3& w) {
    if (!moves()) return;
    setAngular_ = kinematic_.angularVelocity = w;
    btAngular_ = toBt(w);
    body_->setAngularVelocity(btAngular_);
    body_->setInterpolationAngularVelocity(btAngular_);
    wake();
}

void BulletBodyPeer::addForce(const Vec3& force) {
    if (!dynamic()) return;
    force_ += force;
    markForced();
    wake();
}

void BulletBodyPeer::addTorque(const Vec3& torque) {
    if (!dynamic()) return;
    torque_ += torque;
    markForced();
    wake();
}

// The layer's step forces join addForce's in the same accumulator, pushed to Bullet before every
// substep (Bullet clears its forces after each stepSimulation); no wake-up.
void BulletBodyPeer::holdForStep(const Vec3& force, const Vec3& torque) {
    if (!dynamic()) return;
    force_ += force;
    torque_ += torque;
    markForced();
}

// Impulses are added in double to the reported velocity, so that exact values stay exact.
void BulletBodyPeer::applyLinearImpulse(const Vec3& impulse) {
    if (!dynamic()) return;
    setLinearVelocity(state().linearVelocity + impulse / mass_.mass);
}

void BulletBodyPeer::applyAngularImpulse(const Vec3& impulse) {
    if (!dynamic()) return;
    const BodyState s = state();
    const Mat3 r = s.orientation.toRotationMatrix();
    setAngularVelocity(s.angularVelocity + r * mass_.inertia.cwiseInverse().cwiseProduct(r.transpose() * impulse));
}

bool BulletBodyPeer::isAwake() const {
    switch (type_) {
        case BodyType::Static: return false;
        case BodyType::Kinematic: return kinematicAwake_;
        case BodyType::Dynamic: return body_->getActivationState() != ISLAND_SLEEPING;
    }
    return false;
}

void BulletBodyPeer::setAwake(bool awake) {
    if (!moves()) return;
    if (awake) {
        wake();
        return;
    }
    kinematicAwake_ = false;
    setLinear_ = setAngular_ = kinematic_.linearVelocity = kinematic_.angularVelocity = Vec3::Zero();
    btLinear_ = btAngular_ = btVector3(0, 0, 0);
    body_->setLinearVelocity(btLinear_);
    body_->setAngularVelocity(btAngular_);
    force_.setZero();
    torque_.setZero();
    body_->forceActivationState(ISLAND_SLEEPING);
}

void BulletBodyPeer::wake() {
    if (type_ == BodyType::Kinematic) {
        kinematicAwake_ = true;
        body_->forceActivationState(DISABLE_DEACTIVATION);
    } else if (!allowSleep_) {
        body_->forceActivationState(DISABLE_DEACTIVATION);
    } else {
        if (body_->getActivationState() == DISABLE_DEACTIVATION) body_->forceActivationState(ACTIVE_TAG);
        body_->activate(true);  // also restarts its rest time
    }
}

void* BulletBodyPeer::nativeObject(const std::type_info& pointerType) {
    if (pointerType == typeid(btRigidBody*)) return body_.get();
    if (pointerType == typeid(btCollisionObject*)) return static_cast<btCollisionObject*>(body_.get());
    return nullptr;
}

void BulletBodyPeer::markForced() {
    if (forced_) return;
    forced_ = true;
    world_.addForced(this);
}

void BulletBodyPeer::pushForces() {
    body_->applyCentralForce(toBt(force_));
    body_->applyTorque(toBt(torque_));
}

void BulletBodyPeer::clearForces() {
    force_.setZero();
    torque_.setZero();
    forced_ = false;
}

void BulletBodyPeer::advanceKinematic(double h) {
    if (!kinematicAwake_) return;
    kinematic_.position += h * kinematic_.linearVelocity;
    const double speed = kinematic_.angularVelocity.norm();
    if (speed > 0)
        kinematic_.orientation =
            (Quat(Eigen::AngleAxisd(speed * h, kinematic_.angularVelocity / speed)) * kinematic_.orientation).normalized();
    const btTransform xf = toBt(kinematic_.position, kinematic_.orientation);
    body_->setWorldTransform(xf);
    body_->setInterpolationWorldTransform(xf);
}

}  // namespace anyphys::bullet
