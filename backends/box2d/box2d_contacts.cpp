#include "box2d_contacts.hpp"

#include <algorithm>

#include <box2d/b2_distance.h>

#include "anyphys/defs.hpp"
#include "box2d_body.hpp"
#include "box2d_convert.hpp"

namespace anyphys::box2d {

namespace {
const FixtureInfo& fixtureInfo(const b2Fixture* fixture) {
    return *reinterpret_cast<const FixtureInfo*>(const_cast<b2Fixture*>(fixture)->GetUserData().pointer);
}
}  // namespace

Box2dBody& bodyOf(const b2Fixture* fixture) { return *fixtureInfo(fixture).body; }

// Filter and materials are per fixture: a compound's children may carry their own.


bool fixturesCollide(const b2Fixture* fixtureA, const b2Fixture* fixtureB) {
    const FixtureInfo& a = fixtureInfo(fixtureA);
    const FixtureInfo& b = fixtureInfo(fixtureB);
    return layersCollide(a.layer, a.mask, b.layer, b.mask);
}

bool ContactRules::ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB) {
    if (!effects_.has(Effect::Contacts)) return false;  // contacts off: nothing touches
    return fixturesCollide(fixtureA, fixtureB);
}

bool nearestSurfaces(const b2Body& a, const b2Body& b, double reach, b2Vec2& normal, b2Vec2& point, double& gap) {
    gap = reach;
    bool found = false;
    for (const b2Fixture* fa = a.GetFixtureList(); fa; fa = fa->GetNext())
        for (const b2Fixture* fb = b.GetFixtureList(); fb; fb = fb->GetNext()) {
            if (fa->IsSensor() || fb->IsSensor() || !fixturesCollide(fa, fb)) continue;
            const b2Shape* sa = fa->GetShape();
            const b2Shape* sb = fb->GetShape();
            for (int32 ca = 0; ca < sa->GetChildCount(); ++ca)
                for (int32 cb = 0; cb < sb->GetChildCount(); ++cb) {
                    // Between the cores (no radii): their closest points give the normal even
                    // where the rounded shapes would touch.
                    b2DistanceInput in;
                    in.proxyA.Set(sa, ca);
                    in.proxyB.Set(sb, cb);
                    in.transformA = a.GetTransform();
                    in.transformB = b.GetTransform();
                    in.useRadii = false;
                    b2SimplexCache cache;
                    cache.count = 0;
                    b2DistanceOutput out;
                    b2Distance(&out, &cache, &in);
                    if (out.distance <= b2_epsilon) continue;  // cores overlap: Box2D lists such a pair
                    // Each true surface lies kSkin inside the rounded one (box2d_convert.hpp).
                    const double insetA = sa->m_radius - kSkin, insetB = sb->m_radius - kSkin;
                    const double g = out.distance - insetA - insetB;
                    if (!(g < gap)) continue;
                    gap = g;
                    normal = (1.0f / out.distance) * (out.pointB - out.pointA);
                    point = out.pointA + static_cast<float>(insetA + 0.5 * g) * normal;
                    found = true;
                }
        }
    return found;
}

void ContactRules::applyMaterial(b2Contact* contact) const {
    const ContactMaterial& m = materials_.get(fixtureInfo(contact->GetFixtureA()).material, fixtureInfo(contact->GetFixtureB()).material);
    contact->SetFriction(effects_.has(Effect::Friction) ? static_cast<float>(m.friction) : 0.0f);
    contact->SetRestitution(0.0f);
    contact->SetRestitutionThreshold(restitutionThreshold_);
}

void ContactRules::updateBounces() {
    bounces_ = effects_.has(Effect::Restitution) &&
               std::any_of(materials_.values.begin(), materials_.values.end(), [](const ContactMaterial& m) { return m.restitution > 0; });
}

// Runs for every touching contact every step: with nothing that bounces it returns at once (the
// lookups of both bodies' materials were 7 % of a 5 050-box pile's step when done here).
void ContactRules::PreSolve(b2Contact* contact, const b2Manifold* /*oldManifold*/) {
    if (solved_) {  // only time of impact updates contacts after a solve
        timeOfImpact_ = true;
        // The update may re-collide the manifold after the main solve stored its impulses in it:
        // the contact's impulses are summed from the reports (this entry adds nothing to them).
        if (firstSummed_ == kNone) firstSummed_ = solvedImpulses_.size();
        solvedImpulses_.push_back(SolvedImpulses{contact, {}});
    }
    if (!bounces_) return;
    const ContactMaterial& m = materials_.get(fixtureInfo(contact->GetFixtureA()).material, fixtureInfo(contact->GetFixtureB()).material);
    contact->SetRestitution(impactRestitution(contact, static_cast<float>(m.restitution)));
}

