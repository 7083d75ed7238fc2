#pragma once
// The ODE backend's world: a dWorld, one hash space holding every geom, and a joint group for
// the contacts of one ODE step. Each step, per substep: the held forces (addForce and the layer's
// step forces, BodyPeer::holdForStep), collide (contact joints with the layer's resolved
// materials; only pairs with an awake body are visited), quickstep or dWorldStep, and the
// continuous-collision clamp.
#include <ode/ode.h>

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "anyphys/peers/springs_per_body.hpp"
#include "anyphys/peers/world_peer.hpp"
#include "anyphys/world_settings.hpp"
#include "ode_ahead_sweep.hpp"
#include "ode_body.hpp"
#include "ode_direct_step.hpp"
#include "ode_joints.hpp"
#include "ode_near_pairs.hpp"

namespace anyphys::ode {

class OdeWorld final : public WorldPeer {
public:
    explicit OdeWorld(const WorldSettings& settings);
    ~OdeWorld() override;
    OdeWorld(const OdeWorld&) = delete;
    OdeWorld& operator=(const OdeWorld&) = delete;

    std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) override;
    void destroyBody(BodyPeer& body) override;
    std::unique_ptr<JointPeer> createJoint(const JointPeerDef& def) override;
    void destroyJoint(JointPeer& joint) override;
    void setEffects(Effects effects) override;
    void step(double time, double dt) override;
    void setMaterialTable(const MaterialTable& table) override;
    void reportContacts(ContactReport& out) override;
    /// ODE's colliders find only overlapping shapes: a pair a hair apart is collided again with
    /// one shape grown by `reach` (NearProbe).
    bool reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) override;
    void setImpulsesRead(bool read) override { impulsesRead_ = read; }
    bool measuredImpulses() const override { return feedbackValid_; }
    bool hasAwakeBodies() const override;
    void findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const override;
    std::vector<PeerRayHit> raycast(const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly,
                                    std::uint32_t mask) override;
    std::vector<std::uint64_t> overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                       std::uint32_t mask) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for bodies and tests ------------------------------------------------------------
    dWorldID id() const { return world_; }
    dSpaceID space() const { return space_; }
    const WorldSettings& settings() const { return settings_; }
    Effects effects() const { return effects_; }
    double erp() const { return erp_; }
    double cfm() const { return cfm_; }
    /// s, the length of one ODE step: the last one taken, else the one the settings announce.
    double odeStep() const;
    /// ODE steps taken by dWorldStep (the direct solver) and by dWorldQuickStep.
    std::uint64_t directSteps() const { return directSteps_; }
    std::uint64_t quickSteps() const { return quickSteps_; }
    /// Direct steps whose LCP gave up and that quickstep took instead (DirectStepper).
    std::uint64_t directFallbacks() const { return directFallbacks_; }
    /// How the last collide pass found its pairs (see collide()).
    enum class CollidePass { Skipped, PerAwakeGeom, WholeSpace };
    CollidePass lastCollidePass() const { return lastPass_; }
    /// Queues a body whose held forces must be fed to ODE this step.
    void queueForces(OdeBody& body);
    /// Wakes the moving bodies whose geoms touch `body`'s (after a static body moved).
    void wakeTouching(const OdeBody& body);

    /// A joint with collideConnected false joins a and b (either order): no contacts, no sweeps.
    bool jointExcludes(const OdeBody* a, const OdeBody* b) const;

