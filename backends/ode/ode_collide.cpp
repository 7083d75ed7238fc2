// Collision: the space's near callback turns touching geom pairs into ODE contact joints with
// the layer's resolved materials, and (when events are on) remembers them for the layer's
// contact events. Only pairs with an awake body can touch anew, so the pass visits only those:
// none at all when everything sleeps, each awake geom against the space when few are awake,
// the whole space otherwise.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "anyphys/peers/rebound_from_depth.hpp"
#include "ode_contact_completion.hpp"
#include "ode_math.hpp"
#include "ode_mesh_edges.hpp"
#include "ode_slip_friction.hpp"
#include "ode_speculative.hpp"
#include "ode_tuning.hpp"
#include "ode_world.hpp"

namespace anyphys::ode {
namespace {

// Colliding one geom against the space tests its bounds against every geom of the space (ODE's
// hash space has no faster query), where the whole-space pass hashes every geom once. Measured on
// a sleeping 1000-box pile with k boxes awake (instructions per step): the whole space 4.4 M plus
// 4 k per awake box, per awake geom 45 k each: about even at k = 100. In larger spaces the
// whole pass costs more per geom (ODE builds its hash table anew each pass), the test per geom
// about the same: timed on stacks of boxes created asleep, 20 steps, the two passes were even
// near k = 110 of 5 000 geoms, 260 of 20 000 and 400 of 50 000 (2026-12-06). So geom by geom
// below one awake in ten and below 100 + 1 in 150 of the geoms: one in ten alone let 1 500 of
// 20 000 awake geoms be collided one by one (326 ms a step, against 82 for the whole pass).
constexpr std::size_t kAwakeShareForWholeSpace = 10;  // 1 geom in 10 awake
constexpr std::size_t kAwakeAloneBase = 100, kAwakeAloneShare = 150;

// The deepest of the contacts' depths.
double deepest(const dContact* contacts, int count) {
    double depth = contacts[0].geom.depth;
    for (int i = 1; i < count; ++i) depth = std::max(depth, contacts[i].geom.depth);
    return depth;
}

int dropDegenerateContacts(dContact* contacts, int count) {
    // ODE's convex-convex test returns NaN normals for faces that touch exactly (blocks of an
    // arch built flush); one such contact makes the step's quaternions NaN and ODE aborts the
    // process. A contact without a finite point, unit normal and finite depth is dropped.
    // |n| within 1e-6 of 1, compared squared (no square root per contact). The point and depth
    // are finite when their sum is: a NaN or infinity carries into it. Finite values sum to an
    // infinity only near 1e308, far past kMaxCoordinate, where a body is already diverged.
    constexpr double kLeastSquaredNorm = (1.0 - 1e-6) * (1.0 - 1e-6), kMostSquaredNorm = (1.0 + 1e-6) * (1.0 + 1e-6);
    const auto degenerate = [&](const dContact& c) {
        const dContactGeom& g = c.geom;
        const double squaredNorm = toVec3(g.normal).squaredNorm();  // NaN fails both comparisons
        return !(std::isfinite(g.pos[0] + g.pos[1] + g.pos[2] + g.depth) && squaredNorm > kLeastSquaredNorm &&
                 squaredNorm < kMostSquaredNorm);
    };
    return static_cast<int>(std::remove_if(contacts, contacts + count, degenerate) - contacts);
}

// Whether ODE collides this pair with libccd's MPR (a hull against a box or a hull): the colliders
// the backend installs (ode_convex_sphere.hpp, ode_convex_capsule.hpp) are not. By the shapes'
// types, which name their geoms' classes (OdeShape), not by asking ODE twice per pair.
bool collidesThroughMpr(ShapeType a, ShapeType b) {
    const auto flat = [](ShapeType t) { return t == ShapeType::Box || t == ShapeType::Convex; };
    return (a == ShapeType::Convex || b == ShapeType::Convex) && flat(a) && flat(b);
}

// MPR's normal is undefined where the shapes touch without overlapping: the origin then lies on
// the Minkowski difference's surface and the portal it stops at is any face through it. A cube
// hull placed exactly on a box (depth 8e-15, rounding) got the normal (0.89, 0, -0.45): pushed at
// 5 m/s that contact struck it sideways, and it slid off its line by 0.6 m spinning at 2.7 rad/s.
// At 1e-12 m of overlap the normal is already the face's. Such a contact holds nothing yet (no
// overlap to resolve; the next step finds the overlap with its true normal), so it is dropped.
// 1 nm: far above rounding at any coordinate the layer accepts near contacts (1e-16 of 1e5 m),
// far below a resting overlap (about 1 mm).
constexpr double kLeastMprDepth = 1e-9;  // m

int dropUntouchingMprContacts(ShapeType a, ShapeType b, dContact* contacts, int count) {
    if (!collidesThroughMpr(a, b)) return count;
    const auto untouching = [](const dContact& c) { return !(c.geom.depth > kLeastMprDepth); };
    return static_cast<int>(std::remove_if(contacts, contacts + count, untouching) - contacts);
}

// Friction turns a sphere about its contact point, so the joint's point belongs on the sphere. ODE
// puts the point of a sphere against a box or a hull on the other surface, as deep inside the
// sphere as the pair overlaps, which at rest is up to the surface layer (0.2 linearSlop, 1 mm): a
// 5 mm ball rolling down a box slope turned about an arm of 4 mm and rolled 14 % slow (the inertia
// term grows as (r / (r - depth))^2). The normal runs through the centre, so the point moves along
// it to the sphere's surface (ODE's normal points into geom 1). Two spheres keep ODE's point
// between them. Only against a body that does not move (geom 2, then): against a moving one the
// point is the other body's arm too, and moved by the overlap onto the sphere it opened a pinched
// pile of ragdolls (sphere heads) from 55 mm to a median of 91 mm, up to 278. And by at most the
// surface layer, the overlap a resting ball keeps: moved through a deep overlap as well, one of
// that pile's nine draws opened 251 mm (61 to 108 mm capped; 55 to 68 unmoved).
void movePointsOntoTheSphere(dGeomID o1, dGeomID o2, dContact* contacts, int count, double most) {
    const bool first = dGeomGetClass(o1) == dSphereClass, second = dGeomGetClass(o2) == dSphereClass;
    if (first == second) return;
    const dGeomID sphere = first ? o1 : o2;
    const Vec3 centre = toVec3(dGeomGetPosition(sphere));
    const double reach = first ? -dGeomSphereGetRadius(sphere) : dGeomSphereGetRadius(sphere);
    for (int i = 0; i < count; ++i) {
        const Vec3 from = toVec3(contacts[i].geom.pos);
        Vec3 move = centre + reach * toVec3(contacts[i].geom.normal) - from;
        if (move.norm() > most) move *= most / move.norm();
        const Vec3 point = from + move;
        for (int k = 0; k < 3; ++k) contacts[i].geom.pos[k] = point[k];
    }
}

// A point of two overlapping shapes lies in both, so within both bounding boxes. ODE's box-box
// test puts its points on the reference face, which for a small box swallowed by a large one is
// the large box's face: a 0.1 m box inside a kinematic box of half extent 1e7 m got its four
// points 1e7 m away. Each friction row then turned the box about an arm of 1e7 m, and the direct
// solver's factorisation met a zero pivot, where ODE asserts and aborts the process (the api_calls
// fuzzer's input tests/fuzz/corpus/api_calls/crash-ode-direct-swallowed-box). An overlapping point is
// therefore clamped into the two boxes' intersection, grown by `margin` so that points a rounding
// outside (a resting box's, on the ground's top face) keep their bits. Only where a point is
// deeper than the margin are the bounds fetched: a resting pair's overlap is the surface layer
// (a fifth of linearSlop), and the layer's cost per pair stays as it was. Speculative points (no
// overlap) are the pair's gap apart and are left alone. `depth`: the deepest of the points'.
void keepPointsInTheOverlap(dGeomID o1, dGeomID o2, dContact* contacts, int count, double depth, double margin) {
    if (depth <= margin) return;
    dReal boundsA[6], boundsB[6];  // ODE's layout: min x, max x, min y, max y, min z, max z
    dGeomGetAABB(o1, boundsA);
    dGeomGetAABB(o2, boundsB);
    for (int i = 0; i < count; ++i) {
        if (!(contacts[i].geom.depth > 0)) continue;
        for (int k = 0; k < 3; ++k) {
            const double low = std::max(boundsA[2 * k], boundsB[2 * k]) - margin;
            const double high = std::min(boundsA[2 * k + 1], boundsB[2 * k + 1]) + margin;
            if (low <= high) contacts[i].geom.pos[k] = std::clamp(contacts[i].geom.pos[k], low, high);
        }
    }
}

}  // namespace

void OdeWorld::nearCallback(void* self, dGeomID o1, dGeomID o2) { static_cast<OdeWorld*>(self)->collidePair(o1, o2); }

void OdeWorld::awakeGeomCallback(void* self, dGeomID o1, dGeomID o2) {
    auto& world = *static_cast<OdeWorld*>(self);
    const dGeomID other = o1 == world.currentGeom_ ? o2 : o1;
    // A pair of two awake bodies is collided once: from the body that comes first.
    const OdeBody* mine = bodyOfGeom(world.currentGeom_);
    const OdeBody* theirs = bodyOfGeom(other);
    if (theirs->activeInPass && theirs->awakeRank < mine->awakeRank) return;
    world.collidePair(world.currentGeom_, other);
}

void OdeWorld::collidePair(dGeomID o1, dGeomID o2) {
    // Per geom: a compound's children may differ in material, filter and sensor flag.
    const OdeShape* shapeA = shapeOfGeom(o1);
    const OdeShape* shapeB = shapeOfGeom(o2);
    OdeBody* a = shapeA->owner();
    OdeBody* b = shapeB->owner();
    const GeomSurface* sa = &shapeA->surface();
    const GeomSurface* sb = &shapeB->surface();
    // Something must respond: a dynamic body, or a sensor and something moving.
    const bool trigger = sa->trigger || sb->trigger;
    if (trigger ? !(a->moves() || b->moves()) : !(a->isDynamic() || b->isDynamic())) return;
    if (!a->activeInPass && !b->activeInPass) return;  // asleep (or asleep on something static)
    if (!layersCollide(sa->layer, sa->mask, sb->layer, sb->mask)) return;
    if (jointExcludes(a, b)) return;  // joined by a joint with collideConnected false
    if (!collidable(shapeA->type(), shapeB->type())) return;
    // ODE's normals point into geom 1: make that a dynamic body, whose joint feedback is read.
    if (!a->isDynamic()) {
        std::swap(o1, o2);
        std::swap(a, b);
        std::swap(shapeA, shapeB);
        std::swap(sa, sb);
    }
    // Collide into a stack buffer: most candidate pairs from the broad phase have no points.
    dContact found[kMaxContactsPerPair];
    // A mesh (static: geom 2) through the backend's culling and edge correction (ode_mesh_edges.hpp).
    int n = !trigger && shapeB->type() == ShapeType::Mesh
                ? collideWithMesh(o1, o2, *shapeA, *shapeB, nearProbe_, found, kMaxContactsPerPair)
                : dCollide(o1, o2, trigger ? 1 : kMaxContactsPerPair, &found[0].geom, sizeof(dContact));
    n = dropDegenerateContacts(found, n);
    if (!trigger) n = dropUntouchingMprContacts(shapeA->type(), shapeB->type(), found, n);  // a sensor's touch is an overlap all the same
    // Apart, or barely touching (where ODE's colliders give a partial manifold: a box's face just
    // meeting a wall, one edge, on which it tipped and went 5 mm in), but closing within the step:
    // contacts that let the pair close its gap and no more (ode_speculative.hpp).
    double depth = n > 0 ? deepest(found, n) : 0.0;
    const double approach = (n == 0 || depth < 0.5 * meetingOverlap()) && !trigger
                                ? speculativeApproach(*shapeA, *shapeB, *sa, *sb)
                                : 0.0;
    const bool speculative = approach > 0.0;
    if (speculative)
        n = speculativeContacts(nearProbe_, *shapeA, *shapeB,
                                {n > 0, stepFall(*a) - stepFall(*b), approach, settings_.linearSlop, odeStep()}, found,
                                kMaxContactsPerPair);
    if (n <= 0) return;
    if (n == 1 && !trigger && !speculative) {
        n = completeOnePointContact(*shapeA, *shapeB, found, kMaxContactsPerPair);
        depth = deepest(found, n);  // the completion's points have depths of their own
    }
    if (!trigger && !speculative) keepPointsInTheOverlap(o1, o2, found, n, depth, settings_.linearSlop);
    if (effects_.has(Effect::Events)) {  // ODE's points, before the joints' sphere points
        const auto first = static_cast<std::uint32_t>(points_.size());
        if (!trigger)  // a sensor's overlap has no points
            for (int i = 0; i < n; ++i) {
                points_.push_back({toVec3(found[i].geom.pos), found[i].geom.depth, 0.0});
                normals_.push_back(toVec3(found[i].geom.normal));
            }
        pairs_.push_back({a, b, trigger, first, static_cast<std::uint32_t>(points_.size()) - first});
    }
    if (trigger) return;  // sensors never collide
    if (!b->isDynamic() && !speculative) movePointsOntoTheSphere(o1, o2, found, n, dWorldGetContactSurfaceLayer(world_));
    createContactJoints(*a, *b, materials_.get(sa->material, sb->material), found, n, speculative);
    if (!a->activeInPass || !b->activeInPass) wakeIfTouched(*a, *b);  // two awake bodies wake nothing
}

void OdeWorld::createContactJoints(const OdeBody& a, const OdeBody& b, const ContactMaterial& m, dContact* contacts,
                                   int count, bool speculative) {
    // Exactly the layer's resolved pair values (of the two geoms' materials); ODE's own mixing is never used.
    dSurfaceParameters surface{};
    if (effects_.has(Effect::Friction) && m.friction > 0) {
        // Approx1: mu scales the normal force (Coulomb), on two tangent directions.
        surface.mode |= dContactApprox1;
        surface.mu = m.friction;
    }
    // The pair's mass (kCfmReferenceMass): the heavier dynamic body's. Like the
    // reduced mass it scales with the masses; unlike it, a 1 t box on another is a pair of 1 t,
    // as the box stacks kDefaultCfm was tuned on have it.
    const double pairMass = heavierDynamicMass(&a, &b);
    // Always given, never the world's: that follows the heaviest slider or wheel (OdeWorld::step).
    // The friction rows' CFM is the world's unless a slip is given (ODE's contact joint uses slip
    // as their CFM, and the flags do nothing else): left at the world's, a 1 000 t stack walked
    // 0.87 m in 10 s.
    const double rowWeight = a.rowWeightBound() + b.rowWeightBound();
    const double cfm = conditionedCfm(pairCfm(cfm_, pairMass), lastH_, rowWeight);
    surface.mode |= dContactSoftCFM | dContactSlip1 | dContactSlip2;
    surface.soft_cfm = surface.slip1 = surface.slip2 = cfm;
    if (effects_.has(Effect::Restitution) && m.restitution > 0) {
        surface.mode |= dContactBounce;
        surface.bounce = m.restitution;
        surface.bounce_vel = settings_.restitutionThreshold;  // slower impacts do not bounce
        surface.mode |= dContactSoftCFM;  // rigid, so softness does not absorb the rebound
        surface.soft_cfm = conditionedCfm(std::min(cfm, kBounceCfm), lastH_, rowWeight);
    }
    const bool feedback = wantsFeedback();
    const Vec3 fallA = stepFall(a), fallB = stepFall(b);  // once per pair: the same for every point
    const bool bounces = (surface.mode & dContactBounce) != 0;
    for (int i = 0; i < count; ++i) {
        contacts[i].surface = surface;
        // Speculative (ode_speculative.hpp): every point closes to the meeting overlap and no more,
        // those a rounding apart as those a rounding in (a box's face found 8e-9 m in at its top
        // and 8e-9 m out at its bottom turned on its top edge).
        if (speculative && contacts[i].geom.depth < meetingOverlap()) {
            contacts[i].surface.mode |= dContactMotionN;
            contacts[i].surface.motionN = (contacts[i].geom.depth - meetingOverlap()) / odeStep();
        }
        if (surface.mode & (dContactApprox1 | dContactBounce)) {
            const Vec3 point = toVec3(contacts[i].geom.pos);
            const Vec3 velocityA = pointVelocity(a.id(), point), velocityB = pointVelocity(b.id(), point);
            if (surface.mode & dContactApprox1) alignFrictionWithSlip(contacts[i], (velocityA + fallA) - (velocityB + fallB));
            if (bounces)
                aimBounce(contacts[i], m.restitution, velocityA - velocityB,
                          (a.fall.fellLastStep() ? fallA : Vec3::Zero()) - (b.fall.fellLastStep() ? fallB : Vec3::Zero()));
        }
        const dJointID joint = dJointCreateContact(world_, contactGroup_, &contacts[i]);
        dJointAttach(joint, a.id(), b.id());
        if (feedback) joints_.push_back(joint);  // its feedback is wired once the pass is done
    }
}

// ODE bounces a contact at -bounce times its closing speed, and moves the pair with that in the
// same step, from the depth it found it at: for a step's fall of depth the rise falls short by
// that depth (reboundFromDepth). The bounce is scaled per contact to the speed that makes up for
// it, and takes no ERP push on top (ODE keeps the larger of the two targets, not their sum).
// `relative`: geom 1's body's point velocity minus geom 2's; `fall`: what the step's gravity adds
// to it, counting only bodies that fall freely (a box resting on the ground does not). Impacts
// ODE does not bounce (closing no faster than bounce_vel) keep the contact as it is.
void OdeWorld::aimBounce(dContact& contact, double e, const Vec3& relative, const Vec3& fall) const {
    const Vec3 normal = toVec3(contact.geom.normal);  // into geom 1
    const double closing = -relative.dot(normal);
    if (!(closing > contact.surface.bounce_vel)) return;
    const double h = odeStep();
    const double g = -fall.dot(normal) / h;  // fall is zero without gravity
    contact.surface.bounce = restitution::reboundFromDepth(e, closing, contact.geom.depth, g, h) / closing;
    contact.surface.mode |= dContactSoftERP;
    contact.surface.soft_erp = 0.0;
}

void OdeWorld::collide() {
    pairs_.clear();
    points_.clear();
    normals_.clear();
    fallTime_ = effects_.has(Effect::Gravity) ? odeStep() : 0.0;
    joints_.clear();
    feedbackValid_ = false;
    awakeGeoms_.clear();
    awakeBodies_ = 0;
    const Vec3 gravity = effects_.has(Effect::Gravity) ? settings_.gravity : Vec3::Zero();
    const bool bounces = effects_.has(Effect::Restitution);
    const auto dot = [](const Vec3& x, const Vec3& y) { return x.dot(y); };
    for (OdeBody* body : bodies_) {
        body->activeInPass = body->isActive();
        if (!body->activeInPass) continue;
        if (bounces && body->isDynamic())
            body->fall.note(fallNotedLastPass_, toVec3(dBodyGetLinearVel(body->id())), body->gravityScale() * gravity, lastH_, dot);
        body->awakeRank = awakeBodies_++;
        for (std::size_t i = 0; i < body->shapeCount(); ++i) awakeGeoms_.push_back(body->shape(i).geom());
    }
    fallNotedLastPass_ = bounces;
    if (awakeGeoms_.empty()) {
        lastPass_ = CollidePass::Skipped;  // every pair would be skipped as asleep
    } else if (awakeGeoms_.size() * kAwakeShareForWholeSpace < geomCount_ &&
               awakeGeoms_.size() < kAwakeAloneBase + geomCount_ / kAwakeAloneShare) {
        lastPass_ = CollidePass::PerAwakeGeom;
        for (dGeomID geom : awakeGeoms_) {
            currentGeom_ = geom;
            dSpaceCollide2(geom, reinterpret_cast<dGeomID>(space_), this, &OdeWorld::awakeGeomCallback);
        }
        currentGeom_ = nullptr;
    } else {
        lastPass_ = CollidePass::WholeSpace;
        dSpaceCollide(space_, this, &OdeWorld::nearCallback);
    }
    collideAhead();
    collideWokenBodies();
    // Joint feedback (the joints' forces) when events report impulses; wired after the pass, so
    // the array no longer moves while ODE writes into it.
    if (!wantsFeedback()) return;
    feedback_.resize(joints_.size());
    for (std::size_t i = 0; i < joints_.size(); ++i) dJointSetFeedback(joints_[i], &feedback_[i]);
    feedbackValid_ = true;
}

void OdeWorld::wakeIfTouched(OdeBody& a, OdeBody& b) {
    for (OdeBody* body : {&a, &b})
        if (body->isDynamic() && !body->activeInPass && !body->wokenInPass) {
            body->wokenInPass = true;
            wokenBodies_.push_back(body);
        }
}

// ODE wakes a sleeping body that an awake one touches in its step (the contact joins their
// islands), but the pass skipped the sleeper's other pairs as asleep: a box resting on the ground,
// asleep, had no ground under it in the step a ball landed on it, was driven 1.9 cm in and
// bounced off the ground, and the ball rose 42 % of e^2 h. So a woken body's pairs are collided in
// the same pass, as an awake body's, and so are those of any sleeping body they touch in turn (the
// queue grows as it goes). A pair with a body awake before it was collided from that body.
void OdeWorld::collideWokenBodies() {
    for (std::size_t k = 0; k < wokenBodies_.size(); ++k) {
        OdeBody* body = wokenBodies_[k];
        body->activeInPass = true;
        body->awakeRank = awakeBodies_++;
        for (std::size_t i = 0; i < body->shapeCount(); ++i) {
            currentGeom_ = body->shape(i).geom();
            dSpaceCollide2(currentGeom_, reinterpret_cast<dGeomID>(space_), this, &OdeWorld::awakeGeomCallback);
        }
    }
    currentGeom_ = nullptr;
    for (OdeBody* body : wokenBodies_) body->wokenInPass = false;
    wokenBodies_.clear();
}

bool OdeWorld::hasAwakeBodies() const {
    // Counted by the last collide pass, before the ODE step: a body asleep then can only wake
    // through a contact with an awake one. Without contacts nothing was counted.
    return !effects_.has(Effect::Contacts) || awakeBodies_ > 0;
}

void OdeWorld::findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const {
    for (const OdeBody* body : bodies_) {
        const dBodyID b = body->id();
        if (!b) continue;  // static: a geom without a body
        const dReal* q = dBodyGetQuaternion(b);
        if (!limits.admit(toVec3(dBodyGetPosition(b)), q[0] + q[1] + q[2] + q[3], toVec3(dBodyGetLinearVel(b)),
                          toVec3(dBodyGetAngularVel(b))))
            out.push_back(body->userData());
    }
}

bool OdeWorld::reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) {
    if (!effects_.has(Effect::Contacts)) return false;
    const auto& bodyA = static_cast<const OdeBody&>(a);
    const auto& bodyB = static_cast<const OdeBody&>(b);
    if (jointExcludes(&bodyA, &bodyB)) return false;
    bool found = false;
    for (std::size_t i = 0; i < bodyA.shapeCount(); ++i)
        for (std::size_t j = 0; j < bodyB.shapeCount(); ++j) {
            // The pairs collidePair would collide, sensors aside (a trigger overlap is never near).
            const OdeShape& shapeA = bodyA.shape(i);
            const OdeShape& shapeB = bodyB.shape(j);
            const GeomSurface& sa = shapeA.surface();
            const GeomSurface& sb = shapeB.surface();
            if (sa.trigger || sb.trigger || !layersCollide(sa.layer, sa.mask, sb.layer, sb.mask) ||
                !collidable(shapeA.type(), shapeB.type()))
                continue;
            dContactGeom contacts[kMaxContactsPerPair];
            const int n = nearProbe_.collide(shapeA, shapeB, reach, contacts, kMaxContactsPerPair);
            for (int k = 0; k < n; ++k) {
                // ODE's normal points into the first geom, A's; the layer's from A to B.
                if (!found) out.addPair(bodyA.userData(), bodyB.userData(), false, -toVec3(contacts[k].normal));
                found = true;
                out.addPoint({toVec3(contacts[k].pos), contacts[k].depth, 0.0});
            }
        }
    return found;
}

