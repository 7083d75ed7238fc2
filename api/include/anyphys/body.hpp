#pragma once
// A light handle to a body: a link to its world plus a generational id. Copy freely; every call on
// a destroyed body, or on any body of a destroyed world, throws anyphys::Error (kind StaleHandle).
#include <cstdint>
#include <memory>
#include <typeinfo>

#include "anyphys/defs.hpp"
#include "anyphys/ids.hpp"

namespace anyphys {

class World;

namespace detail {
/// Shared by a world and every handle to its bodies and joints (a liveness token, like the control
/// block of a weak_ptr): the world clears `world` when it is destroyed, so a handle that outlives
/// its world reports it instead of reading freed memory. Not thread-safe against a world being
/// destroyed on another thread while a handle is used (no World call is).
struct WorldLink {
    World* world = nullptr;
};
}  // namespace detail

class Body {
public:
    Body() = default;
    /// The handle of body `id` of `world` (World makes these; a null world gives a null handle).
    Body(World* world, BodyId id);

    BodyId id() const { return id_; }
    /// The body's world; nullptr for a null handle or once the world was destroyed.
    World* world() const { return link_ ? link_->world : nullptr; }
    /// False for a null handle, a destroyed body, or a body of a destroyed world.
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
    /// The game's value (BodyDef::userData), and replacing it. Never read by anyphys.
    std::uint64_t userData() const;
    void setUserData(std::uint64_t value);
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

    /// Diverged under WorldSettings::divergencePolicy freeze: the layer holds the body still at its
    /// last checked pose after every step (see World::lastDiverged).
    bool isFrozen() const;

    friend bool operator==(const Body& a, const Body& b) { return a.link_ == b.link_ && a.id_ == b.id_; }

private:
    std::shared_ptr<detail::WorldLink> link_;
    BodyId id_;
};

}  // namespace anyphys
