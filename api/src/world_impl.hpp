#pragma once
// World internals shared by world.cpp and body.cpp.
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "anyphys/fields/field_forces.hpp"
#include "anyphys/fields/particles.hpp"
#include "anyphys/listeners/contact_tracker.hpp"
#include "anyphys/peers/backend.hpp"
#include "anyphys/thread_pool.hpp"
#include "anyphys/world.hpp"

namespace anyphys {

namespace detail {

/// "a, b, c": the names an error message lists (missing capabilities, a library's materials).
inline std::string commaList(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
    return out;
}

/// One evaluation of the forces the layer computes (buoyancy, drag and wind, then the game's
/// callback), as World::evaluateForces sees it. On a ForceEvaluation::PerStage backend it is the
/// backend's ForceStage (intermediate states, forces straight to the stage); on a PerStep backend
/// it is the layer's own evaluation at the step's start (world.cpp, StepStartForces), which sums
/// forces per body slot and hands each body its total once (BodyPeer::holdForStep).
class ForceSink {
public:
    virtual ~ForceSink() = default;
    virtual double time() const = 0;  ///< s, the time of this evaluation
    virtual BodyState state(const BodyPeer& peer) const = 0;  ///< peer frame
    /// `peer` is the body's peer, `slot` its index in the world's slot table.
    virtual void addForce(std::uint32_t slot, BodyPeer& peer, const Vec3& force) = 0;
    virtual void addTorque(std::uint32_t slot, BodyPeer& peer, const Vec3& torque) = 0;
};

/// A body's share of the layer's per-step force evaluation, summed in call order.
struct HeldForce {
    Vec3 force = Vec3::Zero();
    Vec3 torque = Vec3::Zero();
    bool touched = false;  // listed in Impl::heldSlots
};

/// The peer's hits of a ray whose direction is a unit vector, started a little behind its origin
/// (world.cpp's rayStartBehind: a surface through the origin then means the same on every
/// backend), with the distances measured from the origin again.
std::vector<PeerRayHit> castFromOrigin(WorldPeer& peer, const Vec3& origin, const Vec3& direction, double maxDistance,
                                       bool closestOnly, std::uint32_t mask);

}  // namespace detail

struct World::Slot {
    std::unique_ptr<BodyPeer> peer;  // null while the slot is free
    std::uint32_t generation = 1;    // bumped on destroy, so stale ids never match
    BodyDef def;                     // as created (validated, orientation normalised)
    MassProperties mass;
    Transform peerFrame;             // the peer's frame (centre of mass, principal axes) in the body frame
    std::vector<std::uint32_t> joints;  // slots of the live joints holding this body
    std::unique_ptr<FieldBody> fieldBody;  // built on the first field evaluation (world_fields.cpp)
    Transform checkedPose;           // peer pose at the last divergence check that found it sound (or as set)
    bool frozen = false;             // diverged under the freeze policy: held at checkedPose after every step
    Vec3 particleForce = Vec3::Zero();  // what fluids and cloths did to it in the last step (world_particles.cpp)

    /// The body's geometry as the fields see it, built on first use (world_fields.cpp).
    const FieldBody& fieldGeometry();

