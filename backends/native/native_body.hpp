#pragma once
// Body storage of the native backend: one dense array of bodies, and the peer objects the layer
// holds, which find their body by index (kept up to date when the array is compacted).
#include <cstdint>
#include <vector>

#include "anyphys/defs.hpp"
#include "anyphys/peers/body_peer.hpp"
#include "anyphys/peers/rebound_from_depth.hpp"
#include "collision/shape.hpp"
#include "large_pages.hpp"

namespace anyphys::native {

class NativeWorld;
class NativeBodyPeer;

/// One shape's surface as the layer resolved it (a compound child's own, else the body's).
struct ShapeSurface {
    std::uint32_t material = 0;
    std::uint32_t layer = 1;
    std::uint32_t mask = 0xFFFFFFFFu;
    bool trigger = false;
};

// The fields every pass over contacts reads of both bodies (what the body is, whether it is
// awake, where and how fast, its proxies and tight bounds) come first, within the first three
// cache lines; the narrow phase visits many pairs and leaves most at once.
struct NativeBody {
    BodyType type = BodyType::Dynamic;
    bool alive = true;           // false while the slot is free
    bool awake = true;
    BodyState state;
    std::vector<int> proxies;    // broad-phase proxy per shape
    std::vector<Aabb> bounds;    // tight bounds per shape at the pose of the last proxy update
    std::vector<Shape> shapes;
    double invMass = 0.0;
    Vec3 inertia = Vec3::Zero();     // principal moments, body frame
    Vec3 invInertia = Vec3::Zero();  // zero for static and kinematic bodies
    double linearDamping = 0.0;
    double angularDamping = 0.0;
    double gravityScale = 1.0;
    GyroscopicMode gyroscopic = GyroscopicMode::Implicit;
    Vec3 force = Vec3::Zero();   // user force for the current step, world frame
    Vec3 torque = Vec3::Zero();  // user torque for the current step, world frame
    NativeBodyPeer* peer = nullptr;

    // ---- collision (proxies, bounds and shapes above) ----
    std::vector<ShapeSurface> surfaces;  // per shape: material, filter, sensor flag
    std::uint64_t userData = 0;
    bool trigger = false;        // every shape is a sensor: the body never responds (nor sweeps)
    double coreExtent = 0.0;     // m, smallest distance from a shape's centre to its surface (continuous collision)

    // ---- per step ----
    bool constrained = false;    // has contact constraints this step: moved by the contact solver
    Vec3 stepStartPosition = Vec3::Zero();
    Quat stepStartOrientation = Quat::Identity();
    // Whether it fell freely in the last step: only then does its gravity count in a bounce's
    // relative acceleration (restitutionTarget). A body resting on something does not fall: a ball
    // bouncing on a resting box must not be aimed as if the box fell.
    restitution::FreeFallWatch<Vec3> fall{Vec3::Zero()};

    // ---- sleeping ----
    bool allowSleep = true;      // (awake above)
    double sleepTime = 0.0;      // s at rest so far
    int sleepingIsland = -1;     // island it fell asleep with (woken together)

    bool planar = false;         // in a planar world: moves in XY, turns about Z only

    bool isDynamic() const { return type == BodyType::Dynamic; }
    /// Inverse inertia in the world frame (zero unless dynamic). In a planar world only the
    /// turn about Z is free: 1 / I_zz of the world-frame tensor, whatever the principal axes.
    Mat3 worldInverseInertia() const;
    /// Which linear directions an impulse may move: all, or X and Y in a planar world.
    Vec3 linearFreedom() const { return planar ? Vec3(1, 1, 0) : Vec3(1, 1, 1); }
    bool moves() const { return type != BodyType::Static; }
    /// Simulated this step: dynamic or kinematic, and awake.
    bool isActive() const { return alive && moves() && awake; }
    Transform pose() const { return {state.position, state.orientation}; }
};

/// The world's bodies by index: past about 10 000 bodies, on large pages.
using NativeBodies = LargeVector<NativeBody>;

class NativeBodyPeer final : public BodyPeer {
public:
    NativeBodyPeer(NativeWorld& world, std::uint32_t index) : world_(world), index_(index) {}

    std::uint32_t index() const { return index_; }
    void setIndex(std::uint32_t index) { index_ = index; }

    BodyState state() const override;
    void setTransform(const Vec3& position, const Quat& orientation) override;
    void setLinearVelocity(const Vec3& v) override;
    void setAngularVelocity(const Vec3& w) override;
    void addForce(const Vec3& force) override;
    void addTorque(const Vec3& torque) override;
    void applyLinearImpulse(const Vec3& impulse) override;
    void applyAngularImpulse(const Vec3& impulse) override;
    MassProperties massProperties() const override;
    bool isAwake() const override;
    void setAwake(bool awake) override;

private:
    NativeBody& body() const;

    NativeWorld& world_;
    std::uint32_t index_;
};

}  // namespace anyphys::native
