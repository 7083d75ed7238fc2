#include "box2d_body.hpp"

#include <cmath>

#include "box2d_world.hpp"

namespace anyphys::box2d {

Box2dBody::Box2dBody(Box2dWorld& world, b2Body* body, const BodyPeerDef& def, const Embedding& embedding)
    : world_(&world),
      body_(body),
      embedding_(embedding),
      mass_(def.mass),
      userData_(def.userData),
      linearDamping_(def.def.linearDamping),
      angularDamping_(def.def.angularDamping) {}

Box2dBody::~Box2dBody() {
    if (world_) world_->forgetBody(*this);
}

BodyState Box2dBody::state() const {
    BodyState s;
    s.position = fromB2(body_->GetPosition(), embedding_.height);
    s.orientation = embedding_.peerOrientation(body_->GetAngle());
    s.linearVelocity = fromB2(body_->GetLinearVelocity());
    s.angularVelocity = Vec3(0, 0, body_->GetAngularVelocity());
    return s;
}

// Every user change wakes the body: a sleeping body must react to it.
void Box2dBody::setTransform(const Vec3& position, const Quat& orientation) {
    body_->SetTransform(toB2(position), static_cast<float>(embedding_.bodyAngle(orientation)));
    if (body_->GetType() == b2_staticBody)
        world_->wakeTouching(body_);  // what rests on it must notice it moved
    else
        body_->SetAwake(true);
}

void Box2dBody::setLinearVelocity(const Vec3& v) {
    if (body_->GetType() == b2_staticBody) return;
    body_->SetLinearVelocity(toB2(v));
    body_->SetAwake(true);
}

void Box2dBody::setAngularVelocity(const Vec3& w) {
    if (body_->GetType() == b2_staticBody) return;
    body_->SetAngularVelocity(static_cast<float>(w.z()));
    body_->SetAwake(true);
}

void Box2dBody::addForce(const Vec3& force) {
    if (!isDynamic()) return;
    force_ += toB2(force);
    body_->SetAwake(true);
}

void Box2dBody::addTorque(const Vec3& torque) {
    if (!isDynamic()) return;
    torque_ += static_cast<float>(torque.z());
    body_->SetAwake(true);
}

void Box2dBody::holdForStep(const Vec3& force, const Vec3& torque) {
    if (!isDynamic()) return;
    heldForce_ += toB2(force);
    heldTorque_ += static_cast<float>(torque.z());
}

void Box2dBody::applyLinearImpulse(const Vec3& impulse) {
    if (!isDynamic()) return;
    body_->ApplyLinearImpulseToCenter(toB2(impulse), true);
}

void Box2dBody::applyAngularImpulse(const Vec3& impulse) {
    if (!isDynamic()) return;
    body_->ApplyAngularImpulse(static_cast<float>(impulse.z()), true);
}

MassProperties Box2dBody::massProperties() const {
    MassProperties m;
    if (!isDynamic()) return m;
    // What Box2D simulates: its mass, and its moment about Z where Z is a principal axis.
    m.mass = body_->GetMass();
    m.inertia = mass_.inertia;
    if (embedding_.planar()) m.inertia.z() = body_->GetInertia();
    return m;
}

bool Box2dBody::isAwake() const { return body_->IsAwake(); }

void Box2dBody::setAwake(bool awake) {
    if (body_->GetType() == b2_staticBody) return;
    body_->SetAwake(awake);  // asleep: Box2D also zeroes its velocities and forces
    if (!awake) {
        force_.SetZero();
        torque_ = 0.0f;
    }
}

void* Box2dBody::nativeObject(const std::type_info& pointerType) {
    return pointerType == typeid(b2Body*) ? static_cast<void*>(body_) : nullptr;
}

void Box2dBody::applyDamping(bool on, double h) {
    const auto rate = [&](double c) { return on && c > 0 ? static_cast<float>(std::expm1(c * h) / h) : 0.0f; };
    body_->SetLinearDamping(rate(linearDamping_));
    body_->SetAngularDamping(rate(angularDamping_));
}

}  // namespace anyphys::box2d