    /// The user's view (body origin) of the peer's state (centre of mass frame).
    BodyState userState() const;
    /// The peer pose for a user pose of the body origin.
    Transform peerPose(const Vec3& position, const Quat& orientation) const {
        return {position + orientation * peerFrame.position, orientation * peerFrame.orientation};
    }
};

inline BodyState World::Slot::userState() const {
    BodyState s = peer->state();
    s.orientation = (s.orientation * peerFrame.orientation.conjugate()).normalized();
    s.position -= s.orientation * peerFrame.position;
    return s;
}

/// One joint. A live joint without a peer is broken, or was never simulated (lenient policy,
/// type missing on the backend).
struct World::JointSlot {
    std::unique_ptr<JointPeer> peer;
    std::uint32_t generation = 1;    // bumped on destroy, so stale ids never match
    bool live = false;
    bool broken = false;
    JointDef def;                    // as created (normalised), with the motor, limits and spring last set
    JointType peerType = JointType::Ball;  // what the backend runs (a planar ball: a hinge)
    // The joint frame fixed in each body's peer frame (A's in the world when A is the world), as
    // the peer received them: debug drawing places them with the bodies' poses.
    Transform frameA;
    Transform frameB;
    // Thresholds the layer watches: the def's when the backend reports reactions for them
    // (capabilities), else infinite.
    double breakForce = std::numeric_limits<double>::infinity();
    double breakTorque = std::numeric_limits<double>::infinity();
    bool breakable() const { return breakForce < std::numeric_limits<double>::infinity() ||
                                    breakTorque < std::numeric_limits<double>::infinity(); }
};

/// A collision pair that touched ends once its shapes are farther apart than this many
/// linearSlops; it begins when they are closer than one. The band between keeps a gap that
/// wanders about linearSlop (a resting Box2D pile's side contacts sit there) from blinking.
inline constexpr double kExitSlops = 2.0;

/// The key a peer echoes back for a body: its id packed in 64 bits.
inline std::uint64_t packId(BodyId id) { return (std::uint64_t(id.index) << 32) | id.generation; }
inline BodyId unpackId(std::uint64_t key) { return BodyId{std::uint32_t(key >> 32), std::uint32_t(key)}; }
inline std::uint64_t packId(JointId id) { return (std::uint64_t(id.index) << 32) | id.generation; }

struct World::Impl {
    const Backend* backend = nullptr;
    std::unique_ptr<ThreadPool> pool;  // the world's own workers (settings.workers > 1, no taskSystem); outlives the peer
    std::unique_ptr<WorldPeer> peer;  // declared before slots: body peers die first
    std::vector<Slot> slots;
    std::vector<std::uint32_t> freeSlots;
    std::size_t liveBodies = 0;
    std::vector<JointSlot> joints;    // after slots: joint peers die before body peers
    std::vector<std::uint32_t> freeJoints;
    std::size_t liveJoints = 0;
    std::size_t simulatedJoints = 0;  // live joints with a peer: the joints effect
    std::vector<std::uint32_t> breakableJoints;  // slots whose reactions are watched after each step
    std::vector<JointEvent> lastJointEvents;

    // Content counters from which effects are derived without scanning the bodies.
    std::size_t gravityBodies = 0;
    std::size_t dampedBodies = 0;
    std::size_t gyroscopicBodies = 0;
    std::size_t dynamicBodies = 0;
    std::size_t movingBodies = 0;    // dynamic or kinematic
    std::size_t triggerBodies = 0;
    std::size_t sleepyBodies = 0;    // dynamic bodies allowed to sleep
    std::map<ShapeType, std::size_t> shapeBodies;  // bodies having a primitive shape of each type
    bool forcesUsed = false;

    // Materials: index per name (row of the table the peer holds) and whether any pair mixes to
    // a non-zero friction or restitution (else those effects are never derived).
    std::map<std::string, std::uint32_t, std::less<>> materialIndex;
    bool anyFriction = false;
    bool anyRestitution = false;

    // Events: buffers reused every step, so a steady step allocates nothing.
    ContactReport contacts;                  // what the peer reported after the last step
    std::vector<TouchingRange> touching;     // the pairs of it that touch
    std::vector<ContactEvent> lastEvents;   // written from the tracker's diff when first read
    bool eventsUnwritten = false;            // the last diff is not in lastEvents yet
    bool eventsRead = false;                 // lastEvents() was called: write every step from now on
    ContactTracker::AsleepQuery asleep;      // a body is asleep (for pairs the peer did not flag)
    ContactTracker::NearQuery stillTouching; // a pair no longer touching by the rule is within the exit band
    bool eventImpulses = false;              // the step's events carry impulses (dispatchEvents)
    bool impulsesCleared = false;            // settings.contactImpulses false: the points carry none
    // The step's listed collision pairs that do not touch but lie within the exit band, by body
    // pair (packed ids, lower first), for stillTouching.
    struct NearListed {
        std::uint64_t low, high;
        std::uint32_t pair;  // into contacts.pairs
        auto operator<=>(const NearListed&) const = default;
    };
    std::vector<NearListed> nearListed;
    std::vector<ContactListener*> listenersNow;  // the listeners one dispatch delivers to
    int dispatching = 0;                     // listener callbacks running (a callback may step)
    std::vector<std::vector<ContactEvent>> retiredEvents;  // events a callback's step replaced mid-dispatch

