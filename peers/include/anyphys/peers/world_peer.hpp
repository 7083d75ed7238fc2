#pragma once
// The backend side of one world.
#include <functional>
#include <memory>
#include <typeinfo>

#include "anyphys/defs.hpp"
#include "anyphys/effects.hpp"
#include "anyphys/listeners/events.hpp"
#include "anyphys/peers/body_peer.hpp"
#include "anyphys/peers/shape_data.hpp"
#include "anyphys/task_system.hpp"

namespace anyphys {

/// Everything the layer has resolved for a new body.
struct BodyPeerDef {
    BodyDef def;                    ///< validated; position / orientation are those of the peer frame
                                    ///< (centre of mass, principal axes); def.shape is the user's shape
    MassProperties mass;            ///< solved by the layer (zero for static and kinematic bodies);
                                    ///< centerOfMass zero and principalAxes identity in the peer frame
    std::vector<PeerShape> shapes;  ///< the collision shapes, in the peer frame
    std::uint64_t userData = 0;     ///< the layer's key for this body, echoed in contacts and query hits
    std::uint32_t material = 0;     ///< row / column of the MaterialTable
};

/// Friction and restitution of a pair of materials, resolved by the layer.
struct ContactMaterial {
    double friction = 0.6;
    double restitution = 0.0;
};

/// Resolved values for every pair of material indices (symmetric, count x count).
struct MaterialTable {
    std::size_t count = 1;
    std::vector<ContactMaterial> values = std::vector<ContactMaterial>(1);
    const ContactMaterial& get(std::uint32_t a, std::uint32_t b) const { return values[a * count + b]; }
};

/// One pair in contact (or overlapping, for triggers) after a step: points carry depth
/// (-separation), so slightly separated speculative points have depth < 0; the layer decides
/// what counts as touching.
struct PeerContact {
    std::uint64_t bodyA = 0;          ///< userData of the bodies
    std::uint64_t bodyB = 0;
    bool trigger = false;
    Vec3 normal = Vec3::Zero();       ///< from A to B
    std::vector<ContactPoint> points; ///< world frame
};

struct PeerRayHit {
    std::uint64_t body = 0;          ///< userData of the body hit
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();      ///< surface normal at the hit, facing the ray
    double distance = 0.0;           ///< m along the unit direction
};

/// Access to body states while the backend evaluates forces inside a step. For backends with
/// ForceEvaluation::PerStage these are the integrator's intermediate states.
class ForceStage {
public:
    virtual ~ForceStage() = default;
    virtual double time() const = 0;  ///< s, the time of this evaluation
    virtual BodyState state(const BodyPeer& body) const = 0;
    virtual void addForce(BodyPeer& body, const Vec3& force) = 0;
    virtual void addTorque(BodyPeer& body, const Vec3& torque) = 0;
};

using ForceHook = std::function<void(ForceStage&)>;

class WorldPeer {
public:
    virtual ~WorldPeer() = default;

    virtual std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) = 0;
    /// The peer is destroyed by the caller right after this returns.
    virtual void destroyBody(BodyPeer& body) = 0;

    /// The effects to simulate from now on (already intersected with the capabilities).
    virtual void setEffects(Effects effects) = 0;
    /// Called inside each step when forces are evaluated; empty to clear.
    virtual void setForceHook(ForceHook hook) = 0;

    /// Advances by dt seconds (the layer guarantees dt > 0 and finite). `time` is the start time.
    virtual void step(double time, double dt) = 0;

    /// Where to run parallel work from now on (not owned; outlives the peer, or is replaced
    /// first). Null: step on the calling thread. Called after construction when the world has
    /// more than one worker; a backend whose engine steps on one thread ignores it.
    virtual void setTaskSystem(TaskSystem* tasks) { (void)tasks; }

    /// Pair materials; called before any body is created and whenever the library changes.
    virtual void setMaterialTable(const MaterialTable& table) = 0;
    /// Every pair in contact or overlap after the last step (touching or speculative).
    virtual void collectContacts(std::vector<PeerContact>& out) = 0;
    /// Hits along origin + t direction (unit), 0 <= t <= maxDistance, on bodies whose layer is
    /// in `mask`; only the closest if closestOnly, otherwise all sorted by distance. Triggers are skipped.
    virtual std::vector<PeerRayHit> raycast(const Vec3& origin, const Vec3& direction, double maxDistance,
                                            bool closestOnly, std::uint32_t mask) = 0;
    /// Bodies (userData) whose shapes overlap `shapes` placed at `pose`, layer in `mask`. Triggers are skipped.
    virtual std::vector<std::uint64_t> overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                               std::uint32_t mask) = 0;

    /// Escape hatch: the engine's world object if `pointerType` is typeid of a pointer to it
    /// (e.g. typeid(dxWorld*)), else nullptr.
    virtual void* nativeObject(const std::type_info& pointerType) { (void)pointerType; return nullptr; }
};

}  // namespace anyphys
