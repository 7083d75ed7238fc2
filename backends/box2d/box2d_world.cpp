#include "box2d_world.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "anyphys/error.hpp"
#include "anyphys/peers/resolved_settings.hpp"
#include "box2d_manifold.hpp"

namespace anyphys::box2d {
namespace {

b2BodyType bodyType(BodyType t) {
    switch (t) {
        case BodyType::Static: return b2_staticBody;
        case BodyType::Kinematic: return b2_kinematicBody;
        case BodyType::Dynamic: break;
    }
    return b2_dynamicBody;
}

}  // namespace

Box2dWorld::Box2dWorld(const WorldSettings& settings)
    : settings_(settings),
      velocityIterations_(resolvedIterations(settings)),
      positionIterations_(static_cast<int>(backendOption(settings, "positionIterations", kDefaultPositionIterations))),
      substeps_(resolvedSubsteps(settings)),
      world_(std::make_unique<b2World>(b2Vec2(0.0f, 0.0f))) {
    world_->SetContactFilter(&rules_);
    world_->SetContactListener(&rules_);
    // Forces (addForce's and the layer's step forces) are held across substeps and cleared once
    // per step (see step()).
    world_->SetAutoClearForces(false);
    rules_.setRestitutionThreshold(settings_.restitutionThreshold);
    dampingStep_ = settings_.timeStep / substeps_;
    setEffects(Effects::none());
}

Box2dWorld::~Box2dWorld() {
    // Body peers may outlive the world: they must not touch the b2World after this.
    for (Box2dBody* b : bodies_) b->detach();
    for (Box2dJoint* j : joints_) j->detach();
}

std::unique_ptr<BodyPeer> Box2dWorld::createBody(const BodyPeerDef& peerDef) {
    const BodyDef& def = peerDef.def;
    double angle = 0.0;
    const Embedding embedding = Embedding::of({def.position, def.orientation}, angle);
    const b2Transform pose(toB2(def.position), b2Rot(static_cast<float>(angle)));
    const b2Vec2 originInBody = b2MulT(pose, b2Vec2(0.0f, 0.0f));

    // Every piece first: a shape Box2D cannot take throws before anything changed.
    std::vector<Piece> pieces;
    std::vector<const PeerShape*> sources;  // per piece: the shape it came from (its surface)
    try {
        for (std::size_t i = 0; i < peerDef.shapes.size(); ++i) {
            const std::string path = def.shape.type == ShapeType::Compound
                                         ? "BodyDef.shape.shapes[" + std::to_string(i) + "]"
                                         : std::string("BodyDef.shape");
            const PeerShape& shape = peerDef.shapes[i];
            for (Piece& p : makePieces(shape, embedding.toBody(shape.local), originInBody, path)) {
                pieces.push_back(std::move(p));
                sources.push_back(&shape);
            }
        }
    } catch (const Error& e) {
        throw e.reworded(std::string(e.what()) + (def.name.empty() ? "" : " (body \"" + def.name + "\")"));
    }

    b2BodyDef bd;
    bd.type = bodyType(def.type);
    bd.position = pose.p;
    bd.angle = static_cast<float>(angle);
    bd.linearVelocity = toB2(def.linearVelocity);
    bd.angularVelocity = static_cast<float>(def.angularVelocity.z());
    bd.allowSleep = def.allowSleep;
    bd.awake = def.isAwake;
    bd.gravityScale = static_cast<float>(def.gravityScale);
    // The layer's key rides on the b2Body, which contact reports read anyway: reaching it through
    // the fixture's info and the peer cost two cache misses per contact per step.
    static_assert(sizeof(bd.userData.pointer) >= sizeof(peerDef.userData));
    bd.userData.pointer = static_cast<uintptr_t>(peerDef.userData);
    b2Body* body = world_->CreateBody(&bd);
    auto peer = std::make_unique<Box2dBody>(*this, body, peerDef, embedding);
    peer->slot = bodies_.size();
    bodies_.push_back(peer.get());

    double inner = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        Piece& piece = pieces[i];
        const PeerShape& source = *sources[i];
        inner = std::min(inner, innerRadius(piece));
        auto info = std::make_unique<FixtureInfo>(
            FixtureInfo{peer.get(), std::move(piece), source.material, source.layer, source.mask,
                        static_cast<std::uint32_t>(&source - peerDef.shapes.data())});
        b2FixtureDef fd;
        fd.shape = info->piece.collision.get();
        fd.density = 0.0f;   // mass comes from the layer (below), not from Box2D's areas
        fd.friction = 0.0f;  // friction and restitution are set per contact in pre-solve
        fd.isSensor = source.isTrigger;
        fd.userData.pointer = reinterpret_cast<uintptr_t>(info.get());
        body->CreateFixture(&fd);
        peer->addFixture(std::move(info));
    }
    peer->setInnerRadius(inner);
    // A trigger plane's edges make no Box2D contacts (TriggerPlanes): nothing of it to merge.
    if (!triggerPlanes_.addIfTriggerPlane(*peer) && pieces.size() > 1) ++multiFixtureBodies_;
    if (hasBasements(*peer)) rules_.countBasements(+1);
    if (def.type == BodyType::Kinematic) kinematic_.push_back(peer.get());
    if (hasSensor(*peer)) ++sensorBodies_;
    if (def.type == BodyType::Dynamic) {
        // The layer's mass and its moment about Z through the centre of mass (the peer frame's
        // inertia turned into the Box2D body frame), so masses agree with the 3D backends.
        const Mat3 r = embedding.rotation.toRotationMatrix();
        const Mat3 inertia = r * peerDef.mass.inertia.asDiagonal() * r.transpose();
        b2MassData md;
        md.mass = static_cast<float>(peerDef.mass.mass);
        md.center.SetZero();
        md.I = static_cast<float>(inertia(2, 2));
        body->SetMassData(&md);
    }
    peer->applyDamping(effects_.has(Effect::Damping), dampingStep_);
    return peer;
}

