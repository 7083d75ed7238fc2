#include "ode_body.hpp"

#include <cmath>
#include <limits>

#include "anyphys/peers/gyroscopic.hpp"
#include "ode_math.hpp"
#include "ode_world.hpp"

namespace anyphys::ode {

OdeBody::OdeBody(OdeWorld& world, const BodyPeerDef& peerDef)
    : world_(world), type_(peerDef.def.type), mass_(peerDef.mass), userData_(peerDef.userData),
      layer_(summarize(peerDef.shapes).anyLayer), mask_(summarize(peerDef.shapes).anyMask),
      trigger_(summarize(peerDef.shapes).allTriggers),
      allowSleep_(peerDef.def.allowSleep), gravityScale_(peerDef.def.gravityScale),
      linearDamping_(peerDef.def.linearDamping), angularDamping_(peerDef.def.angularDamping),
      gyroscopic_(peerDef.def.gyroscopic) {
    const BodyDef& def = peerDef.def;
    staticPose_ = {def.position, def.orientation.normalized()};
    if (type_ != BodyType::Static) {
        body_ = dBodyCreate(world.id());
        dBodySetData(body_, this);
        dBodySetPosition(body_, def.position.x(), def.position.y(), def.position.z());
        dQuaternion q;
        toOde(staticPose_.orientation, q);
        dBodySetQuaternion(body_, q);
        dBodySetLinearVel(body_, def.linearVelocity.x(), def.linearVelocity.y(), def.linearVelocity.z());
        dBodySetAngularVel(body_, def.angularVelocity.x(), def.angularVelocity.y(), def.angularVelocity.z());
        // Exact rotation by w h each step (ODE's finite rotation mode) instead of the first-order
        // quaternion update: kinematic bodies then turn exactly as set.
        dBodySetFiniteRotationMode(body_, 1);
        if (type_ == BodyType::Kinematic) {
            dBodySetKinematic(body_);
        } else {
            dMass m;
            // The peer frame is the centre of mass with principal axes: diagonal inertia, no offset.
            dMassSetParameters(&m, mass_.mass, 0, 0, 0, mass_.inertia.x(), mass_.inertia.y(), mass_.inertia.z(), 0, 0, 0);
            dBodySetMass(body_, &m);
            if (gravityScale_ == 0.0) dBodySetGravityMode(body_, 0);
            // A planar world: ODE's plane-2D joint keeps the body in z = 0, turning about Z.
            if (world.settings().planar) {
                planeJoint_ = dJointCreatePlane2D(world.id(), nullptr);
                dJointAttach(planeJoint_, body_, nullptr);
                planeTilt_ = staticPose_.orientation;
                planeZ_ = def.position.z();  // the centre of mass may sit off z = 0 (a hull uneven in z)
            }
        }
    }
    coreExtent_ = std::numeric_limits<double>::infinity();
    for (const PeerShape& ps : peerDef.shapes) {
        auto shape = std::make_unique<OdeShape>(ps, world.space());
        shape->setOwner(this);
        // ODE's broad phase pre-filter: it pairs geoms when either's category meets the other's
        // collide bits, weaker than layersCollide (both ways), which the near callback applies.
        dGeomSetCategoryBits(shape->geom(), ps.layer);
        dGeomSetCollideBits(shape->geom(), ps.mask);
        if (body_)
            shape->attach(body_);
        else
            shape->place(staticPose_);
        coreExtent_ = std::min(coreExtent_, shape->coreExtent());
        shapes_.push_back(std::move(shape));
    }
    if (type_ == BodyType::Dynamic) rowWeightBound_ = largestRowWeight();
    if (body_ && !def.isAwake) dBodyDisable(body_);
}

double OdeBody::largestRowWeight() const {
    // A unit row acting at r from the centre of mass weighs 1/m + |r x d|^2 / I along d, at most
    // 1/m + |r|^2 / I_min; r is bounded by the farthest corner of the geoms' bounding boxes.
    const Vec3 centre = toVec3(dBodyGetPosition(body_));
    double reach2 = 0.0;
    for (const auto& shape : shapes_) {
        dReal box[6];
        dGeomGetAABB(shape->geom(), box);
        const Vec3 far(std::max(std::abs(box[0] - centre.x()), std::abs(box[1] - centre.x())),
                       std::max(std::abs(box[2] - centre.y()), std::abs(box[3] - centre.y())),
                       std::max(std::abs(box[4] - centre.z()), std::abs(box[5] - centre.z())));
        reach2 = std::max(reach2, far.squaredNorm());
    }
    return 1.0 / mass_.mass + reach2 / mass_.inertia.minCoeff();
}

OdeBody::~OdeBody() {
    shapes_.clear();  // geoms first: they refer to the body
    if (planeJoint_) dJointDestroy(planeJoint_);
    if (body_) dBodyDestroy(body_);
}

void OdeBody::projectToPlane() const {
    // The plane-2D joint removes out-of-plane velocity within the step, but not the drift its
    // linearised constraint leaves (as ODE's own plane-2D demo notes): put z back where it
    // started, and its speed and the off-axis spin back to exactly zero.
    // The orientation is a turn about Z of the one it was created with (planeTilt_, which holds
    // the principal axes' fixed tilt): keep the twist about Z of the drifted turn, drop the rest.
    if (!planeJoint_ || !dBodyIsEnabled(body_)) return;
    const dReal* p = dBodyGetPosition(body_);
    const dReal* v = dBodyGetLinearVel(body_);
    const dReal* w = dBodyGetAngularVel(body_);
    dBodySetPosition(body_, p[0], p[1], planeZ_);
    dBodySetLinearVel(body_, v[0], v[1], 0.0);
    dBodySetAngularVel(body_, 0.0, 0.0, w[2]);
    const Quat turn = toQuat(dBodyGetQuaternion(body_)) * planeTilt_.conjugate();
    const double angle = 2.0 * std::atan2(turn.z(), turn.w());
    dQuaternion q;
    toOde((Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())) * planeTilt_).normalized(), q);
    dBodySetQuaternion(body_, q);
}

