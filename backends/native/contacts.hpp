#pragma once
// Contacts of the native backend: one per pair of shapes whose fat bounds overlap. Each holds
// the manifolds of the last collision pass with the impulses the solver accumulated on them,
// matched by feature id from step to step so the solver can warm start.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "anyphys/peers/world_peer.hpp"
#include "collision/broad_phase.hpp"
#include "collision/shape.hpp"

namespace anyphys::native {

struct NativeBody;

/// A manifold point with the solver's data for it.
struct ContactPointState {
    ManifoldPoint geometry;
    Vec3 anchorA = Vec3::Zero();   // point - centre of mass of A, world frame, at step start
    Vec3 anchorB = Vec3::Zero();
    double normalMass = 0.0;
    double tangentMass[2] = {0.0, 0.0};
    double normalImpulse = 0.0;    // accumulated, N s
    double tangentImpulse[2] = {0.0, 0.0};
    double maxNormalImpulse = 0.0;
    double relativeVelocity = 0.0; // normal approach speed at step start (restitution)
    double restitutionTarget = 0.0; // normal velocity the bounce aims for (see ContactSolver)
};

struct ContactManifold {
    Vec3 normal = Vec3::Zero();    // A -> B
    Vec3 tangent[2] = {Vec3::Zero(), Vec3::Zero()};
    std::uint32_t key = 0;
    int pointCount = 0;
    ContactPointState points[4];
};

struct Contact {
    std::uint32_t bodyA = 0, bodyB = 0;
    int shapeA = 0, shapeB = 0;
    bool trigger = false;
    bool touching = false;          // some point within linearSlop (or overlapping, for triggers)
    double friction = 0.0;
    double restitution = 0.0;
    std::vector<ContactManifold> manifolds;
};

/// Broad-phase proxy key of a body's shape.
inline std::uint64_t proxyKey(std::uint32_t body, int shape) { return (std::uint64_t(body) << 20) | std::uint64_t(shape); }
inline std::uint32_t proxyBody(std::uint64_t key) { return std::uint32_t(key >> 20); }
inline int proxyShape(std::uint64_t key) { return int(key & ((1u << 20) - 1)); }

class ContactManager {
public:
    struct PairHash {
        std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t>& k) const noexcept {
            return std::hash<std::uint64_t>()(k.first * 0x9E3779B97F4A7C15ull ^ k.second);
        }
    };
    using Map = std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, Contact, PairHash>;

    /// A broad-phase pair: creates the contact if the bodies may touch at all.
    void addPair(std::uint64_t keyA, std::uint64_t keyB, const std::vector<NativeBody>& bodies, const MaterialTable& materials);
    /// Runs the narrow phase on every contact with an awake moving body, drops contacts whose
    /// fat bounds separated. Returns the bodies that began touching an awake body while asleep.
    /// The speculative margin of a pair grows with how fast the bodies approach (relative speed
    /// x dt), so an impact in the next step always has a contact to stop it.
    void update(std::vector<NativeBody>& bodies, const BroadPhase& broadPhase, double speculativeDistance,
                double linearSlop, double dt, std::vector<std::uint32_t>& toWake);
    void removeBody(std::uint32_t body);
    void clear() { contacts_.clear(); }

    Map& contacts() { return contacts_; }
    const Map& contacts() const { return contacts_; }

private:
    Map contacts_;
    std::vector<Manifold> scratch_;
};

}  // namespace anyphys::native