bool Box2dWorld::hasSensor(const Box2dBody& body) {
    for (const b2Fixture* f = body.b2()->GetFixtureList(); f; f = f->GetNext())
        if (f->IsSensor()) return true;
    return false;
}

bool Box2dWorld::hasBasements(const Box2dBody& body) {
    return std::any_of(body.fixtures().begin(), body.fixtures().end(), [](const auto& info) { return info->piece.basement; });
}

void Box2dWorld::destroyBody(BodyPeer& body) { removeBody(static_cast<Box2dBody&>(body)); }

std::unique_ptr<JointPeer> Box2dWorld::createJoint(const JointPeerDef& def) {
    auto peer = std::make_unique<Box2dJoint>(*this, def, def.bodyA ? nullptr : ground());
    peer->slot = joints_.size();
    joints_.push_back(peer.get());
    peer->enable(*world_, effects_.has(Effect::Joints));
    return peer;
}

void Box2dWorld::destroyJoint(JointPeer& joint) {
    auto& j = static_cast<Box2dJoint&>(joint);
    if (j.attached()) removeJoint(j);  // else already let go with one of its bodies
}

void Box2dWorld::forgetJoint(Box2dJoint& joint) { removeJoint(joint); }

void Box2dWorld::removeJoint(Box2dJoint& joint) {
    joint.enable(*world_, false);  // wakes both bodies
    joints_.back()->slot = joint.slot;
    joints_[joint.slot] = joints_.back();
    joints_.pop_back();
    joint.detach();
}

b2Body* Box2dWorld::ground() {
    if (!ground_) {
        b2BodyDef bd;  // static at the origin
        ground_ = world_->CreateBody(&bd);
    }
    return ground_;
}

void Box2dWorld::forgetBody(Box2dBody& body) { removeBody(body); }