BodyState OdeBody::state() const {
    if (!body_) return {staticPose_.position, staticPose_.orientation, Vec3::Zero(), Vec3::Zero()};
    return {toVec3(dBodyGetPosition(body_)), toQuat(dBodyGetQuaternion(body_)), toVec3(dBodyGetLinearVel(body_)),
            toVec3(dBodyGetAngularVel(body_))};
}

void OdeBody::wake() {
    if (body_) dBodyEnable(body_);  // also restarts ODE's idle countdown
}

void OdeBody::setTransform(const Vec3& position, const Quat& orientation) {
    if (!body_) {
        staticPose_ = {position, orientation.normalized()};
        for (auto& shape : shapes_) shape->place(staticPose_);
        world_.wakeTouching(*this);  // bodies resting on it must react
        return;
    }
    dBodySetPosition(body_, position.x(), position.y(), position.z());
    dQuaternion q;
    toOde(orientation.normalized(), q);
    dBodySetQuaternion(body_, q);
    wake();
}

void OdeBody::setLinearVelocity(const Vec3& v) {
    if (!body_) return;
    dBodySetLinearVel(body_, v.x(), v.y(), v.z());
    wake();
}

void OdeBody::setAngularVelocity(const Vec3& w) {
    if (!body_) return;
    dBodySetAngularVel(body_, w.x(), w.y(), w.z());
    wake();
}

void OdeBody::addForce(const Vec3& force) {
    if (!isDynamic()) return;
    force_ += force;
    world_.queueForces(*this);
    wake();
}

void OdeBody::addTorque(const Vec3& torque) {
    if (!isDynamic()) return;
    torque_ += torque;
    world_.queueForces(*this);
    wake();
}

// Held apart from addForce's: every substep ODE gets force_ + heldForce_, the sum it got when
// this backend ran the force hook itself.
void OdeBody::holdForStep(const Vec3& force, const Vec3& torque) {
    if (!isDynamic()) return;
    heldForce_ += force;
    heldTorque_ += torque;
    world_.queueForces(*this);
}

void OdeBody::applyLinearImpulse(const Vec3& impulse) {
    if (!isDynamic()) return;
    const Vec3 v = toVec3(dBodyGetLinearVel(body_)) + impulse / mass_.mass;
    dBodySetLinearVel(body_, v.x(), v.y(), v.z());
    wake();
}

