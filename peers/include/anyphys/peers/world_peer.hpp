#pragma once
// The backend side of one world.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <typeinfo>
#include <vector>

#include "anyphys/defs.hpp"
#include "anyphys/effects.hpp"
#include "anyphys/listeners/events.hpp"
#include "anyphys/peers/body_peer.hpp"
#include "anyphys/peers/joint_peer.hpp"
#include "anyphys/peers/motion_limits.hpp"
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

/// Every pair in contact or overlap after a step, flat: a pair's points are a range of one array
/// shared by all pairs, so a step of thousands of pairs allocates nothing once the buffers have
/// grown (the layer keeps one report and hands it over cleared every step). One entry per body
/// pair and kind (touching or speculative; or overlapping, for a trigger: a compound's sensor
/// child and its solid children make two entries for the same bodies), normal from A to B, points in
/// the world frame with depth = -separation, so slightly separated speculative points have
/// depth < 0: the layer decides what counts as touching.
struct ContactReport {
    struct Pair {
        std::uint64_t bodyA = 0;        ///< userData of the bodies
        std::uint64_t bodyB = 0;
        bool trigger = false;
        bool asleep = false;            ///< a body of the pair is asleep (see sleepKnown)
        /// The peer left this pair's points unwritten (their range is set) until the layer asks
        /// for them (WorldPeer::writeDeferredPoints). Only a collision pair some point of which
        /// carried an impulse: it touches whatever its depths (World::dispatchEvents), and the
        /// points are needed only when the events are read, which most steps they are not.
        bool pointsDeferred = false;
        Vec3 normal = Vec3::Zero();     ///< from A to B
        std::uint32_t firstPoint = 0;   ///< the pair's points: [firstPoint, firstPoint + pointCount)
        std::uint32_t pointCount = 0;
    };
    std::vector<Pair> pairs;
    /// World frame. Only the pairs' ranges are read: a peer may copy all its points at once and
    /// leave those of pairs it skips unreferenced.
    std::vector<ContactPoint> points;
    /// The peer flagged each pair `asleep` when one of its bodies is a dynamic or kinematic body
    /// that is not awake (BodyPeer::isAwake); otherwise the layer asks the bodies.
    bool sleepKnown = false;
    /// Some pair's points are deferred (Pair::pointsDeferred) and not yet written.
    bool pointsDeferred = false;

    void clear() {
        pairs.clear();
        points.clear();
        sleepKnown = false;
        pointsDeferred = false;
    }
    /// Starts a pair; the points added next are its points.
    void addPair(std::uint64_t bodyA, std::uint64_t bodyB, bool trigger, const Vec3& normal, bool asleep = false) {
        pairs.push_back({bodyA, bodyB, trigger, asleep, false, normal, static_cast<std::uint32_t>(points.size()), 0});
    }
    void addPoint(const ContactPoint& point) {
        points.push_back(point);
        ++pairs.back().pointCount;
    }

    /// For peers whose bodies may meet in several shape pairs: merges the entries of one body
    /// pair (either order, same trigger flag) into the first, its points followed by the
    /// others' in report order. Pairs come out ordered by body pair. Every point must be
    /// written: a peer that defers writes its deferred points first.
    void mergeRepeatedPairs() {
        // Room for the largest outcome at once: a world's first merge may come late (Bullet merges
        // only while continuous collision adds predictive manifolds), and doubling its three
        // buffers up from empty cost a collapsing 5 050-box pile 42 allocations in one step.
        // The room is the report's capacity, not its size: the merged buffers are swapped in as the
        // report's, and one sized to this step alone would grow again as the next step's pairs
        // (or the layer's near pairs, World::stillTouching) pass it.
        order_.clear();
        keepRoomToMerge();
        for (std::uint32_t i = 0; i < pairs.size(); ++i) {
            const auto [low, high] = std::minmax(pairs[i].bodyA, pairs[i].bodyB);
            order_.push_back({low, high, i});
        }
        // A body pair's collision and trigger entries stay apart (a compound with a sensor child
        // has both): ordered by trigger flag after the bodies, so each kind merges into one.
        std::sort(order_.begin(), order_.end(), [this](const Order& x, const Order& y) {
            const bool tx = pairs[x.index].trigger, ty = pairs[y.index].trigger;
            return x.low != y.low ? x.low < y.low : x.high != y.high ? x.high < y.high : tx != ty ? tx < ty : x.index < y.index;
        });
        mergedPairs_.clear();
        mergedPoints_.clear();
        const Order* previous = nullptr;
        for (const Order& o : order_) {
            const Pair& p = pairs[o.index];
            const bool repeat = previous && previous->low == o.low && previous->high == o.high &&
                                mergedPairs_.back().trigger == p.trigger;
            if (!repeat) {
                mergedPairs_.push_back(p);
                mergedPairs_.back().firstPoint = static_cast<std::uint32_t>(mergedPoints_.size());
                mergedPairs_.back().pointCount = 0;
            }
            mergedPoints_.insert(mergedPoints_.end(), points.begin() + p.firstPoint,
                                 points.begin() + p.firstPoint + p.pointCount);
            mergedPairs_.back().pointCount += p.pointCount;
            previous = &o;
        }
        pairs.swap(mergedPairs_);
        points.swap(mergedPoints_);
    }

    /// For a peer that may merge in a later step: sizes the merge's buffers to the report's
    /// capacity now, so they grow when the report does (rarely, geometrically) and a merge that
    /// first comes late in a run (a collapsing pile's first fast body) allocates nothing.
    void keepRoomToMerge() {
        order_.reserve(pairs.capacity());
        mergedPairs_.reserve(pairs.capacity());
        mergedPoints_.reserve(points.capacity());
    }

private:
    struct Order {
        std::uint64_t low, high;
        std::uint32_t index;
    };
    std::vector<Order> order_;  // scratch of mergeRepeatedPairs, kept for reuse
    std::vector<Pair> mergedPairs_;
    std::vector<ContactPoint> mergedPoints_;
};