void Box2dWorld::removeBody(Box2dBody& body) {
    b2Body* b = body.b2();
    wakeTouching(b);  // bodies resting on this one must not hang in the air
    // The layer destroys joints first; a body dropped without that takes its joints with it
    // (Box2D would destroy their b2Joints behind the peers' backs).
    for (std::size_t i = joints_.size(); i-- > 0;)
        if (joints_[i]->holds(body)) removeJoint(*joints_[i]);
    for (b2ContactEdge* e = b->GetContactList(); e; e = e->next)
        if (const SummedImpulses* sum = summedImpulses(e->contact))
            impulses_.erase(impulses_.begin() + (sum - impulses_.data()));
    world_->DestroyBody(b);
    if (!triggerPlanes_.remove(body) && body.fixtures().size() > 1) --multiFixtureBodies_;
    if (hasBasements(body)) rules_.countBasements(-1);
    std::erase(kinematic_, &body);
    if (hasSensor(body)) --sensorBodies_;
    bodies_.back()->slot = body.slot;
    bodies_[body.slot] = bodies_.back();
    bodies_.pop_back();
    body.detach();
}

void Box2dWorld::wakeTouching(b2Body* body) {
    for (b2ContactEdge* e = body->GetContactList(); e; e = e->next)
        if (e->contact->IsTouching()) e->other->SetAwake(true);
}

void Box2dWorld::refilterAll() {
    for (b2Body* b = world_->GetBodyList(); b; b = b->GetNext())
        for (b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) f->Refilter();
}

void Box2dWorld::setEffects(Effects effects) {
    const bool contactsChanged = effects.has(Effect::Contacts) != effects_.has(Effect::Contacts);
    effects_ = effects;
    rules_.setEffects(effects);
    world_->SetGravity(effects.has(Effect::Gravity) ? toB2(settings_.gravity) : b2Vec2(0.0f, 0.0f));
    world_->SetAllowSleeping(effects.has(Effect::Sleeping));
    world_->SetContinuousPhysics(effects.has(Effect::ContinuousCollision) && effects.has(Effect::Contacts));
    for (Box2dBody* b : bodies_) {
        b->applyDamping(effects.has(Effect::Damping), dampingStep_);
        if (!effects.has(Effect::ContinuousCollision)) b->updateBullet(false, dampingStep_);
    }
    if (contactsChanged) refilterAll();
    reapplyMaterials();
    for (Box2dJoint* j : joints_) j->enable(*world_, effects.has(Effect::Joints));
}

void Box2dWorld::reapplyMaterials() {
    for (b2Contact* c = world_->GetContactList(); c; c = c->GetNext()) rules_.applyMaterial(c);
}

void Box2dWorld::setMaterialTable(const MaterialTable& table) {
    rules_.setMaterials(table);
    reapplyMaterials();
}

namespace {

// The larger fraction of Box2D's per-step caps that one Box2D step of dt would use for this body,
// if Box2D moves it (awake, dynamic or kinematic: Box2D clamps both): its speed and spin now plus
// what the step's gravity and held forces add by its end (after its flushForces; bounds by the
// triangle inequality; damping ignored, it only slows). Contact and joint impulses are not known
// before the solve: the headroom covers them (kCapHeadroom). A non-finite velocity is the layer's
// to catch (findUnsound): left out here (a NaN fails every comparison, so the caller's std::max
// keeps the other). Inline: it runs for every body every step.
[[gnu::always_inline]] inline double capShare(const Box2dBody& body, const b2Vec2& gravity, double dt) {
    const b2Body& b = *body.b2();
    if (b.GetType() == b2_staticBody || !b.IsAwake()) return 0.0;
    const b2Vec2 v = b.GetLinearVelocity();
    double speed = std::sqrt(static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y);
    double spin = std::abs(static_cast<double>(b.GetAngularVelocity()));
    if (b.GetType() == b2_dynamicBody) {
        const double m = b.GetMass(), inertia = b.GetInertia();  // centre of mass at the origin (createBody)
        const b2Vec2 f = body.stepForce();
        const double ax = gravity.x * b.GetGravityScale() + (m > 0.0 ? f.x / m : 0.0);
        const double ay = gravity.y * b.GetGravityScale() + (m > 0.0 ? f.y / m : 0.0);
        speed += dt * std::sqrt(ax * ax + ay * ay);
        if (inertia > 0.0) spin += dt * std::abs(static_cast<double>(body.stepTorque())) / inertia;
    }
    return std::max(speed * dt / b2_maxTranslation, spin * dt / b2_maxRotation);
}

// Speeds and spins a body may have and still be passed over by the caps' check: step only needs
// capShare above `limit` (at most that, substepsFor keeps the configured substeps). Below these,
// with no held force or torque this step, capShare is at most 0.99 of the limit (the 1 % covers
// rounding), so the square roots and divisions are left to the few bodies near the caps.
struct WellInsideCaps {
    double speed;  // m/s, for the body's velocity once its fall this step is taken off
    double spin;   // rad/s
    double fall;   // m/s, dt |g|: what gravity adds over the step (times the gravity scale)

