#include "box2d_contacts.hpp"

#include <algorithm>

#include <box2d/b2_distance.h>

#include "anyphys/defs.hpp"
#include "anyphys/peers/rebound_from_depth.hpp"
#include "box2d_body.hpp"
#include "box2d_convert.hpp"
#include "box2d_triggers.hpp"

namespace anyphys::box2d {

Box2dBody& bodyOf(const b2Fixture* fixture) { return *fixtureInfo(fixture).body; }

// Filter and materials are per fixture: a compound's children may carry their own.


bool fixturesCollide(const b2Fixture* fixtureA, const b2Fixture* fixtureB) {
    const FixtureInfo& a = fixtureInfo(fixtureA);
    const FixtureInfo& b = fixtureInfo(fixtureB);
    return layersCollide(a.layer, a.mask, b.layer, b.mask);
}

bool ContactRules::ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB) {
    if (!effects_.has(Effect::Contacts)) return false;  // contacts off: nothing touches
    if (isTriggerPlane(*fixtureA) || isTriggerPlane(*fixtureB)) return false;  // the world lists those
    return fixturesCollide(fixtureA, fixtureB);
}

namespace {

bool apartBeyond(const b2AABB& a, const b2AABB& b, float reach) {
    return a.lowerBound.x - reach > b.upperBound.x || b.lowerBound.x - reach > a.upperBound.x ||
           a.lowerBound.y - reach > b.upperBound.y || b.lowerBound.y - reach > a.upperBound.y;
}

}  // namespace

