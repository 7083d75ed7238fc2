#pragma once
// Contacts of the native backend: one per pair of shapes whose fat bounds overlap. Each holds
// the manifolds of the last collision pass with the impulses the solver accumulated on them,
// matched by feature id from step to step so the solver can warm start.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "anyphys/peers/world_peer.hpp"
#include "anyphys/task_system.hpp"
#include "collision/broad_phase.hpp"
#include "collision/collide.hpp"
#include "collision/shape.hpp"
#include "native_body.hpp"
#include "solver/prefetch.hpp"

namespace anyphys::native {

/// A manifold point with the impulses the solver left on it.
struct ContactPointState {
    ManifoldPoint geometry;
    double normalImpulse = 0.0;    // N s, accumulated in the last substep: the next step's warm start
    double stepImpulse = 0.0;      // N s, pushed through this point over the whole last step (events)
    // Where the narrow phase found the point: the solver's anchors, offsets from each body's
    // centre of mass (world axes; on a round shape's core, see contactAnchor), and the separation
    // there. Recycling (flat shapes only, whose anchors are the point itself) keeps them and moves
    // only the separation (ContactManager::recycle).
    Vec3 anchorA = Vec3::Zero(), anchorB = Vec3::Zero();
    double baseSeparation = 0.0;
};

struct ContactManifold {
    Vec3 normal = Vec3::Zero();    // A -> B
    std::uint32_t key = 0;
    int pointCount = 0;
    ContactPointState points[4];
    Vec3 frictionImpulse = Vec3::Zero();  // N s, world frame, at the friction centre (warm start)
    double twistImpulse = 0.0;            // N m s, about the normal (warm start)

    /// The normal impulse its points carried over the last substep (N s): the load it bears.
    double carriedImpulse() const {
        double sum = 0.0;
        for (int i = 0; i < pointCount; ++i) sum += points[i].normalImpulse;
        return sum;
    }
};

// The first 64 bytes hold what the narrow phase reads of every contact, most of which (in a
// pile, neighbours whose fat bounds overlap) it leaves at once: the bodies, their proxies, whether
// tight bounds can tell, and the flags.
struct Contact {
    std::uint32_t bodyA = 0, bodyB = 0;
    int shapeA = 0, shapeB = 0;
    int proxyA = 0, proxyB = 0;     // the shapes' broad-phase proxies (fixed while the bodies live)
    bool alive = false;             // false while the slot is free
    bool trigger = false;
    bool touching = false;          // some point within linearSlop (or overlapping, for triggers)
    bool separated = false;         // set by the narrow phase: fat bounds apart, destroy the contact
    bool boxed = false;             // neither shape is a plane or mesh: tight bounds may rule the pair out
    bool flatPair = false;          // neither shape is round (sphere, capsule): see ContactLane::flatPair
    std::vector<ContactManifold> manifolds;  // capacity kept from step to step (and slot reuse)
    double friction = 0.0;
    double restitution = 0.0;
    CollideCache collideCache;      // the narrow phase's memory of this pair (last separating axis, ...)
    // The poses at the last narrow phase, against which recycle measures how far the pair moved.
    bool recyclable = false;        // a pair of flat shapes whose manifolds the narrow phase filled
    Quat cachedQA = Quat::Identity(), cachedQB = Quat::Identity(), cachedRelQ = Quat::Identity();
    Vec3 cachedRelP = Vec3::Zero();
    double extent = 0.0;            // farthest a point of either moving shape lies from its centre of mass
};

/// Broad-phase proxy key of a body's shape.
inline std::uint64_t proxyKey(std::uint32_t body, int shape) { return (std::uint64_t(body) << 20) | std::uint64_t(shape); }
inline std::uint32_t proxyBody(std::uint64_t key) { return std::uint32_t(key >> 20); }
inline int proxyShape(std::uint64_t key) { return int(key & ((1u << 20) - 1)); }

/// Contacts live in slots of one array, visited in slot order; freed slots are reused last
/// freed first. So the order in which constraints are solved depends only on the sequence of
/// operations, never on hashing: the same run gives the same bits with any standard library.
class ContactManager {
public:
    /// A broad-phase pair: creates the contact if the bodies may touch at all.
    void addPair(std::uint64_t keyA, std::uint64_t keyB, const NativeBodies& bodies, const MaterialTable& materials);
    /// Runs the narrow phase on every contact with an awake moving body (on the workers of
    /// `tasks`, if any), then, in slot order, destroys contacts whose fat bounds separated, lists
    /// the contacts that may touch (forEachTouchCandidate) and appends to `toWake` the sleeping
    /// bodies that an awake body is about to touch. The
    /// speculative margin of a pair grows with how fast the bodies approach (relative speed x
    /// dt), so an impact in the next step always has a contact to stop it.
    /// In a planar world (`planar`) points that differ only in Z are merged: the plane holds the
    /// bodies, so they would be the same constraint twice.
    void update(NativeBodies& bodies, const BroadPhase& broadPhase, double speculativeDistance,
                double linearSlop, double dt, bool planar, std::vector<std::uint32_t>& toWake, TaskSystem* tasks);
    void removeBody(std::uint32_t body);
    void clear();
    /// Bodies a and b never get contacts (a joint between them does not let them collide):
    /// contacts they have are destroyed, new pairs refused. Counted: two joints need two includes.
    void excludePair(std::uint32_t a, std::uint32_t b);
    void includePair(std::uint32_t a, std::uint32_t b);
    /// A joint with collideConnected false joins bodies a and b (either order).
    bool excludes(std::uint32_t a, std::uint32_t b) const;