    WellInsideCaps(double limit, const b2Vec2& gravity, double dt)
        : speed(0.99 * limit * b2_maxTranslation / dt),
          spin(0.99 * limit * b2_maxRotation / dt),
          fall(dt * std::hypot(static_cast<double>(gravity.x), static_cast<double>(gravity.y))) {}

    [[gnu::always_inline]] bool holds(const Box2dBody& body) const {
        if (body.stepTorque() != 0.0f || body.stepForce().x != 0.0f || body.stepForce().y != 0.0f) return false;
        const b2Body& b = *body.b2();
        const b2Vec2 v = b.GetLinearVelocity();
        const double room = speed - fall * std::abs(static_cast<double>(b.GetGravityScale()));
        const double v2 = static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y;
        return room > 0.0 && v2 <= room * room && std::abs(static_cast<double>(b.GetAngularVelocity())) <= spin;
    }
};

}  // namespace

void Box2dWorld::step(double /*time: forces come evaluated from the layer*/, double dt) {
    const bool userForces = effects_.has(Effect::UserForces);
    const bool continuous = effects_.has(Effect::ContinuousCollision) && effects_.has(Effect::Contacts);
    // One pass over the bodies: forces flushed, then each body's share of the caps (after its
    // forces: they are part of its motion) and its bullet flag for the configured Box2D step.
    const b2Vec2 gravity = world_->GetGravity();
    const double configuredStep = dt / substeps_;
    double worst = 0.0;
    const WellInsideCaps inside(substeps_ * kCapHeadroom, gravity, dt);
    for (Box2dBody* b : bodies_) {
        b->flushForces(userForces);
        if (!inside.holds(*b)) worst = std::max(worst, capShare(*b, gravity, dt));
        b->updateBullet(continuous, configuredStep);
    }
    // Below the caps this is substeps_, and the step is what it was without them, bit for bit.
    const int substeps = substepsFor(worst);
    lastStepSubsteps_ = substeps;
    const double h = dt / substeps;
    if (h != dampingStep_) {  // Box2D's damping factor depends on the step: convert again
        dampingStep_ = h;
        for (Box2dBody* b : bodies_) b->applyDamping(effects_.has(Effect::Damping), h);
    }
    if (substeps != substeps_)  // split for the caps: bullets by the shorter step
        for (Box2dBody* b : bodies_) b->updateBullet(continuous, h);
    // Split or not, the layer sees one step: forces held over every Box2D step (flushForces),
    // contacts reported once after the last, impulses and joint reactions summed over all of
    // them, restitution aimed per Box2D step (markStepStart), joint springs set for h.
    rules_.clearSolvedImpulses(substeps > 1);
    beginJointSteps(h);
    for (int i = 0; i < substeps; ++i) {
        rules_.beginStep(static_cast<float>(h), world_->GetGravity());
        // Soft springs' pulls first: the step start's velocities include them (markStepStart).
        for (Box2dJoint* j : joints_) j->beforeSubstep(h);
        const bool bounces = effects_.has(Effect::Restitution);
        if (bounces)
            for (Box2dBody* b : bodies_) b->markStepStart(stepStartsMarked_, world_->GetGravity(), static_cast<float>(h));
        stepStartsMarked_ = bounces;
        world_->Step(static_cast<float>(h), velocityIterations_, positionIterations_);
        for (Box2dJoint* j : joints_) j->afterSubstep();
    }
    world_->ClearForces();
    for (Box2dJoint* j : joints_) j->endStep(dt);
    sumImpulses();
}