bool nearestSurfaces(const b2Body& a, const b2Body& b, double reach, b2Vec2& normal, b2Vec2& point, double& gap) {
    gap = reach;
    bool found = false;
    for (const b2Fixture* fa = a.GetFixtureList(); fa; fa = fa->GetNext())
        for (const b2Fixture* fb = b.GetFixtureList(); fb; fb = fb->GetNext()) {
            if (fa->IsSensor() || fb->IsSensor() || !fixturesCollide(fa, fb)) continue;
            // A plane's edges give its surface; its basements lie under them (box2d_shapes.hpp).
            if (fixtureInfo(fa).piece.basement || fixtureInfo(fb).piece.basement) continue;
            const b2Shape* sa = fa->GetShape();
            const b2Shape* sb = fb->GetShape();
            for (int32 ca = 0; ca < sa->GetChildCount(); ++ca)
                for (int32 cb = 0; cb < sb->GetChildCount(); ++cb) {
                    // Box2D's broad-phase boxes hold each child with room to spare: children whose
                    // boxes lie farther apart than the reach have no surfaces within it (most of a
                    // plane's run of edges). Every child has its box: the backend never disables
                    // a body, which would take its fixtures out of the broad phase.
                    if (apartBeyond(fa->GetAABB(ca), fb->GetAABB(cb), static_cast<float>(reach))) continue;
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

namespace {
// A plane's basement (box2d_shapes.hpp) holds a piece only where the edge above it lets go: when
// the piece's centre (a polygon's centroid, a circle's centre) is behind the edge's line, as
// Box2D's one-sided edge tests it (b2CollideEdgeAndPolygon, b2CollideEdgeAndCircle, in the edge's
// frame). Elsewhere the edge holds the piece alone: one smooth surface across the edges' joints.
bool basementLetsGo(const b2Contact& contact) {
    const b2Fixture* basement = contact.GetFixtureA();
    const b2Fixture* other = contact.GetFixtureB();
    // Only a static body has a basement: most contacts are settled by the body's type.
    const auto isBasement = [](const b2Fixture* f) { return f->GetBody()->GetType() == b2_staticBody && fixtureInfo(f).piece.basement; };
    if (!isBasement(basement)) {
        std::swap(basement, other);
        if (!isBasement(basement)) return false;
    }
    const b2Shape& shape = *other->GetShape();
    b2Vec2 centre;
    if (shape.GetType() == b2Shape::e_circle)
        centre = static_cast<const b2CircleShape&>(shape).m_p;
    else if (shape.GetType() == b2Shape::e_polygon)
        centre = static_cast<const b2PolygonShape&>(shape).m_centroid;
    else
        return false;
    const HalfPlane& plane = *fixtureInfo(basement).piece.plane;  // in the basement's body frame
    const b2Transform xf = b2MulT(basement->GetBody()->GetTransform(), other->GetBody()->GetTransform());
    const float edgeLine = plane.offset - (b2_polygonRadius - static_cast<float>(kSkin));  // the edge's core (makePieces)
    return b2Dot(plane.normal, b2Mul(xf, centre)) >= edgeLine;
}
}  // namespace

// Runs for every touching contact every step: with nothing that bounces it returns at once (the
// lookups of both bodies' materials were 7 % of a 5 050-box pile's step when done here).
void ContactRules::PreSolve(b2Contact* contact, const b2Manifold* /*oldManifold*/) {
    if (basementBodies_ > 0 && basementLetsGo(*contact)) {
        contact->SetEnabled(false);  // until its next update: unsolved and unreported
        return;
    }
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
// leave with e times the speed at the instant of impact, so that the pair rises e^2 of its drop.
// Under gravity the two differ, because semi-implicit Euler (Box2D's integrator) moves each step
// with the velocity after that step's gravity, and because Box2D finds the impact late:
// - in the main solve (pre-solve before the step's gravity) the pair is found up to a step's fall
//   into the skins, and moves with the rebound from there: reboundFromDepth;
// - at time of impact (pre-solve after the solve) it was stopped part way through the step, and
//   moves on with the rebound for the rest of it: timeOfImpactRebound;
// - the main solve sees v_rel after this step's gravity (|v_n| + g h); time of impact sees v_n.
// g is the closing part of the pair's relative gravity along the normal; without gravity e' = e.
float ContactRules::impactRestitution(b2Contact* contact, float e) const {
    if (e <= 0.0f) return e;
    b2WorldManifold wm;
    contact->GetWorldManifold(&wm);
    const int32 count = contact->GetManifold()->pointCount;
    if (count == 0) return e;
    const b2Body* a = contact->GetFixtureA()->GetBody();
    const b2Body* b = contact->GetFixtureB()->GetBody();
    float vn = 0.0f, depth = 0.0f;  // means over the points; the depth of the true surfaces
    for (int32 i = 0; i < count; ++i) {
        const b2Vec2 dv = b->GetLinearVelocityFromWorldPoint(wm.points[i]) - a->GetLinearVelocityFromWorldPoint(wm.points[i]);
        vn += b2Dot(dv, wm.normal) / static_cast<float>(count);
        depth -= (wm.separations[i] + static_cast<float>(kPairSkin)) / static_cast<float>(count);
    }
    if (vn >= 0.0f) return e;  // separating: nothing to bounce
    // Only bodies falling freely: a box resting on the ground does not fall with the ball.
    const auto fall = [&](const b2Fixture* fixture) {
        const b2Body* body = fixture->GetBody();
        return body->GetType() == b2_dynamicBody && bodyOf(fixture).fellLastStep() ? body->GetGravityScale() * gravity_
                                                                                    : b2Vec2(0.0f, 0.0f);
    };
    const float g = -b2Dot(fall(contact->GetFixtureB()) - fall(contact->GetFixtureA()), wm.normal);  // > 0: gravity closes the pair
    // Pre-solve runs twice a step: in Box2D's collide phase, before any velocity changed, and
    // again for time-of-impact contacts after the solve (gravity already added).
    const bool afterSolve = solved_ || bodyOf(contact->GetFixtureA()).movedSinceStepStart() ||
                            bodyOf(contact->GetFixtureB()).movedSinceStepStart();
    if (afterSolve) {
        const float leave = timeOfImpactRebound(contact, wm.normal, e, -vn, depth, g);
        if (leave < 0.0f) return 0.0f;  // below the threshold
        return std::max(0.0f, leave / -vn);
    }
    // Before the solve: the impact came at v_impact = |v_n| + g h / 2 at contact. The main solve
    // bounces the pair from where the collide phase found it, up to a step's fall in the ground:
    // aimed as from contact (reboundFromDepth; at depth 0, e v_impact - g h / 2). Unless time of
    // impact finds the pair past its target already at the step's start: it then pushes it out to
    // about contact before moving it on, and the bounce starts from there. (Counting the depth
    // there, a ball with e = 0.2 at 4 substeps rose 32 % high.)
    if (-vn + 0.5f * g * h_ <= restitutionThreshold_) return 0.0f;
    const float from = pushedOutByTimeOfImpact(*contact, depth) ? 0.0f : depth;
    const float leave = static_cast<float>(restitution::reboundFromDepth(e, -vn, from, g, h_));
    const float seen = -vn + g * h_;  // the main solve sees the velocity after this step's gravity
    return seen > 0.0f ? std::max(0.0f, leave / seen) : e;
}

// Box2D 2.4's time of impact (b2World::SolveTOI) takes pairs of a dynamic body and a static,
// kinematic or bullet one, and stops them where the cores are max(linear slop, radii - 3 linear
// slops) apart, within a quarter slop: a pair overlapping its skins more than that at the step's
// start is caught at once, and pushed out (b2_toiBaumgarte) to about a slop into the skins.
bool ContactRules::pushedOutByTimeOfImpact(const b2Contact& contact, float depth) const {
    if (!effects_.has(Effect::ContinuousCollision)) return false;
    const b2Body* a = contact.GetFixtureA()->GetBody();
    const b2Body* b = contact.GetFixtureB()->GetBody();
    const auto sweeps = [](const b2Body* body) { return body->IsBullet() || body->GetType() != b2_dynamicBody; };
    if (!sweeps(a) && !sweeps(b)) return false;
    const float radii = contact.GetFixtureA()->GetShape()->m_radius + contact.GetFixtureB()->GetShape()->m_radius;
    const float overlapAtTarget = std::min(radii - b2_linearSlop, 3.0f * b2_linearSlop) - 0.25f * b2_linearSlop;
    return depth + static_cast<float>(kPairSkin) > overlapAtTarget;
}

// Time of impact moves the pair back to where it overlaps 3 linear slops into the skins (a share
// `alpha` of the step's travel at `closing`, the speed it moved with), pushes it out to about
// contact, bounces it, and moves it on at the rebound u for the rest of the step: it ends the step
// u (1 - alpha) h up and then flies as semi-implicit Euler does, rising u^2 / 2g - u h / 2 more. It
// met the contact at v_i^2 = (closing - g h / 2)^2 + 2 g gap, from the gap at the step's start
// (the speed's lag as in reboundFromDepth). The apex e^2 v_i^2 / 2g needs
// u^2 + 2 g h (1/2 - alpha) u = e^2 v_i^2. (Aimed as if it ended the step at contact, alpha = 1,
// a ball with e = 0.2 rose up to 32 % high.) Returns -1 for an impact under the threshold.
float ContactRules::timeOfImpactRebound(const b2Contact* contact, const b2Vec2& normal, float e, float closing, float depth,
                                        float g) const {
    const b2Vec2 travel = bodyOf(contact->GetFixtureB()).travelSinceStepStart() - bodyOf(contact->GetFixtureA()).travelSinceStepStart();
    const float travelled = -b2Dot(travel, normal);
    const float stepTravel = closing * h_;
    const float alpha = stepTravel > 0.0f ? std::clamp(travelled / stepTravel, 0.0f, 1.0f) : 1.0f;
    const float gap = std::clamp(travelled - depth, 0.0f, stepTravel);
    const float lagged = closing - 0.5f * g * h_;
    const float impactSquared = std::max(lagged * lagged + 2.0f * g * gap, 0.0f);
    if (impactSquared <= restitutionThreshold_ * restitutionThreshold_) return -1.0f;
    const float b = g * h_ * (0.5f - alpha);  // half the linear term
    return -b + std::sqrt(std::max(b * b + e * e * impactSquared, 0.0f));
}

}  // namespace anyphys::box2d