    /// Calls fn(contact) for every live contact, in slot order.
    template <class Fn>
    void forEach(Fn&& fn) {
        for (Contact& c : slots_)
            if (c.alive) fn(c);
    }
    template <class Fn>
    void forEach(Fn&& fn) const {
        for (const Contact& c : slots_)
            if (c.alive) fn(c);
    }
    /// Calls fn(contact) for the live contacts that may touch, in slot order: those whose last
    /// narrow phase left manifolds (speculative points included), and triggers. These are all
    /// the solver, the contact report and the islands read; in a pile most contacts are pairs of
    /// neighbours whose fat bounds overlap with no point, and skipping them skips most of the
    /// memory. Listed by update(); a contact destroyed since is skipped. `bodies`: the world's,
    /// which every such walk reads (asked for ahead: prefetchCandidate).
    template <class Fn>
    void forEachTouchCandidate(const NativeBodies& bodies, Fn&& fn) {
        const std::size_t end = touchCandidates_.size();
        for (std::size_t i = 0; i < end; ++i) {
            prefetchCandidate(i, end, bodies);
            if (Contact& c = slots_[touchCandidates_[i]]; c.alive) fn(c);
        }
    }
    /// Those among the candidates [begin, end) of the list (to split them among workers).
    template <class Fn>
    void forEachTouchCandidateIn(std::size_t begin, std::size_t end, const NativeBodies& bodies, Fn&& fn) const {
        for (std::size_t i = begin; i < end; ++i) {
            prefetchCandidate(i, end, bodies);
            if (const Contact& c = slots_[touchCandidates_[i]]; c.alive) fn(c);
        }
    }
    std::size_t touchCandidateCount() const { return touchCandidates_.size(); }
    std::size_t size() const { return index_.size(); }

private:
    struct PairHash {
        std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t>& k) const noexcept {
            return std::hash<std::uint64_t>()(k.first * 0x9E3779B97F4A7C15ull ^ k.second);
        }
    };
    struct Scratch {  // one per worker
        std::vector<Manifold> found;
        std::vector<ContactManifold> previous;
    };
    struct ChunkLists {  // what the narrow phase found in one chunk of slots (update), in slot order
        std::vector<std::uint32_t> separated;   // contacts to destroy
        std::vector<std::uint32_t> candidates;  // contacts that may touch (forEachTouchCandidate)
        std::vector<std::uint32_t> wake;        // sleeping bodies an awake one is about to touch
    };