int Box2dWorld::substepsFor(double worstShare) const {
    const int most = std::max(substeps_, kMaxCapSubsteps);
    const double needed = worstShare / kCapHeadroom;  // Box2D steps of dt / needed keep the worst at the headroom
    if (needed <= substeps_) return substeps_;
    if (!(needed < most)) return most;  // also infinity
    return static_cast<int>(std::ceil(needed));
}

void Box2dWorld::beginJointSteps(double h) {
    springsPerBody_.clear();
    for (const Box2dJoint* j : joints_)
        if (j->sprung())
            for (const b2Body* b : {static_cast<const b2Body*>(j->bodyA()), static_cast<const b2Body*>(j->bodyB())})
                if (b->GetType() == b2_dynamicBody) springsPerBody_.add(b);  // not static or kinematic
    springsPerBody_.sort();
    for (Box2dJoint* j : joints_) j->beginStep(h, j->sprung() ? springsPerBody_.onBusierBody(j->bodyA(), j->bodyB()) : 1);
}

namespace {
/// The entry of `contact` in sums sorted by contact, or nullptr.
template <class Sums>
auto findSum(Sums& sums, const b2Contact* contact) -> decltype(sums.data()) {
    const auto it = std::lower_bound(sums.begin(), sums.end(), contact,
                                     [](const auto& s, const b2Contact* c) { return std::less<const b2Contact*>{}(s.contact, c); });
    return it != sums.end() && it->contact == contact ? &*it : nullptr;
}
}  // namespace

// The step's impulse per contact point is the sum over every solve of the step: each substep's
// main solve and any time-of-impact solve. Most steps solve each contact once, in the main solve,
// which leaves those impulses in the manifold: only the contacts whose manifold misses some (all
// of them with substeps) get a sum here, in the order of the solves.
void Box2dWorld::sumImpulses() {
    std::vector<ContactRules::SolvedImpulses>& solved = rules_.solvedImpulses();
    impulses_.clear();
    for (std::size_t k = rules_.firstSummedEntry(); k < solved.size(); ++k) impulses_.push_back(SummedImpulses{solved[k].contact, {}});
    const auto byContact = [](const SummedImpulses& x, const SummedImpulses& y) { return std::less<const b2Contact*>{}(x.contact, y.contact); };
    std::sort(impulses_.begin(), impulses_.end(), byContact);
    impulses_.erase(std::unique(impulses_.begin(), impulses_.end(), [](const auto& x, const auto& y) { return x.contact == y.contact; }),
                    impulses_.end());
    summedFilter_.reset();
    for (const SummedImpulses& s : impulses_) summedFilter_.set(filterBit(s.contact));
    if (!impulses_.empty())
        for (const ContactRules::SolvedImpulses& s : solved)
            if (SummedImpulses* summed = summedFilter_[filterBit(s.contact)] ? findSum(impulses_, s.contact) : nullptr)
                for (std::size_t p = 0; p < summed->sum.size(); ++p) summed->sum[p] += s.normal[p];
    solved.clear();
}

const Box2dWorld::SummedImpulses* Box2dWorld::findSummed(const b2Contact* contact) const { return findSum(impulses_, contact); }

bool Box2dWorld::hasAwakeBodies() const {
    if (!effects_.has(Effect::Contacts)) return true;
    return std::any_of(bodies_.begin(), bodies_.end(), [](const Box2dBody* b) { return b->b2()->IsAwake(); });
}

