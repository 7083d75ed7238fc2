#pragma once
// The Box2D backend's world: a b2World simulating the XY plane, its bodies, the layer's contact
// rules, and the step (held forces, damping, bullets, substeps).
#include <box2d/box2d.h>

#include <array>
#include <bitset>
#include <cstdint>
#include <memory>
#include <vector>

#include "anyphys/peers/springs_per_body.hpp"
#include "anyphys/peers/world_peer.hpp"
#include "anyphys/world_settings.hpp"
#include "box2d_body.hpp"
#include "box2d_contacts.hpp"
#include "box2d_joints.hpp"
#include "box2d_triggers.hpp"

namespace anyphys::box2d {

class Box2dWorld final : public WorldPeer {
public:
    /// Defaults: Box2D 2.4's recommended 8 velocity and 3 position iterations, one Box2D step per
    /// step. The first three are published as the capabilities (the layer fills unset settings
    /// with them); positionIterations is this backend's option, read with this fallback.
    static constexpr Solver kDefaultSolver = Solver::ProjectedGaussSeidel;
    static constexpr int kDefaultIterations = 8;
    static constexpr int kDefaultSubsteps = 1;
    static constexpr int kDefaultPositionIterations = 3;
    /// Box2D 2.4 clamps every body's motion per b2World::Step to b2_maxTranslation (2 m) and
    /// b2_maxRotation (pi/2 rad), compile-time constants: at 60 Hz no body would move faster than
    /// 120 m/s or spin faster than 94.2 rad/s (a 5 mm ball could not roll past 0.47 m/s). A step
    /// whose fastest awake body would use more than kCapHeadroom of either cap is split into the
    /// fewest equal Box2D steps that keep it within kCapHeadroom (substepsFor); others step as
    /// configured, bit for bit. Half: the prediction knows the step's gravity and forces but not
    /// its contact and joint impulses, which can double a body's speed within one Box2D step
    /// (an elastic blow from a heavier body) or spin a small ball up (rolling 5/7 g sin 20 deg
    /// adds 0.13 rad per 1/60 s step to a 5 mm ball's w h, a twelfth of the cap).
    static constexpr double kCapHeadroom = 0.5;
    /// At most this many Box2D steps per step (or the configured substeps, if more): beyond it
    /// the cap applies again, at 64 times its one-step value (7 680 m/s and 6 032 rad/s at
    /// 60 Hz), so that one runaway body cannot make a step cost thousands of Box2D steps.
    static constexpr int kMaxCapSubsteps = 64;

    explicit Box2dWorld(const WorldSettings& settings);
    ~Box2dWorld() override;

    std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) override;
    void destroyBody(BodyPeer& body) override;
    std::unique_ptr<JointPeer> createJoint(const JointPeerDef& def) override;
    void destroyJoint(JointPeer& joint) override;
    void setEffects(Effects effects) override;
    void step(double time, double dt) override;
    void setMaterialTable(const MaterialTable& table) override;
    void reportContacts(ContactReport& out) override;
    void writeDeferredPoints(ContactReport& out) override;
    void setImpulsesRead(bool read) override { eventsRead_ = read; }
    /// Box2D lists a pair only while its skinned shapes overlap: the layer's exit band needs the
    /// gap beyond (nearestSurfaces, Box2D's own b2Distance).
    bool reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) override;
    bool hasAwakeBodies() const override;
    /// The Box2D steps the last step took (substepsFor's count).
    int lastStepSubsteps() const { return lastStepSubsteps_; }
    void findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const override;
    std::vector<PeerRayHit> raycast(const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly,
                                    std::uint32_t mask) override;
    std::vector<std::uint64_t> overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                       std::uint32_t mask) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for body peers ------------------------------------------------------------------
    /// A body peer destroyed without destroyBody: drop its b2Body.
    void forgetBody(Box2dBody& body);
    /// Wakes every body touching `body` (it moved, or is about to disappear).
    void wakeTouching(b2Body* body);
    /// A joint peer destroyed without destroyJoint: drop its b2Joint.
    void forgetJoint(Box2dJoint& joint);