    // A walk over the touch candidates reads each one's slot, bodies and manifolds, all scattered
    // in memory: it asks for a candidate's slot kCandidatesAhead ahead, and for its bodies' first
    // lines and first manifold kCandidateDataAhead ahead, once the slot's line has arrived.
    static constexpr std::size_t kCandidatesAhead = 8, kCandidateDataAhead = 4;
    [[gnu::always_inline]] void prefetchCandidate(std::size_t i, std::size_t end, const NativeBodies& bodies) const {
        if (i + kCandidatesAhead < end) prefetchBytes(&slots_[touchCandidates_[i + kCandidatesAhead]], kCacheLine);
        if (i + kCandidateDataAhead >= end) return;
        const Contact& c = slots_[touchCandidates_[i + kCandidateDataAhead]];
        if (!c.alive) return;
        prefetchBytes(&bodies[c.bodyA], kCacheLine);
        prefetchBytes(&bodies[c.bodyB], kCacheLine);
        if (!c.manifolds.empty()) prefetchBytes(c.manifolds.data(), kCacheLine);
    }
    // The narrow phase walks every slot in order and leaves most at once (neighbours whose fat
    // bounds overlap, with no point) after reading the slot's first line and its bodies' first
    // lines: past a core's cache each was a wait. It asks for a slot's line kSlotsAhead slots
    // ahead, and for its bodies' lines kBodiesAhead ahead, once the slot's line has arrived.
    static constexpr std::size_t kSlotsAhead = 12, kBodiesAhead = 6;
    static constexpr std::size_t kBodyBytesRead = 192;  // NativeBody's fields every pass over contacts reads
    void prefetchAhead(std::size_t slot, const NativeBodies& bodies) const;
    void destroy(std::uint32_t slot);
    /// Sorts a contact the narrow phase has just updated into its chunk's lists.
    static void classify(const Contact& c, std::uint32_t slot, const NativeBodies& bodies, ChunkLists& lists);
    void collideContact(Contact& c, NativeBodies& bodies, const BroadPhase& broadPhase,
                        double speculativeDistance, double linearSlop, double dt, bool planar, Scratch& scratch) const;
    // Contact recycling (as Box2D v3 and Box3D): while a pair of flat shapes rests and has moved
    // less than linearSlop since the narrow phase last ran on it, its manifolds are kept, the
    // normal and each body's anchors as found, and only the separations follow the bodies. True
    // when it did so; false (nothing changed) when the narrow phase must run. Kept anchors give a
    // leaning stack the lever arms of its upright build: without them, soft contacts let a
    // column of cubes buckle under its own weight above about 24 cubes at 60 Hz.
    bool recycle(Contact& c, const NativeBody& a, const NativeBody& b, double linearSlop, double dt) const;

    LargeVector<Contact> slots_;
    std::vector<std::uint32_t> free_;
    std::vector<std::uint32_t> touchCandidates_;  // slots, ascending (forEachTouchCandidate)
    std::vector<ChunkLists> chunks_;              // per chunk of slots (update); capacity kept
    // Finds a pair's slot. Only looked up, never iterated. Nodes of destroyed pairs are kept
    // and reused, so pairs that come and go cost no allocation once the pile is warm.
    using PairIndex = std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, std::uint32_t, PairHash>;
    PairIndex index_;
    std::vector<PairIndex::node_type> spareNodes_;
    std::vector<Scratch> scratch_;
    std::unordered_map<std::uint64_t, int> excluded_;  // body pair (low << 32 | high) -> joints excluding it
};

}  // namespace anyphys::native