namespace {
// The main solve stores its impulses in the manifold before it reports them (b2Island::Solve:
// StoreImpulses, then Report); a time-of-impact solve reports without storing.
bool storedInManifold(b2Contact& contact, const b2ContactImpulse& impulse) {
    const b2Manifold& m = *contact.GetManifold();
    if (m.pointCount != impulse.count) return false;
    for (int32 p = 0; p < m.pointCount; ++p)
        if (m.points[p].normalImpulse != impulse.normalImpulses[p]) return false;
    return true;
}
}  // namespace

void ContactRules::PostSolve(b2Contact* contact, const b2ContactImpulse* impulse) {
    if (!solved_) {
        solved_ = true;
        // The substep's first report: from the main solve, unless that solved nothing and time
        // of impact reports first (then no pre-solve after a solve marked the phase).
        if (!storedInManifold(*contact, *impulse)) timeOfImpact_ = true;
    }
    if (timeOfImpact_ && firstSummed_ == kNone) firstSummed_ = solvedImpulses_.size();
    SolvedImpulses& entry = solvedImpulses_.emplace_back(SolvedImpulses{contact, {}});
    for (int32 p = 0; p < impulse->count && p < b2_maxManifoldPoints; ++p) entry.normal[static_cast<std::size_t>(p)] = impulse->normalImpulses[p];
}

// Box2D bounces the normal velocity its solver finds, -e' v_rel. The layer's restitution means:
// leave with e times the speed at the instant of impact. Under gravity the two differ by parts of
// a step's g h, because semi-implicit Euler (Box2D's integrator) moves each step with the
// velocity after that step's gravity:
// - a body reaching the contact moved its last step with v_n, which on the discrete path lies
//   g h / 2 below the speed of the exact fall (v_n^2 + v_n g h = 2 g H), so v_impact = |v_n| + g h / 2
//   when pre-solve runs before the step's gravity, and |v_n| - g h / 2 at time of impact, after it;
// - leaving with u, a discrete flight rises to about u^2 / 2g - u h / 2 when its first move
//   uses u - g h (after a time-of-impact stop, which ends the step at the contact), or
//   u^2 / 2g + u h / 2 when its first move uses u (a bounce in the main solve, which moves the
//   body in the same step); e^2 H needs u = e v_impact + g h / 2 or - g h / 2 respectively;
// - the main solve sees v_rel after this step's gravity (|v_n| + g h); time of impact sees v_n.
// (Taking + g h / 2 at time of impact too made rebounds 14 % high at some drop heights.)
// g is the closing part of the pair's relative gravity along the normal; without gravity e' = e.
float ContactRules::impactRestitution(b2Contact* contact, float e) const {
    if (e <= 0.0f) return e;
    b2WorldManifold wm;
    contact->GetWorldManifold(&wm);
    const int32 count = contact->GetManifold()->pointCount;
    if (count == 0) return e;
    const b2Body* a = contact->GetFixtureA()->GetBody();
    const b2Body* b = contact->GetFixtureB()->GetBody();
    float vn = 0.0f;
    for (int32 i = 0; i < count; ++i) {
        const b2Vec2 dv = b->GetLinearVelocityFromWorldPoint(wm.points[i]) - a->GetLinearVelocityFromWorldPoint(wm.points[i]);
        vn += b2Dot(dv, wm.normal) / static_cast<float>(count);
    }
    if (vn >= 0.0f) return e;  // separating: nothing to bounce
    const auto fall = [&](const b2Body* body) {
        return body->GetType() == b2_dynamicBody ? body->GetGravityScale() * gravity_ : b2Vec2(0.0f, 0.0f);
    };
    const float g = -b2Dot(fall(b) - fall(a), wm.normal);  // > 0: gravity closes the pair
    // Pre-solve runs twice a step: in Box2D's collide phase, before any velocity changed, and
    // again for time-of-impact contacts after the solve (gravity already added).
    const bool afterSolve = solved_ || bodyOf(contact->GetFixtureA()).movedSinceStepStart() ||
                            bodyOf(contact->GetFixtureB()).movedSinceStepStart();
    // After the solve, v_n already holds this step's gravity: v_impact = |v_n| - g h / 2.
    const float impact = afterSolve ? -vn - 0.5f * g * h_ : -vn + 0.5f * g * h_;
    // The threshold is on the speed at the instant of impact; Box2D would compare the speed its
    // solver sees, up to g h faster, and bounce an impact just below the threshold.
    if (impact <= restitutionThreshold_) return 0.0f;
    const float leave = afterSolve ? e * impact + 0.5f * g * h_ : e * impact - 0.5f * g * h_;
    const float seen = afterSolve ? -vn : -vn + g * h_;
    return seen > 0.0f ? std::max(0.0f, leave / seen) : e;
}

}  // namespace anyphys::box2d
