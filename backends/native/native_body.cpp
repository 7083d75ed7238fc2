#include "native_body.hpp"

#include "native_world.hpp"

namespace anyphys::native {

NativeBody& NativeBodyPeer::body() const { return world_.bodies()[index_]; }

BodyState NativeBodyPeer::state() const { return body().state; }

void NativeBodyPeer::setTransform(const Vec3& position, const Quat& orientation) {
    body().state.position = position;
    body().state.orientation = orientation.normalized();
}

void NativeBodyPeer::setLinearVelocity(const Vec3& v) {
    if (body().moves()) body().state.linearVelocity = v;
}

void NativeBodyPeer::setAngularVelocity(const Vec3& w) {
    if (body().moves()) body().state.angularVelocity = w;
}

void NativeBodyPeer::addForce(const Vec3& force) {
    if (body().isDynamic()) body().force += force;
}

void NativeBodyPeer::addTorque(const Vec3& torque) {
    if (body().isDynamic()) body().torque += torque;
}

void NativeBodyPeer::applyLinearImpulse(const Vec3& impulse) {
    NativeBody& b = body();
    b.state.linearVelocity += b.invMass * impulse;
}

void NativeBodyPeer::applyAngularImpulse(const Vec3& impulse) {
    NativeBody& b = body();
    if (!b.isDynamic()) return;
    const Mat3 r = b.state.orientation.toRotationMatrix();
    b.state.angularVelocity += r * b.invInertia.cwiseProduct(r.transpose() * impulse);
}

MassProperties NativeBodyPeer::massProperties() const {
    const NativeBody& b = body();
    return {b.invMass > 0 ? 1.0 / b.invMass : 0.0, b.isDynamic() ? b.inertia : Vec3::Zero()};
}

}  // namespace anyphys::native
