#pragma once
// The backend side of one body. Inputs arrive validated and resolved by the layer (mass
// properties, materials); a peer only applies them. A peer body's frame is the body's centre of
// mass and principal axes: positions, orientations and velocities here are those of that frame
// (the layer converts to the user's body origin).
#include <stdexcept>
#include <typeinfo>

#include "anyphys/defs.hpp"

namespace anyphys {

class BodyPeer {
public:
    virtual ~BodyPeer() = default;

    virtual BodyState state() const = 0;
    virtual void setTransform(const Vec3& position, const Quat& orientation) = 0;
    virtual void setLinearVelocity(const Vec3& v) = 0;
    virtual void setAngularVelocity(const Vec3& w) = 0;

    /// Accumulated for the next step only (cleared after it), world frame.
    virtual void addForce(const Vec3& force) = 0;
    virtual void addTorque(const Vec3& torque) = 0;
    /// ForceEvaluation::PerStep backends only: the force and torque (world frame) the layer
    /// evaluated for this body at the start of the coming step (its fields and the force
    /// callback, summed), handed over at most once per step, just before WorldPeer::step. They
    /// act over that whole step, every substep of it, on top of addForce's, and are cleared after
    /// it. Unlike addForce they do not wake the body: a field pressing on a resting body must let
    /// it sleep. Only dynamic bodies receive them.
    virtual void holdForStep(const Vec3& force, const Vec3& torque) {
        (void)force;
        (void)torque;
        throw std::logic_error("BodyPeer::holdForStep: a ForceEvaluation::PerStep backend must implement it");
    }
    /// Immediate velocity changes, world frame.
    virtual void applyLinearImpulse(const Vec3& impulse) = 0;
    virtual void applyAngularImpulse(const Vec3& impulse) = 0;

    virtual MassProperties massProperties() const = 0;

    /// Sleeping: an asleep body is not simulated until woken (by contact, or by the layer on
    /// any user change).
    virtual bool isAwake() const = 0;
    virtual void setAwake(bool awake) = 0;

    /// Escape hatch: the engine's body object if `pointerType` is typeid of a pointer to it
    /// (e.g. typeid(btRigidBody*)), else nullptr.
    virtual void* nativeObject(const std::type_info& pointerType) { (void)pointerType; return nullptr; }
};

}  // namespace anyphys
