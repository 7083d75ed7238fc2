#include "native_body.hpp"

#include "native_world.hpp"

namespace anyphys::native {

// Every user change wakes the body (and its island): a sleeping body must react to it.
NativeBody& NativeBodyPeer::body() const { return world_.bodies()[index_]; }

BodyState NativeBodyPeer::state() const { return body().state; }

void NativeBodyPeer::setTransform(const Vec3& position, const Quat& orientation) {
    body().state.position = position;
    body().state.orientation = orientation.normalized();
    world_.bodyTeleported(index_);
}

void NativeBodyPeer::setLinearVelocity(const Vec3& v) {
    if (!body().moves()) return;
    body().state.linearVelocity = v;
    world_.wakeBody(index_);
}

void NativeBodyPeer::setAngularVelocity(const Vec3& w) {
    if (!body().moves()) return;
    body().state.angularVelocity = w;
    world_.wakeBody(index_);
}

void NativeBodyPeer::addForce(const Vec3& force) {
    if (!body().isDynamic()) return;
    body().force += force;
    world_.wakeBody(index_);
}

void NativeBodyPeer::addTorque(const Vec3& torque) {
    if (!body().isDynamic()) return;
    body().torque += torque;
    world_.wakeBody(index_);
}

void NativeBodyPeer::applyLinearImpulse(const Vec3& impulse) {
    NativeBody& b = body();
    if (!b.isDynamic()) return;
    b.state.linearVelocity += b.invMass * b.linearFreedom().cwiseProduct(impulse);
    world_.wakeBody(index_);
}

void NativeBodyPeer::applyAngularImpulse(const Vec3& impulse) {
    NativeBody& b = body();
    if (!b.isDynamic()) return;
    b.state.angularVelocity += b.worldInverseInertia() * impulse;
    world_.wakeBody(index_);
}

Mat3 NativeBody::worldInverseInertia() const {
    if (!isDynamic()) return Mat3::Zero();
    const Mat3 r = state.orientation.toRotationMatrix();
    if (!planar) return r * invInertia.asDiagonal() * r.transpose();
    const Vec3 z = r.transpose() * Vec3::UnitZ();  // world Z in the principal frame
    const double izz = z.dot(inertia.cwiseProduct(z));
    Mat3 out = Mat3::Zero();
    out(2, 2) = izz > 0.0 ? 1.0 / izz : 0.0;
    return out;
}

MassProperties NativeBodyPeer::massProperties() const {
    const NativeBody& b = body();
    MassProperties m;
    m.mass = b.invMass > 0 ? 1.0 / b.invMass : 0.0;
    m.inertia = b.isDynamic() ? b.inertia : Vec3::Zero();
    return m;
}

bool NativeBodyPeer::isAwake() const { return body().awake; }

void NativeBodyPeer::setAwake(bool awake) {
    if (awake)
        world_.wakeBody(index_);
    else
        world_.sleepBody(index_);
}

}  // namespace anyphys::native