// In Box2D's floats, widened exactly: the same verdicts as on Box2dBody::state, whose orientation
// is finite exactly when the angle is.
void Box2dWorld::findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const {
    for (const Box2dBody* body : bodies_) {
        const b2Body& b = *body->b2();
        if (b.GetType() == b2_staticBody) continue;
        const b2Vec2 p = b.GetPosition(), v = b.GetLinearVelocity();
        if (!limits.admit(Vec3(p.x, p.y, body->embedding().height), b.GetAngle(), Vec3(v.x, v.y, 0.0),
                          Vec3(0.0, 0.0, b.GetAngularVelocity())))
            out.push_back(body->userData());
    }
}

namespace {

// Point p of a world manifold as the layer reports it. Box2D's separations are of the skinned
// fixtures: the true surfaces are kPairSkin further apart.
[[gnu::always_inline]] inline ContactPoint reportedPoint(const WorldManifold& wm, int32 p, float impulse) {
    return {fromB2(wm.points[p]), -(wm.separations[p] + kPairSkin), impulse};
}

bool severalFixtures(const b2Body& body) { return body.GetFixtureList() && body.GetFixtureList()->GetNext(); }

// Whether the bodies of touching contact `c` also touch through another of their fixture pairs.
// Walks the contact list of a body of one fixture, else of a moving body: a ground's is long.
bool touchesTwice(const b2Contact& c) {
    const b2Body* a = c.GetFixtureA()->GetBody();
    const b2Body* b = c.GetFixtureB()->GetBody();
    const bool severalA = severalFixtures(*a), severalB = severalFixtures(*b);
    if (!severalA && !severalB) return false;
    const bool walkA = severalA != severalB ? !severalA : a->GetType() != b2_staticBody;
    const b2Body* walked = walkA ? a : b;
    const b2Body* partner = walkA ? b : a;
    for (const b2ContactEdge* e = const_cast<b2Body*>(walked)->GetContactList(); e; e = e->next)
        if (e->other == partner && e->contact != &c && e->contact->IsTouching() && e->contact->IsEnabled()) return true;
    return false;
}

}  // namespace

