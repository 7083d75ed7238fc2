// Body handle methods: validate, then forward to the body's peer.
#include "anyphys/body.hpp"

#include "anyphys/validation.hpp"
#include "handle_link.hpp"
#include "world_impl.hpp"

namespace anyphys {
namespace {

World& worldOf(const std::shared_ptr<detail::WorldLink>& link, BodyId id, const char* operation) {
    return detail::linkedWorld(link, id, "body", operation);
}

// A planar world keeps motion in the XY plane: pushes out of it are dropped (the plane holds the
// body, as a table holds a puck), and velocities or poses out of it are refused.
Vec3 inPlane(const World* world, Vec3 linear) {
    if (world->settings().planar) linear.z() = 0.0;
    return linear;
}
Vec3 aboutZ(const World* world, Vec3 angular) {
    if (world->settings().planar) angular.x() = angular.y() = 0.0;
    return angular;
}
void requireInPlane(const World* world, const char* field, const Vec3& linear) {
    if (world->settings().planar && std::abs(linear.z()) > detail::kPlanarTolerance)
        throw Error::invalid(field, formatVec3(linear), "must have z = 0 in a planar world");
}
void requireAboutZ(const World* world, const char* field, const Vec3& angular) {
    if (world->settings().planar &&
        (std::abs(angular.x()) > detail::kPlanarTolerance || std::abs(angular.y()) > detail::kPlanarTolerance))
        throw Error::invalid(field, formatVec3(angular), "must be about Z only (x = y = 0) in a planar world");
}

// A force whose one step (settings().timeStep) changes a dynamic body's speed by more than
// maxSpeed is an absurd input, refused like an absurd velocity.
void requireForceWithinCeiling(const World* world, BodyType type, double mass, const char* field, const Vec3& force) {
    if (type != BodyType::Dynamic) return;
    const double dv = force.stableNorm() / mass * world->settings().timeStep;
    detail::requirePushWithinCeiling(field, force, dv, detail::PushedMotion::Speed, true, world->settings().maxSpeed);
}

}  // namespace

// Resolves the handle to its live slot or throws a stale-handle error naming the operation.
#define ANYPHYS_SLOT(op) worldOf(link_, id_, op).slot(id_, op)

Body::Body(World* world, BodyId id) : link_(world ? world->link_ : nullptr), id_(id) {}

bool Body::isValid() const { return world() && world()->isValid(id_); }
bool Body::isFrozen() const { return ANYPHYS_SLOT("Body.isFrozen").frozen; }

const std::string& Body::name() const { return ANYPHYS_SLOT("Body.name").def.name; }
BodyType Body::type() const { return ANYPHYS_SLOT("Body.type").def.type; }
BodyState Body::state() const { return ANYPHYS_SLOT("Body.state").userState(); }
Vec3 Body::position() const { return ANYPHYS_SLOT("Body.position").userState().position; }
Quat Body::orientation() const { return ANYPHYS_SLOT("Body.orientation").userState().orientation; }
Vec3 Body::linearVelocity() const { return ANYPHYS_SLOT("Body.linearVelocity").peer->state().linearVelocity; }
Vec3 Body::angularVelocity() const { return ANYPHYS_SLOT("Body.angularVelocity").peer->state().angularVelocity; }
MassProperties Body::massProperties() const { return ANYPHYS_SLOT("Body.massProperties").mass; }
const std::string& Body::material() const { return ANYPHYS_SLOT("Body.material").def.material; }

bool Body::isTrigger() const { return ANYPHYS_SLOT("Body.isTrigger").def.isTrigger; }
std::uint64_t Body::userData() const { return ANYPHYS_SLOT("Body.userData").def.userData; }
void Body::setUserData(std::uint64_t value) { ANYPHYS_SLOT("Body.setUserData").def.userData = value; }
bool Body::isAwake() const { return ANYPHYS_SLOT("Body.isAwake").peer->isAwake(); }
void Body::wake() { ANYPHYS_SLOT("Body.wake").peer->setAwake(true); }
void* Body::nativeObject(const std::type_info& pointerType) const {
    return ANYPHYS_SLOT("Body.native").peer->nativeObject(pointerType);
}
Vec3 Body::centerOfMass() const { return ANYPHYS_SLOT("Body.centerOfMass").peer->state().position; }

Vec3 Body::angularVelocityLocal() const {
    const BodyState s = ANYPHYS_SLOT("Body.angularVelocityLocal").userState();
    return s.orientation.conjugate() * s.angularVelocity;
}

Vec3 Body::angularMomentum() const {
    // In the peer frame the inertia is diagonal: L = R diag(I) R^T w.
    const auto& slot = ANYPHYS_SLOT("Body.angularMomentum");
    const BodyState s = slot.peer->state();
    const Vec3 local = s.orientation.conjugate() * s.angularVelocity;
    return s.orientation * slot.mass.inertia.cwiseProduct(local);
}

void Body::setTransform(const Vec3& position, const Quat& orientation) {
    auto& slot = ANYPHYS_SLOT("Body.setTransform");
    detail::requireCoordinate("Body.setTransform.position", position);
    if (!orientation.coeffs().allFinite() || std::abs(orientation.norm() - 1.0) > kUnitQuaternionTolerance)
        throw Error::invalid("Body.setTransform.orientation", formatQuat(orientation), "must be a unit quaternion");
    requireInPlane(world(), "Body.setTransform.position", position);
    if (world()->settings().planar && !detail::rotatesAboutZOnly(orientation.normalized()))
        throw Error::invalid("Body.setTransform.orientation", formatQuat(orientation),
                             "must be a rotation about Z (x = y = 0) in a planar world");
    const Transform pose = slot.peerPose(position, orientation.normalized());
    slot.peer->setTransform(pose.position, pose.orientation);
    slot.checkedPose = pose;  // a frozen body is held here from now on
}

void Body::setLinearVelocity(const Vec3& v) {
    auto& slot = ANYPHYS_SLOT("Body.setLinearVelocity");
    detail::requireSpeed("Body.setLinearVelocity.velocity", v, world()->settings().maxSpeed, "WorldSettings.maxSpeed", "m/s");
    if (slot.def.type == BodyType::Static && !v.isZero(0))
        throw Error::invalid("Body.setLinearVelocity.velocity", formatVec3(v), "must be zero for a static body");
    requireInPlane(world(), "Body.setLinearVelocity.velocity", v);
    slot.peer->setLinearVelocity(v);
}

void Body::setAngularVelocity(const Vec3& w) {
    auto& slot = ANYPHYS_SLOT("Body.setAngularVelocity");
    detail::requireSpeed("Body.setAngularVelocity.velocity", w, world()->settings().maxAngularSpeed,
                         "WorldSettings.maxAngularSpeed", "rad/s");
    if (slot.def.type == BodyType::Static && !w.isZero(0))
        throw Error::invalid("Body.setAngularVelocity.velocity", formatVec3(w), "must be zero for a static body");
    requireAboutZ(world(), "Body.setAngularVelocity.velocity", w);
    slot.peer->setAngularVelocity(w);
}

void Body::applyForce(const Vec3& force) {
    auto& slot = ANYPHYS_SLOT("Body.applyForce");
    detail::requireFinite("Body.applyForce.force", force);
    requireForceWithinCeiling(world(), slot.def.type, slot.mass.mass, "Body.applyForce.force", force);
    world()->noteForcesUsed();
    slot.peer->addForce(inPlane(world(), force));
}

void Body::applyForceAtPoint(const Vec3& force, const Vec3& worldPoint) {
    auto& slot = ANYPHYS_SLOT("Body.applyForceAtPoint");
    detail::requireFinite("Body.applyForceAtPoint.force", force);
    requireForceWithinCeiling(world(), slot.def.type, slot.mass.mass, "Body.applyForceAtPoint.force", force);
    detail::requireCoordinate("Body.applyForceAtPoint.point", worldPoint);
    world()->noteForcesUsed();
    slot.peer->addForce(inPlane(world(), force));
    slot.peer->addTorque(aboutZ(world(), (worldPoint - slot.peer->state().position).cross(force)));
}

void Body::applyTorque(const Vec3& torque) {
    auto& slot = ANYPHYS_SLOT("Body.applyTorque");
    detail::requireFinite("Body.applyTorque.torque", torque);
    if (slot.def.type == BodyType::Dynamic) {
        // The spin change over one step, I^-1 torque dt, in the peer's principal frame.
        const Vec3 local = slot.peer->state().orientation.conjugate() * torque;
        const double dw = local.cwiseQuotient(slot.mass.inertia).stableNorm() * world()->settings().timeStep;
        detail::requirePushWithinCeiling("Body.applyTorque.torque", torque, dw, detail::PushedMotion::Spin, true,
                                         world()->settings().maxAngularSpeed);
    }
    world()->noteForcesUsed();
    slot.peer->addTorque(aboutZ(world(), torque));
}

void Body::applyLinearImpulse(const Vec3& impulse) {
    auto& slot = ANYPHYS_SLOT("Body.applyLinearImpulse");
    detail::requireFinite("Body.applyLinearImpulse.impulse", impulse);
    if (slot.def.type == BodyType::Dynamic) {
        const double dv = impulse.stableNorm() / slot.mass.mass;
        detail::requirePushWithinCeiling("Body.applyLinearImpulse.impulse", impulse, dv, detail::PushedMotion::Speed,
                                         false, world()->settings().maxSpeed);
    }
    slot.peer->applyLinearImpulse(inPlane(world(), impulse));
}

void Body::applyAngularImpulse(const Vec3& impulse) {
    auto& slot = ANYPHYS_SLOT("Body.applyAngularImpulse");
    detail::requireFinite("Body.applyAngularImpulse.impulse", impulse);
    if (slot.def.type == BodyType::Dynamic) {
        // The spin change I^-1 impulse, in the peer's principal frame.
        const Vec3 local = slot.peer->state().orientation.conjugate() * impulse;
        const double dw = local.cwiseQuotient(slot.mass.inertia).stableNorm();
        detail::requirePushWithinCeiling("Body.applyAngularImpulse.impulse", impulse, dw, detail::PushedMotion::Spin,
                                         false, world()->settings().maxAngularSpeed);
    }
    slot.peer->applyAngularImpulse(aboutZ(world(), impulse));
}

#undef ANYPHYS_SLOT

}  // namespace anyphys