void OdeWorld::reportContacts(ContactReport& out) {
    // ODE reports each joint's constraint force averaged over the ODE step; over the anyphys step
    // the normal impulse is that force along the normal times dt (with substeps: the last
    // substep's force held for the whole step). The feedback array outlives the joints.
    const bool haveImpulses = feedbackValid_ && feedback_.size() == points_.size();
    // Every point in one copy (a pair skipped below leaves its points unreferenced, which the
    // layer allows), rather than one push per point: the report runs every step.
    const auto base = static_cast<std::uint32_t>(out.points.size());
    out.points.insert(out.points.end(), points_.begin(), points_.end());
    for (const PairRecord& p : pairs_) {
        const bool activeA = p.a->isActive(), activeB = p.b->isActive();  // after the step
        if (!activeA && !activeB) continue;  // both asleep: the layer keeps the pair
        const bool sleeping = (p.a->moves() && !activeA) || (p.b->moves() && !activeB);
        if (p.trigger) {
            out.addPair(p.a->userData(), p.b->userData(), true, Vec3::Zero(), sleeping);
            continue;
        }
        // ODE's normal points into body a; the layer's from A to B. The pair's points are the
        // step's, at the same place in `out` (below), its impulses filled in there.
        out.pairs.push_back({p.a->userData(), p.b->userData(), false, sleeping, false, -normals_[p.first], base + p.first, p.count});
        if (!haveImpulses) continue;
        for (std::uint32_t i = p.first; i < p.first + p.count; ++i) {
            const dReal* f = feedback_[i].f1;  // dCalcVectorDot3, inline: the report visits every point every step
            const Vec3& n = normals_[i];
            out.points[base + i].normalImpulse = std::max(0.0, f[0] * n.x() + f[1] * n.y() + f[2] * n.z()) * lastDt_;
        }
    }
    out.sleepKnown = true;
    // A body of several geoms meets another in several geom pairs: one report per body pair.
    if (multiShapeBodies_ > 0) out.mergeRepeatedPairs();
}

}  // namespace anyphys::ode