private:
    // One geom pair found touching in the last ODE step (recorded for events only).
    struct PairRecord {
        OdeBody* a;            // contact normals point into a (ODE's convention for geom 1)
        OdeBody* b;
        bool trigger;
        std::uint32_t first;   // points_[first, first + count)
        std::uint32_t count;
    };

    static void nearCallback(void* self, dGeomID o1, dGeomID o2);
    static void awakeGeomCallback(void* self, dGeomID o1, dGeomID o2);
    void collidePair(dGeomID o1, dGeomID o2);
    void collide();
    /// Queues the sleeping one of a touching pair (wokenInPass).
    void wakeIfTouched(OdeBody& a, OdeBody& b);
    void collideWokenBodies();
    /// m: how far the pair of `a` (geom 1) and `b`, apart or barely touching, closes in the step
    /// if it gets speculative contacts (ode_speculative.hpp), else 0: `a` can grow, the pair does
    /// not bounce, and it closes by more than kLeastApproach and at most kMostApproach.
    double speculativeApproach(const OdeShape& a, const OdeShape& b, const GeomSurface& sa,
                               const GeomSurface& sb) const;
    /// m: how far a speculative contact lets its pair into each other. ODE's colliders give shapes
    /// that touch at depth zero a partial manifold (a box's face against a wall: one edge, on which
    /// the box tipped and went 5 mm in), so the pair meets overlapping a little: half the surface
    /// layer, which ERP does not push out (10 um on the direct solver, which has none).
    double meetingOverlap() const { return 0.5 * dWorldGetContactSurfaceLayer(world_) + 1e-5; }
    /// The pairs the broad phase leaves out because their bounds do not overlap yet, though a
    /// moving body reaches them within the step: collided (collidePair) for speculative contacts.
    void collideAhead();
    /// `speculative`: the contacts are speculativeContacts' (rows that let the pair close its gap).
    void createContactJoints(const OdeBody& a, const OdeBody& b, const ContactMaterial& m, dContact* contacts, int count,
                             bool speculative);
    void aimBounce(dContact& contact, double e, const Vec3& relative, const Vec3& fall) const;
    /// The velocity gravity adds to the body over one ODE step (m/s): with its velocity now at a
    /// point, the point's velocity at the step's end before contacts (slip-aligned friction).
    Vec3 stepFall(const OdeBody& body) const {
        // A gravityScale of 0 (ODE's gravity mode off, OdeBody) gives 0 here without asking ODE.
        return body.isDynamic() ? Vec3(body.gravityScale() * settings_.gravity * fallTime_) : Vec3::Zero();
    }
    void continuousCollision(const std::vector<Vec3>& before);
    void applyDampingStep(double h);
    /// Gives each sprung joint the count of sprung joints on the busier of its bodies
    /// (anyphys/peers/springs_per_body.hpp).
    void countSpringsPerBody();

    WorldSettings settings_;
    Effects effects_;
    MaterialTable materials_;
    dWorldID world_ = nullptr;
    dSpaceID space_ = nullptr;
    dJointGroupID contactGroup_ = nullptr;
    dGeomID ray_ = nullptr;  // reused by raycasts and continuous collision
    double erp_ = 0.2, cfm_ = 1e-5;
    bool direct_ = false;
    double lastH_ = 0.0;  // s, the ODE step the bodies' damping scales were computed for
    bool fallNotedLastPass_ = false;  // the last collide pass noted its bodies' OdeBody::fall

    std::vector<OdeBody*> bodies_;
    std::vector<OdeJoint*> userJoints_;
    SpringsPerBody<OdeBody> springsPerBody_;  // countSpringsPerBody's
    // Body pairs joined by joints with collideConnected false, and how many such joints each has.
    std::map<std::pair<const OdeBody*, const OdeBody*>, int> excludedPairs_;
    std::vector<OdeBody*> forced_;         // bodies with held forces this step
    std::vector<OdeBody*> scaledGravity_;  // dynamic bodies with gravityScale other than 0 and 1
    std::vector<OdeBody*> gyroscopic_;     // bodies whose implicit gyroscopic term this backend applies
    std::size_t multiShapeBodies_ = 0;     // bodies with more than one geom (contacts then merge per body pair)
    std::size_t geomCount_ = 0;            // geoms of every body

    // The collide pass: geoms of awake bodies (in body order), the one being collided, and
    // how many bodies were awake when it ran.
    std::vector<dGeomID> awakeGeoms_;
    std::vector<OdeBody*> wokenBodies_;  // this pass's, in the order they woke (collideWokenBodies)
    dGeomID currentGeom_ = nullptr;
    std::size_t awakeBodies_ = 0;
    CollidePass lastPass_ = CollidePass::Skipped;

    // Contacts of the last ODE step for events (recorded when events are on): the pairs; their
    // points as the report hands them on (it fills in the impulses), and beside them each point's
    // normal as ODE gave it (into body a), which the feedback is projected on; the joints, and
    // their feedback (a point's is feedback_ at the same index).
    std::vector<PairRecord> pairs_;
    std::vector<ContactPoint> points_;
    std::vector<Vec3> normals_;
    double fallTime_ = 0.0;  // s: the ODE step when gravity is on, else 0 (set by collide())
    std::vector<dJointID> joints_;
    std::vector<dJointFeedback> feedback_;
    bool feedbackValid_ = false;    // feedback_ holds the last ODE step's joint forces
    // Events report impulses: every contact joint keeps its force (ODE then copies each joint's
    // Jacobian and multiplies it out after the solve). Without them nothing is lost to the layer's
    // touching rule: ODE makes contacts only where geoms overlap, so every point touches by depth.
    // Only once someone reads them (setImpulsesRead): the feedback costs a world with events on
    // and nobody listening 1.9 % of its step (the 20-row pyramid, in instructions: a listener with
    // impulses 3.44 % over the raw program, without 1.53 %).
    bool wantsFeedback() const { return effects_.has(Effect::Events) && settings_.contactImpulses && impulsesRead_; }
    bool impulsesRead_ = false;
    double lastDt_ = 0.0;           // s, the last anyphys step (impulse = force x dt)
    std::vector<Vec3> before_;      // positions before the ODE step (continuous collision)

    std::uint64_t directSteps_ = 0, quickSteps_ = 0, directFallbacks_ = 0;
    DirectStepper directStepper_;
    NearProbe nearProbe_;  // reportNearPair's and speculativeContacts' grown shapes
    // collideAhead's shapes (every shape but sensors) and their bounds, and its sweep.
    std::vector<const OdeShape*> aheadShapes_;
    std::vector<SweptBounds> aheadBounds_;
    AheadSweep aheadSweep_;
    unsigned long randomSeed_ = 0;  // this world's stream of ODE's global generator (quickstep reorders rows)
};

}  // namespace anyphys::ode