private:
    void removeBody(Box2dBody& body);
    void removeJoint(Box2dJoint& joint);
    /// The static body that joints held to the world hang from (origin, angle 0, no fixtures),
    /// made at the first such joint.
    b2Body* ground();
    /// Contacts on or off changes which pairs pass the filter: let Box2D ask again.
    void refilterAll();
    /// The table's friction into every existing contact (after the table or the effects change).
    void reapplyMaterials();
    /// Begins every joint's step: each sprung joint with the most sprung joints on either of its
    /// moving bodies (springs on one body share its stable range: see Box2dJoint::beginStep).
    void beginJointSteps(double h);
    /// Whether the body has a sensor fixture.
    static bool hasSensor(const Box2dBody& body);
    /// Whether the body is a plane over basements (box2d_shapes.hpp).
    static bool hasBasements(const Box2dBody& body);
    /// The Box2D steps this step takes, given its bodies' largest capShare: substeps_, or more
    /// where the caps need them (see kCapHeadroom).
    int substepsFor(double worstShare) const;

    WorldSettings settings_;
    int velocityIterations_;
    int positionIterations_;
    int substeps_;
    int lastStepSubsteps_ = 0;
    bool stepStartsMarked_ = false;  // the last Box2D step marked its bodies' (Box2dBody::markStepStart)
    Effects effects_;
    ContactRules rules_;
    std::unique_ptr<b2World> world_;
    std::vector<Box2dBody*> bodies_;
    std::vector<Box2dJoint*> joints_;
    SpringsPerBody<b2Body> springsPerBody_;  // beginJointSteps'
    b2Body* ground_ = nullptr;
    TriggerPlanes triggerPlanes_;  // overlaps listed by the world, not by Box2D
    std::vector<Box2dBody*> kinematic_;  // the kinematic bodies: their triggers are the world's too
    std::size_t sensorBodies_ = 0;       // bodies with a sensor fixture
    std::vector<const b2Body*> kinematicFound_;  // scratch of reportKinematicTriggers
    std::size_t multiFixtureBodies_ = 0;  // bodies of several fixtures (contacts then merge per body pair)
    double dampingStep_ = 0.0;  // s, the Box2D step the bodies' damping rates are converted for

    /// Per contact whose manifold misses part of its step impulse (see sumImpulses), the normal
    /// impulses summed over this step's solves. Sorted by contact, so a step looks them up
    /// without allocating.
    struct SummedImpulses {
        const b2Contact* contact;
        std::array<float, b2_maxManifoldPoints> sum;
    };
    std::vector<SummedImpulses> impulses_;
    /// One bit per contact of impulses_, at filterBit(contact): a step sums a few contacts (those
    /// time of impact solved: about 70 of 14 900 in a 5 050-box pyramid) and asks about every
    /// contact; a clear bit answers without the binary search.
    std::bitset<1024> summedFilter_;
    static std::size_t filterBit(const b2Contact* contact) {
        // Fibonacci hashing: the product's top ten bits mix all of the address's bits.
        return static_cast<std::size_t>((reinterpret_cast<std::uintptr_t>(contact) * 0x9E3779B97F4A7C15ull) >> 54);
    }
    void sumImpulses();  // after the step
    /// The entry of `contact` in impulses_, or none. Inline: the report asks for every contact.
    const SummedImpulses* summedImpulses(const b2Contact* contact) const {
        return summedFilter_[filterBit(contact)] ? findSummed(contact) : nullptr;
    }
    const SummedImpulses* findSummed(const b2Contact* contact) const;  // the binary search

    /// A reported pair whose points wait until the events are read (ContactReport::Pair::
    /// pointsDeferred): a copy of what its world manifold is made of, so that the points come out
    /// as the report would have written them, whatever happens to the world in between. Working
    /// them out for every touching contact was a third of this backend's event overhead.
    struct DeferredManifold {
        b2Manifold manifold;
        b2Transform xfA, xfB;
        float radiusA, radiusB;
        std::array<float, b2_maxManifoldPoints> impulses;
        std::uint32_t pair;  // in the report
    };
    std::vector<DeferredManifold> deferred_;  // the last report's
    bool eventsRead_ = false;  // someone reads the events every step: no point is deferred
};

}  // namespace anyphys::box2d
