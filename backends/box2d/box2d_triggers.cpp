#include "box2d_triggers.hpp"

#include <algorithm>

#include "anyphys/defs.hpp"
#include "box2d_body.hpp"

namespace anyphys::box2d {

namespace {

// How far the exact piece at xf reaches below the plane of unit normal n through `point`, in
// double: far from the origin floats would round the two sides of the difference apart.
double heightAbove(const b2Shape& exact, const b2Transform& xf, const b2Vec2& n, const b2Vec2& point) {
    const double centre = static_cast<double>(n.x) * (static_cast<double>(xf.p.x) - point.x) +
                          static_cast<double>(n.y) * (static_cast<double>(xf.p.y) - point.y);
    // The piece's own extent is small: lowest() below the body's origin, in floats.
    const b2Transform turned(b2Vec2(0.0f, 0.0f), xf.q);
    return centre + lowest(exact, turned, n);
}

// Whether a piece at xf overlaps the half-plane of a plane piece on a body at planeXf.
bool reachesBelow(const b2Shape& exact, const b2Transform& xf, const Piece& plane, const b2Transform& planeXf) {
    return heightAbove(exact, xf, plane.plane->worldNormal(planeXf), plane.plane->worldPoint(planeXf)) < kPairSkin;
}

// Box2D leaves out pairs a joint joins without collideConnected (b2Body::ShouldCollide).
bool jointForbids(const b2Body& body, const b2Body& other) {
    for (const b2JointEdge* e = const_cast<b2Body&>(body).GetJointList(); e; e = e->next)
        if (e->other == &other && !e->joint->GetCollideConnected()) return true;
    return false;
}

bool moves(const b2Body& b) { return b.GetType() != b2_staticBody; }

// The overlap of a kinematic body's fixture with a static or kinematic body's, as Box2D would
// test it were one of the bodies dynamic (b2Contact::Update for sensors).
class KinematicOverlaps final : public b2QueryCallback {
public:
    KinematicOverlaps(const b2Fixture& fixture, std::vector<const b2Body*>& found) : fixture_(fixture), found_(found) {}

    bool ReportFixture(b2Fixture* other) override {
        const b2Body& mine = *fixture_.GetBody();
        const b2Body& theirs = *other->GetBody();
        if (&theirs == &mine || theirs.GetType() == b2_dynamicBody) return true;  // dynamic: Box2D's own
        if (!fixture_.IsSensor() && !other->IsSensor()) return true;
        // A kinematic pair is listed once, from its body of lower key; trigger planes are
        // TriggerPlanes'. A collision plane's edges and basements answer with its half-plane.
        if (theirs.GetType() == b2_kinematicBody && bodyKey(&theirs) < bodyKey(&mine)) return true;
        if (isTriggerPlane(*other)) return true;
        const FixtureInfo &a = fixtureInfo(&fixture_), &b = fixtureInfo(other);
        if (std::find(found_.begin(), found_.end(), &theirs) != found_.end()) return true;
        if (!layersCollide(a.layer, a.mask, b.layer, b.mask) || jointForbids(mine, theirs)) return true;
        const bool overlaps = b.piece.plane ? reachesBelow(*a.piece.exact, mine.GetTransform(), b.piece, theirs.GetTransform())
                                            : b2TestOverlap(fixture_.GetShape(), 0, other->GetShape(), 0,
                                                            mine.GetTransform(), theirs.GetTransform());
        if (overlaps) found_.push_back(&theirs);
        return true;
    }

private:
    const b2Fixture& fixture_;
    std::vector<const b2Body*>& found_;
};

}  // namespace

bool isTriggerPlane(const b2Fixture& fixture) { return fixture.IsSensor() && fixtureInfo(&fixture).piece.plane.has_value(); }

bool TriggerPlanes::addIfTriggerPlane(Box2dBody& body) {
    const b2Fixture* f = body.b2()->GetFixtureList();
    if (!f || !isTriggerPlane(*f)) return false;  // a plane is a body's only shape: all its edges alike
    planes_.push_back(&body);
    return true;
}

bool TriggerPlanes::remove(Box2dBody& body) { return std::erase(planes_, &body) > 0; }

void TriggerPlanes::report(const std::vector<Box2dBody*>& bodies, Effects effects, ContactReport& out) const {
    if (planes_.empty() || !effects.has(Effect::Contacts)) return;  // contacts off: nothing overlaps
    for (const Box2dBody* plane : planes_) {
        const b2Body& p = *plane->b2();
        const FixtureInfo& edge = *plane->fixtures().front();
        for (const Box2dBody* body : bodies) {
            const b2Body& b = *body->b2();
            // Asleep: the layer keeps the pair, as for Box2D's own contacts of a sleeping body.
            if (!moves(b) || !b.IsAwake() || jointForbids(b, p)) continue;
            const bool overlaps = std::any_of(body->fixtures().begin(), body->fixtures().end(), [&](const auto& info) {
                return layersCollide(edge.layer, edge.mask, info->layer, info->mask) &&
                       reachesBelow(*info->piece.exact, b.GetTransform(), edge.piece, p.GetTransform());
            });
            if (overlaps) out.addPair(plane->userData(), body->userData(), true, Vec3::Zero());
        }
    }
}

void reportKinematicTriggers(const std::vector<Box2dBody*>& kinematic, const b2World& world, Effects effects,
                             ContactReport& out, std::vector<const b2Body*>& found) {
    if (!effects.has(Effect::Contacts)) return;
    for (const Box2dBody* body : kinematic) {
        const b2Body& b = *body->b2();
        found.clear();
        for (const b2Fixture* f = const_cast<b2Body&>(b).GetFixtureList(); f; f = f->GetNext()) {
            KinematicOverlaps overlaps(*f, found);
            world.QueryAABB(&overlaps, f->GetAABB(0));
        }
        for (const b2Body* other : found) {
            if (!b.IsAwake() && !other->IsAwake()) continue;  // asleep: the layer keeps the pair
            const bool asleep = !b.IsAwake() || (moves(*other) && !other->IsAwake());
            out.addPair(body->userData(), bodyKey(other), true, Vec3::Zero(), asleep);
        }
    }
}

}  // namespace anyphys::box2d
