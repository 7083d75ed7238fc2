#pragma once
// A light handle to a body: a world pointer plus a generational id. Copy freely; every call on a
// destroyed body throws anyphys::Error.
#include <typeinfo>

#include "anyphys/defs.hpp"
#include "anyphys/ids.hpp"

namespace anyphys {

class World;

class Body {
public:
    Body() = default;
    Body(World* world, BodyId id) : world_(world), id_(id) {}

    BodyId id() const { return id_; }
    World* world() const { return world_; }
    bool isValid() const;

    const std::string& name() const;
    BodyType type() const;
    BodyState state() const;
    Vec3 position() const;
    Quat orientation() const;
    Vec3 linearVelocity() const;
    Vec3 angularVelocity() const;
    /// Angular velocity in the body frame.
    Vec3 angularVelocityLocal() const;
    MassProperties massProperties() const;
    /// World-frame angular momentum I_world * omega, kg m^2/s.
    Vec3 angularMomentum() const;
    const std::string& material() const;
    /// Centre of mass, world frame.
    Vec3 centerOfMass() const;
    bool isTrigger() const;
    bool isAwake() const;
    /// Wakes the body (and its island). Any velocity, force or transform change wakes it too.
    void wake();

    void setTransform(const Vec3& position, const Quat& orientation);
    void setLinearVelocity(const Vec3& v);
    void setAngularVelocity(const Vec3& w);
    /// Force (N) and torque (N m) for the next step only, world frame.
    void applyForce(const Vec3& force);
    /// Force at a world point: adds the torque (point - centre) x force.
    void applyForceAtPoint(const Vec3& force, const Vec3& worldPoint);
    void applyTorque(const Vec3& torque);
    /// Immediate velocity changes: N s and N m s.
    void applyLinearImpulse(const Vec3& impulse);
    void applyAngularImpulse(const Vec3& impulse);

    /// Escape hatch: the engine's own body object when the world's engine has a T, else
    /// nullptr: dxBody (ODE's dBodyID) on ode, btRigidBody on bullet, b2Body on box2d.
    template <class T>
    T* native() const { return static_cast<T*>(nativeObject(typeid(T*))); }
    void* nativeObject(const std::type_info& pointerType) const;

    friend bool operator==(const Body& a, const Body& b) { return a.world_ == b.world_ && a.id_ == b.id_; }

private:
    World* world_ = nullptr;
    BodyId id_;
};

}  // namespace anyphys