void OdeBody::applyAngularImpulse(const Vec3& impulse) {
    if (!isDynamic()) return;
    const Mat3 r = toQuat(dBodyGetQuaternion(body_)).toRotationMatrix();
    const Vec3 w = toVec3(dBodyGetAngularVel(body_)) + r * mass_.inertia.cwiseInverse().cwiseProduct(r.transpose() * impulse);
    dBodySetAngularVel(body_, w.x(), w.y(), w.z());
    wake();
}

MassProperties OdeBody::massProperties() const {
    MassProperties m;
    if (isDynamic()) {
        m.mass = mass_.mass;
        m.inertia = mass_.inertia;
    }
    return m;
}

bool OdeBody::isAwake() const { return isActive(); }

void OdeBody::setAwake(bool awake) {
    if (!body_) return;
    if (awake) {
        wake();
        return;
    }
    // As ODE's own auto-disable does: a body put to sleep stops, so it wakes at rest.
    dBodySetLinearVel(body_, 0, 0, 0);
    dBodySetAngularVel(body_, 0, 0, 0);
    dBodyDisable(body_);
}

void* OdeBody::nativeObject(const std::type_info& pointerType) {
    if (pointerType == typeid(dxBody*)) return body_;
    if (pointerType == typeid(dxGeom*)) return shapes_.empty() ? nullptr : shapes_.front()->geom();
    return nullptr;
}

void OdeBody::applyEffects(Effects effects, double h) {
    if (!isDynamic()) return;
    // Damping: the layer's dv/dt = -c v over a step of h is exactly v *= exp(-c h); ODE scales
    // velocities by (1 - scale) at the end of each step, so scale = 1 - exp(-c h). Thresholds
    // 0: ODE would otherwise leave slow bodies undamped.
    const bool damping = effects.has(Effect::Damping) && (linearDamping_ > 0 || angularDamping_ > 0);
    if (damping) {
        dBodySetDamping(body_, -std::expm1(-linearDamping_ * h), -std::expm1(-angularDamping_ * h));
        dBodySetLinearDampingThreshold(body_, 0.0);
        dBodySetAngularDampingThreshold(body_, 0.0);
    } else {
        dBodySetDamping(body_, 0.0, 0.0);
    }
    // Gyroscopic: ODE's own term is always off; the world applies the layer's implicit form
    // (anyphys/peers/gyroscopic.hpp) to bodies that need it.
    dBodySetGyroscopicMode(body_, 0);
    // Sleeping: ODE's auto-disable, with the thresholds the world set as ODE's defaults. Turning
    // it off also enables the body in ODE: a body asleep (e.g. created asleep) stays asleep.
    const bool asleep = !dBodyIsEnabled(body_);
    dBodySetAutoDisableFlag(body_, effects.has(Effect::Sleeping) && allowSleep_ ? 1 : 0);
    if (asleep) dBodyDisable(body_);
}

bool OdeBody::needsGyroscopic(Effects effects) const {
    // In a plane the gyroscopic term w x Iw has no part about Z: the plane absorbs it.
    return isDynamic() && !planeJoint_ && effects.has(Effect::Gyroscopic) && gyroscopic_ == GyroscopicMode::Implicit &&
           gyroscopic::isAnisotropic(mass_.inertia);
}

void OdeBody::applyGyroscopic(double h) const {
    const Vec3 w = gyroscopic::solveImplicit(toVec3(dBodyGetAngularVel(body_)), toQuat(dBodyGetQuaternion(body_)),
                                           mass_.inertia, h);
    dBodySetAngularVel(body_, w.x(), w.y(), w.z());
}

void OdeBody::feedForces() const {
    const Vec3 f = force_ + heldForce_, t = torque_ + heldTorque_;
    dBodyAddForce(body_, f.x(), f.y(), f.z());
    dBodyAddTorque(body_, t.x(), t.y(), t.z());
}

void OdeBody::clearForces() {
    force_ = torque_ = heldForce_ = heldTorque_ = Vec3::Zero();
    forceQueued = false;
}

}  // namespace anyphys::ode