struct PeerRayHit {
    std::uint64_t body = 0;          ///< userData of the body hit
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();      ///< surface normal at the hit, facing the ray
    double distance = 0.0;           ///< m along the unit direction
};

/// Sorts a ray's hits nearest first and keeps one per body and distance (within a millionth of
/// it, or a micrometre): an engine whose one shape is several pieces (Box2D's capsules and planes,
/// Bullet's plane as two triangles under the ray) answers twice for a ray through a seam, where
/// the layer promises at most one hit per shape.
inline void sortAndMergeSeamHits(std::vector<PeerRayHit>& hits) {
    std::sort(hits.begin(), hits.end(), [](const PeerRayHit& a, const PeerRayHit& b) { return a.distance < b.distance; });
    const auto seam = [](const PeerRayHit& a, const PeerRayHit& b) {
        return a.body == b.body && std::abs(a.distance - b.distance) <= 1e-6 * std::max(1.0, b.distance);
    };
    hits.erase(std::unique(hits.begin(), hits.end(), seam), hits.end());
}

/// Access to body states while a ForceEvaluation::PerStage backend evaluates forces inside a
/// step: the integrator's intermediate states. (On PerStep backends the layer evaluates forces
/// itself, once before the step, and hands them over with BodyPeer::holdForStep.)
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

    /// A joint between live bodies of this world, of a type the backend's capabilities list, with
    /// only the parameters it lists for that type (the layer checks both first). Joints are
    /// destroyed before their bodies.
    virtual std::unique_ptr<JointPeer> createJoint(const JointPeerDef& def) {
        (void)def;
        throw std::logic_error("this backend declares no joint types");
    }
    /// The peer is destroyed by the caller right after this returns.
    virtual void destroyJoint(JointPeer& joint) { (void)joint; }

    /// The effects to simulate from now on (already intersected with the capabilities).
    virtual void setEffects(Effects effects) = 0;
    /// ForceEvaluation::PerStage backends only: called inside each step at every force
    /// evaluation (integrator stage), while the effect userForces is on; empty to clear. The
    /// layer never calls it on a PerStep backend.
    virtual void setForceHook(ForceHook hook) {
        (void)hook;
        throw std::logic_error("WorldPeer::setForceHook: a ForceEvaluation::PerStage backend must implement it");
    }

    /// Advances by dt seconds (the layer guarantees dt > 0 and finite). `time` is the start time.
    virtual void step(double time, double dt) = 0;

    /// Where to run parallel work from now on (not owned; outlives the peer, or is replaced
    /// first). Null: step on the calling thread. Called after construction when the world has
    /// more than one worker; a backend whose engine steps on one thread ignores it.
    virtual void setTaskSystem(TaskSystem* tasks) { (void)tasks; }

    /// Pair materials; called before any body is created and whenever the library changes.
    virtual void setMaterialTable(const MaterialTable& table) = 0;
    /// Every pair in contact or overlap after the last step, appended to `out` (the layer
    /// clears it first), without a vector per pair.
    virtual void reportContacts(ContactReport& out) = 0;
    /// Writes the points of the pairs the last reportContacts deferred (Pair::pointsDeferred)
    /// into their ranges of `out.points`, as that report would have written them, from what the
    /// peer kept when it reported: the world may have changed since (bodies moved or destroyed).
    /// Called at most once per report, before the layer reads any deferred point. Only a peer
    /// that defers implements it.
    virtual void writeDeferredPoints(ContactReport& out) { (void)out; }
    /// Whether anyone reads the events' impulses: false until a listener is added or the events
    /// are read (World::lastEvents), told before each step. A backend that measures impulses
    /// only for the events (ODE's joint feedback) may skip them until then, and says so through
    /// measuredImpulses(). One that defers points (writeDeferredPoints) defers them only while
    /// this is false: once events are read every step, deferring is work on top.
    virtual void setImpulsesRead(bool read) { (void)read; }
    /// False when the last step's report carries no impulses because setImpulsesRead(false)
    /// let the backend skip them (its points then say 0); the layer's events then say
    /// hasImpulses false.
    virtual bool measuredImpulses() const { return true; }
    /// For a collision pair that touched after the step before and that reportContacts no longer
    /// lists: appends the pair (a then b, normal from a to b) with its closest points to `out`
    /// and returns true when its shapes are within `reach` of each other, depths against the
    /// true surfaces (negative: apart). The layer keeps a touching pair until its shapes are
    /// farther apart than twice linearSlop; an engine that stops listing pairs sooner (ODE:
    /// once the shapes no longer overlap; Box2D: once the skinned shapes part) answers here.
    /// The default: false (the engine lists its pairs that far apart).
    virtual bool reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) {
        (void)a, (void)b, (void)reach, (void)out;
        return false;
    }
    /// False only when no dynamic or kinematic body is awake after the last step: then no
    /// contact can begin, stay or end (each has a sleeping body), and the layer skips the step's
    /// events. True when the peer cannot tell cheaply (the default).
    virtual bool hasAwakeBodies() const { return true; }
    /// Appends the userData of every dynamic and kinematic body, awake or asleep, whose state
    /// `limits` do not admit (MotionLimits::admit on the state BodyPeer::state would return), in
    /// any order. Runs after every step: a backend reads its own arrays in place, without building
    /// a BodyState per body.
    virtual void findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const = 0;
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
