// collide(): places both shapes in the world and dispatches to the pair routine, with the pair
// ordered sphere < capsule < box < convex < plane < mesh; a swapped pair gets its normals flipped
// back so they always point from a to b. Each shape's rotation matrix is made once here.
#include "collision/collide.hpp"

#include <algorithm>
#include <array>

#include "collision/narrow_phase.hpp"
#include "collision/queries.hpp"

namespace anyphys::native {
namespace {

int rank(ShapeType t) {
    switch (t) {
        case ShapeType::Sphere: return 0;
        case ShapeType::Capsule: return 1;
        case ShapeType::Box: return 2;
        case ShapeType::Convex: return 3;
        case ShapeType::Plane: return 4;
        case ShapeType::Mesh: return 5;
        case ShapeType::Compound: return 6;
    }
    return 6;
}

SphereGeom sphereOf(const Shape& s, const Transform& xf) { return {xf.position, s.radius}; }

CapsuleGeom capsuleOf(const Shape& s, const Transform& xf) {
    const Vec3 axis = xf.orientation * Vec3(0, s.halfHeight, 0);
    return {xf.position - axis, xf.position + axis, s.radius};
}

BoxGeom boxOf(const Shape& s, const Transform& xf) { return {xf.position, xf.orientation.toRotationMatrix(), s.halfExtents}; }

PlaneGeom planeOf(const Shape& s) { return {s.normal.normalized(), s.offset}; }

Polytope polytopeOf(const Shape& s, const Transform& xf) {
    const Mat3 r = xf.orientation.toRotationMatrix();
    return s.type == ShapeType::Box ? makeBoxPolytope(s.halfExtents, r, xf.position)
                                    : makeHullPolytope(*s.hull, r, xf.position);
}

bool collideWithPlane(const Shape& a, const Transform& xfA, const PlaneGeom& plane, double speculative, Manifold& m) {
    switch (a.type) {
        case ShapeType::Sphere: return collidePointsPlane({&xfA.position, 1}, a.radius, plane, speculative, m);
        case ShapeType::Capsule: {
            const CapsuleGeom c = capsuleOf(a, xfA);
            const std::array<Vec3, 2> ends{c.p0, c.p1};
            return collidePointsPlane(ends, a.radius, plane, speculative, m);
        }
        case ShapeType::Box: return collideBoxPlane(boxOf(a, xfA), plane, speculative, m);
        case ShapeType::Convex: return collidePolytopePlane(polytopeOf(a, xfA), plane, speculative, m);
        default: return false;
    }
}

// A point of two overlapping shapes lies in both, so within both bounding boxes. Midway between
// the surfaces is such a point while the overlap is shallow for the shapes. A small box swallowed
// by a large one is overlapped through and through, and its midpoints lay half the large box
// away (4.7 m for a 0.1 m box in a 10 m one): events reported them there and friction acted about
// that arm (ODE's points on the large box's face made its direct solver abort). Where a point is
// deeper than kDeepOverlap, each point is clamped into the intersection of the two bounds, grown
// by the same margin. Shallower manifolds, every resting one, are not looked at (no bounds).
constexpr double kDeepOverlap = 0.01;  // m: twice the default linear slop

void keepDeepPointsInBothBounds(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, Manifold& m) {
    const auto deep = [](const ManifoldPoint& p) { return p.separation < -kDeepOverlap; };
    if (std::none_of(m.points.begin(), m.points.begin() + m.pointCount, deep)) return;
    const Aabb boundsA = computeAabb(a, xfA), boundsB = computeAabb(b, xfB);
    const Vec3 low = boundsA.min.cwiseMax(boundsB.min).array() - kDeepOverlap;
    const Vec3 high = boundsA.max.cwiseMin(boundsB.max).array() + kDeepOverlap;
    if (!(low.array() <= high.array()).all()) return;  // bounds apart: nothing to clamp into
    for (int i = 0; i < m.pointCount; ++i) m.points[i].point = m.points[i].point.cwiseMax(low).cwiseMin(high);
}

// a ranks no higher than b.
void collideOrdered(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculative,
                    std::vector<Manifold>& out, CollideCache* cache) {
    if (b.type == ShapeType::Mesh) {
        if (a.type != ShapeType::Plane && a.type != ShapeType::Mesh) collideConvexMesh(a, xfA, b, xfB, speculative, out);
        return;
    }
    Manifold m;
    bool hit = false;
    if (b.type == ShapeType::Plane) {
        if (a.type != ShapeType::Plane) hit = collideWithPlane(a, xfA, planeOf(b), speculative, m);
    } else if (a.type == ShapeType::Sphere) {
        const SphereGeom s = sphereOf(a, xfA);
        switch (b.type) {
            case ShapeType::Sphere: hit = collideSpheres(s, sphereOf(b, xfB), speculative, m); break;
            case ShapeType::Capsule: hit = collideSphereCapsule(s, capsuleOf(b, xfB), speculative, m); break;
            case ShapeType::Box: hit = collideSphereBox(s, boxOf(b, xfB), speculative, m); break;
            case ShapeType::Convex: hit = collideSpherePolytope(s, polytopeOf(b, xfB), speculative, m); break;
            default: break;
        }
    } else if (a.type == ShapeType::Capsule) {
        const CapsuleGeom c = capsuleOf(a, xfA);
        if (b.type == ShapeType::Capsule) hit = collideCapsules(c, capsuleOf(b, xfB), speculative, m);
        else if (b.type == ShapeType::Box || b.type == ShapeType::Convex)
            hit = collideCapsulePolytope(c, polytopeOf(b, xfB), speculative, m);
    } else if (a.type == ShapeType::Box && b.type == ShapeType::Box) {
        if (cache && boxesStillApart(a.halfExtents, xfA, b.halfExtents, xfB, *cache, speculative)) return;
        hit = collideBoxes(boxOf(a, xfA), boxOf(b, xfB), speculative, m, cache);
    } else if ((a.type == ShapeType::Box || a.type == ShapeType::Convex) && b.type == ShapeType::Convex) {
        hit = collidePolytopes(polytopeOf(a, xfA), polytopeOf(b, xfB), speculative, m, cache);
    }
    if (!hit) return;
    keepDeepPointsInBothBounds(a, xfA, b, xfB, m);
    out.push_back(m);
}

}  // namespace

void collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculativeDistance,
             std::vector<Manifold>& out, CollideCache* cache) {
    if (rank(a.type) <= rank(b.type)) {
        collideOrdered(a, xfA, b, xfB, speculativeDistance, out, cache);
        return;
    }
    const std::size_t first = out.size();
    collideOrdered(b, xfB, a, xfA, speculativeDistance, out, cache);
    for (std::size_t i = first; i < out.size(); ++i) out[i].normal = -out[i].normal;
}

}  // namespace anyphys::native
