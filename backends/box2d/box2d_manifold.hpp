#pragma once
// A contact's manifold in world coordinates: b2WorldManifold::Initialize (Box2D 2.4.1), inline.
// Events read every touching contact every step, and Box2D's out-of-line version (reached
// through b2Contact::GetWorldManifold) costs twice as much as the same arithmetic inlined here.
#include <box2d/box2d.h>

namespace anyphys::box2d {

/// Box2D's normal (from fixture A to B), points (midway between the surfaces) and separations.
struct WorldManifold {
    b2Vec2 normal{1.0f, 0.0f};
    b2Vec2 points[b2_maxManifoldPoints];
    float separations[b2_maxManifoldPoints];
};

/// The world manifold of manifold `m` between fixtures of radii radiusA and radiusB on bodies at
/// xfA and xfB, exactly as b2WorldManifold::Initialize computes it. Always inline: GCC kept it out
/// of line, and inlined the report and it run 8 % fewer instructions.
[[gnu::always_inline]] inline WorldManifold worldManifold(const b2Manifold& m, const b2Transform& xfA, float radiusA,
                                                          const b2Transform& xfB, float radiusB) {
    WorldManifold w;
    switch (m.type) {
        case b2Manifold::e_circles: {
            const b2Vec2 pointA = b2Mul(xfA, m.localPoint);
            const b2Vec2 pointB = b2Mul(xfB, m.points[0].localPoint);
            if (b2DistanceSquared(pointA, pointB) > b2_epsilon * b2_epsilon) {
                w.normal = pointB - pointA;
                w.normal.Normalize();
            }
            const b2Vec2 cA = pointA + radiusA * w.normal;
            const b2Vec2 cB = pointB - radiusB * w.normal;
            w.points[0] = 0.5f * (cA + cB);
            w.separations[0] = b2Dot(cB - cA, w.normal);
            break;
        }
        case b2Manifold::e_faceA: {
            w.normal = b2Mul(xfA.q, m.localNormal);
            const b2Vec2 planePoint = b2Mul(xfA, m.localPoint);
            for (int32 i = 0; i < m.pointCount; ++i) {
                const b2Vec2 clipPoint = b2Mul(xfB, m.points[i].localPoint);
                const b2Vec2 cA = clipPoint + (radiusA - b2Dot(clipPoint - planePoint, w.normal)) * w.normal;
                const b2Vec2 cB = clipPoint - radiusB * w.normal;
                w.points[i] = 0.5f * (cA + cB);
                w.separations[i] = b2Dot(cB - cA, w.normal);
            }
            break;
        }
        case b2Manifold::e_faceB: {
            w.normal = b2Mul(xfB.q, m.localNormal);
            const b2Vec2 planePoint = b2Mul(xfB, m.localPoint);
            for (int32 i = 0; i < m.pointCount; ++i) {
                const b2Vec2 clipPoint = b2Mul(xfA, m.points[i].localPoint);
                const b2Vec2 cB = clipPoint + (radiusB - b2Dot(clipPoint - planePoint, w.normal)) * w.normal;
                const b2Vec2 cA = clipPoint - radiusA * w.normal;
                w.points[i] = 0.5f * (cA + cB);
                w.separations[i] = b2Dot(cA - cB, w.normal);
            }
            w.normal = -w.normal;  // from A to B
            break;
        }
    }
    return w;
}

/// The world normal of a face manifold (from fixture A to B), the same bits as worldManifold's.
[[gnu::always_inline]] inline b2Vec2 faceNormal(const b2Manifold& m, const b2Transform& xfA, const b2Transform& xfB) {
    return m.type == b2Manifold::e_faceA ? b2Mul(xfA.q, m.localNormal) : -b2Mul(xfB.q, m.localNormal);
}

/// A touching contact's world manifold, as b2Contact::GetWorldManifold computes it.
[[gnu::always_inline]] inline WorldManifold worldManifold(const b2Contact& contact) {
    return worldManifold(*contact.GetManifold(), contact.GetFixtureA()->GetBody()->GetTransform(),
                         contact.GetFixtureA()->GetShape()->m_radius, contact.GetFixtureB()->GetBody()->GetTransform(),
                         contact.GetFixtureB()->GetShape()->m_radius);
}

}  // namespace anyphys::box2d