    /// The points the peer deferred (ContactReport::pointsDeferred), written before any is read.
    void writeDeferredPoints() {
        if (!contacts.pointsDeferred) return;
        contacts.pointsDeferred = false;
        peer->writeDeferredPoints(contacts);
        if (!impulsesCleared) return;
        for (const ContactReport::Pair& c : contacts.pairs)
            if (c.pointsDeferred)
                for (std::uint32_t k = c.firstPoint; k < c.firstPoint + c.pointCount; ++k) contacts.points[k].normalImpulse = 0.0;
    }

    /// The last step's events. Until someone reads events, a step only diffs the touching pairs;
    /// the events (a copy of every staying pair's points) are written here, the first time a
    /// listener or World::lastEvents reads them, from the report and pairs the step kept. Once
    /// World::lastEvents has been called, every step writes them (the reference it returned
    /// follows every step).
    std::vector<ContactEvent>& writtenEvents() {
        if (eventsUnwritten) {
            writeDeferredPoints();
            tracker.writeEvents(touching, contacts.points, lastEvents);
            eventsUnwritten = false;
        }
        return lastEvents;
    }

    ForceCallback forceCallback;
    // PerStep backends: the layer evaluates the fields and the callback itself before each step
    // (World::holdStepForces) while this is set, and the peer runs it while `peerEffects` has
    // userForces (the peer's effects: activeEffects_ plus userForces while fields push).
    bool layerForces = false;
    Effects peerEffects;
    std::vector<detail::HeldForce> heldForces;  // by slot, zero between steps; grows with the slots
    std::vector<std::uint32_t> heldSlots;       // slots with a held force this step, in first-touch order
    std::vector<FieldDef> fields;  // World::addField, in order
    Effects fieldEffects;          // the effects of the fields held
    std::vector<FluidDef> fluidDefs;                    // World::addFluid, in order
    std::vector<std::unique_ptr<FluidSystem>> fluids;
    std::vector<ClothDef> clothDefs;                    // World::addCloth, in order
    std::vector<std::unique_ptr<ClothSystem>> cloths;
    Effects particleEffects;                            // fluid and cloth, while any is held
    std::vector<ParticleCollider> colliders;            // reused by every particle step
    std::vector<std::uint32_t> colliderSlots;
    std::vector<ContactListener*> listeners;
    ContactTracker tracker;
    WarningHandler warningHandler;
    std::set<std::string> warned;
    std::vector<std::string> warningLog;     // World::warnings(), in order
    std::vector<DivergedBody> lastDiverged;  // what the last step's divergence check found
    std::vector<std::uint64_t> unsound;      // the divergence check's scratch: keys the peer found unsound
    bool divergedUnresolved = false;         // the last step threw Diverged: lastDiverged not yet set right
    std::vector<std::uint32_t> frozenSlots;  // slots held still under the freeze policy
    bool stepping = false;  // inside a step: structural changes are refused
    bool drawing = false;   // inside World::debugDraw: a drawer may read, not change the world

    /// Throws when called from a DebugDraw callback: `operation` would change what is being drawn.
    void refuseWhileDrawing(const char* operation) const {
        if (drawing)
            throw Error(ErrorKind::InvalidState, "",
                        std::string(operation) + ": not allowed inside World::debugDraw (a DebugDraw callback)");
    }
    void refuseWhileStepping(const char* operation, const char* what = " (inside a force callback)") const {
        if (stepping)
            throw Error(ErrorKind::InvalidState, "",
                        std::string(operation) + ": not allowed while the world is stepping" + what);
    }
};

}  // namespace anyphys