void Box2dWorld::reportContacts(ContactReport& out) {
    const auto asleep = [](const b2Body* b) { return b->GetType() != b2_staticBody && !b->IsAwake(); };
    bool repeats = false;
    deferred_.clear();
    std::uint32_t deferredPoints = 0;
    for (b2Contact* c = world_->GetContactList(); c; c = c->GetNext()) {
        if (!c->IsTouching() || !c->IsEnabled()) continue;  // disabled: a basement's, its edge holding the piece
        const b2Fixture *fa = c->GetFixtureA(), *fb = c->GetFixtureB();
        const b2Body *ba = fa->GetBody(), *bb = fb->GetBody();
        if (!ba->IsAwake() && !bb->IsAwake()) continue;  // asleep: the layer keeps the pair
        if (multiFixtureBodies_ > 0 && !repeats) repeats = touchesTwice(*c);
        const std::uint64_t a = bodyKey(ba), b = bodyKey(bb);
        const bool sleeping = asleep(ba) || asleep(bb);
        if (fa->IsSensor() || fb->IsSensor()) {  // a trigger overlap has no points
            out.addPair(a, b, true, Vec3::Zero(), sleeping);
            continue;
        }
        const b2Manifold& m = *c->GetManifold();
        const b2Transform &xfA = ba->GetTransform(), &xfB = bb->GetTransform();
        const float radiusA = fa->GetShape()->m_radius, radiusB = fb->GetShape()->m_radius;
        // None: the manifold holds the step's impulses, or the contact was not solved (asleep).
        const SummedImpulses* summed = summedImpulses(c);
        std::array<float, b2_maxManifoldPoints> impulses{};
        bool pushed = false;
        for (int32 p = 0; p < m.pointCount; ++p) {
            const auto k = static_cast<std::size_t>(p);
            impulses[k] = summed ? summed->sum[k] : m.points[p].normalImpulse;
            pushed = pushed || impulses[k] > 0.0f;
        }
        // Box2D's normal points from fixture A to B.
        if (pushed && !eventsRead_ && m.type != b2Manifold::e_circles) {  // touches: its points wait (the normal is cheap)
            out.addPair(a, b, false, fromB2(faceNormal(m, xfA, xfB)), sleeping);
            ContactReport::Pair& pair = out.pairs.back();
            pair.pointsDeferred = true;
            pair.firstPoint = deferredPoints;  // within the deferred block, placed below
            pair.pointCount = static_cast<std::uint32_t>(m.pointCount);
            deferredPoints += pair.pointCount;
            deferred_.push_back({m, xfA, xfB, radiusA, radiusB, impulses, static_cast<std::uint32_t>(out.pairs.size() - 1)});
            continue;
        }
        const WorldManifold wm = worldManifold(m, xfA, radiusA, xfB, radiusB);
        out.addPair(a, b, false, fromB2(wm.normal), sleeping);
        for (int32 p = 0; p < m.pointCount; ++p)
            out.addPoint(reportedPoint(wm, p, impulses[static_cast<std::size_t>(p)]));
    }
    // The deferred pairs' points follow the others', as room the layer's later additions pass.
    if (!deferred_.empty()) {
        const auto base = static_cast<std::uint32_t>(out.points.size());
        for (const DeferredManifold& d : deferred_) out.pairs[d.pair].firstPoint += base;
        out.points.resize(base + deferredPoints);
        out.pointsDeferred = true;
    }
    triggerPlanes_.report(bodies_, effects_, out);
    // Box2D makes contacts only where a body is dynamic (box2d_triggers.hpp).
    if (sensorBodies_ > 0 && !kinematic_.empty()) reportKinematicTriggers(kinematic_, *world_, effects_, out, kinematicFound_);
    out.sleepKnown = true;
    // Box2D keeps one contact per fixture pair; the layer wants one per body pair (a capsule has
    // three fixtures, a plane a run of edges): merged, the first contact's body order and normal
    // leading. Only when some body pair touches twice: a plane ground under every pile would
    // otherwise sort the whole report every step.
    if (repeats) {
        if (out.pointsDeferred) {  // the merge moves points
            writeDeferredPoints(out);
            out.pointsDeferred = false;
        }
        out.mergeRepeatedPairs();
    } else if (multiFixtureBodies_ > 0) {
        out.keepRoomToMerge();  // a later step's first merge then allocates nothing
    }
}

void Box2dWorld::writeDeferredPoints(ContactReport& out) {
    for (const DeferredManifold& d : deferred_) {
        const WorldManifold wm = worldManifold(d.manifold, d.xfA, d.radiusA, d.xfB, d.radiusB);
        ContactPoint* points = out.points.data() + out.pairs[d.pair].firstPoint;
        for (int32 p = 0; p < d.manifold.pointCount; ++p) points[p] = reportedPoint(wm, p, d.impulses[static_cast<std::size_t>(p)]);
    }
}

bool Box2dWorld::reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) {
    if (!effects_.has(Effect::Contacts)) return false;
    const Box2dBody& bodyA = static_cast<const Box2dBody&>(a);
    const Box2dBody& bodyB = static_cast<const Box2dBody&>(b);
    b2Vec2 normal, point;
    double gap = 0.0;
    if (!nearestSurfaces(*bodyA.b2(), *bodyB.b2(), reach, normal, point, gap)) return false;
    out.addPair(bodyA.userData(), bodyB.userData(), false, fromB2(normal));
    out.addPoint({fromB2(point), -gap, 0.0});
    return true;
}

void* Box2dWorld::nativeObject(const std::type_info& pointerType) {
    return pointerType == typeid(b2World*) ? static_cast<void*>(world_.get()) : nullptr;
}

}  // namespace anyphys::box2d
