#include "box2d_trigger_planes.hpp"

#include <algorithm>

#include "anyphys/defs.hpp"
#include "box2d_body.hpp"

namespace anyphys::box2d {

namespace {

const FixtureInfo& infoOf(const b2Fixture& fixture) {
    return *reinterpret_cast<const FixtureInfo*>(const_cast<b2Fixture&>(fixture).GetUserData().pointer);
}

// How far the exact piece at xf reaches below the plane of unit normal n through `point`, in
// double: far from the origin floats would round the two sides of the difference apart.
double heightAbove(const b2Shape& exact, const b2Transform& xf, const b2Vec2& n, const b2Vec2& point) {
    const double centre = static_cast<double>(n.x) * (static_cast<double>(xf.p.x) - point.x) +
                          static_cast<double>(n.y) * (static_cast<double>(xf.p.y) - point.y);
    // The piece's own extent is small: lowest() below the body's origin, in floats.
    const b2Transform turned(b2Vec2(0.0f, 0.0f), xf.q);
    return centre + lowest(exact, turned, n);
}

// Box2D leaves out pairs a joint joins without collideConnected (b2Body::ShouldCollide).
bool jointForbids(const b2Body& body, const b2Body& other) {
    for (const b2JointEdge* e = const_cast<b2Body&>(body).GetJointList(); e; e = e->next)
        if (e->other == &other && !e->joint->GetCollideConnected()) return true;
    return false;
}

}  // namespace

bool isTriggerPlane(const b2Fixture& fixture) { return fixture.IsSensor() && infoOf(fixture).piece.plane.has_value(); }

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
        const b2Vec2 n = b2Mul(p.GetTransform().q, edge.piece.plane->normal);
        const b2Vec2 point = p.GetTransform().p + edge.piece.plane->offset * n;  // on the plane
        for (const Box2dBody* body : bodies) {
            const b2Body& b = *body->b2();
            // Asleep: the layer keeps the pair, as for Box2D's own contacts of a sleeping body.
            if (b.GetType() != b2_dynamicBody || !b.IsAwake() || jointForbids(b, p)) continue;
            const bool overlaps = std::any_of(body->fixtures().begin(), body->fixtures().end(), [&](const auto& info) {
                return layersCollide(edge.layer, edge.mask, info->layer, info->mask) &&
                       heightAbove(*info->piece.exact, b.GetTransform(), n, point) < kPairSkin;
            });
            if (overlaps) out.addPair(plane->userData(), body->userData(), true, Vec3::Zero());
        }
    }
}

}  // namespace anyphys::box2d
