// Time of impact (timeOfImpact) by conservative advancement on the distance queries.
#include <algorithm>
#include <array>
#include <stdexcept>

#include "collision/mesh_data.hpp"
#include "collision/query_helpers.hpp"

namespace anyphys::native {
namespace {

/// How far any surface point of a convex shape lies from its frame origin: bounds the motion a
/// rotation causes. A sphere is unchanged by rotation about its centre, hence 0.
double maxRadius(const Shape& s) {
    switch (s.type) {
        case ShapeType::Sphere: return 0.0;
        case ShapeType::Capsule: return s.halfHeight + s.radius;
        case ShapeType::Box: return s.halfExtents.norm();
        case ShapeType::Convex: {
            double r = 0.0;
            for (const Vec3& v : s.hull->vertices) r = std::max(r, v.norm());
            return r;
        }
        default: return 0.0;
    }
}

/// Conservative advancement of a over [0, tEnd] against a convex b given by its distance
/// function. With n the separating normal at t, no point of a approaches b faster than
/// n.dx + angle * rMax (per unit t), so advancing by (d - target) / that bound never passes
/// the target distance.
template <class DistanceFn>
double advance(const Transform& start, const Transform& end, double rMax, double target, double tEnd,
               const DistanceFn& distanceAt) {
    constexpr int kMaxIterations = 30;
    const double tolerance = 0.05 * target;  // accept distances in [target, 1.05 target]
    const Vec3 dx = end.position - start.position;
    const double angle = start.orientation.angularDistance(end.orientation);
    double t = 0.0;
    for (int iter = 0; iter < kMaxIterations; ++iter) {
        const Transform xf{start.position + t * dx, start.orientation.slerp(t, end.orientation)};
        const DistanceResult d = distanceAt(xf);
        if (d.distance <= target + tolerance) return t;
        const double approach = d.normal.dot(dx) + angle * rMax;
        if (approach <= 0.0) return tEnd;  // moving apart
        t += (d.distance - target) / approach;
        if (t >= tEnd) return tEnd;
    }
    return t;  // out of iterations: t is still safe (never past the target)
}

}  // namespace

double timeOfImpact(const Shape& a, const Transform& startA, const Transform& endA, const Shape& b, const Transform& xfB,
                    double target) {
    if (!isConvex(a.type)) throw std::invalid_argument("timeOfImpact: the moving shape must be convex");
    const double rMax = maxRadius(a);
    if (b.type != ShapeType::Mesh)
        return advance(startA, endA, rMax, target, 1.0, [&](const Transform& xf) { return distance(a, xf, b, xfB); });

    // A mesh is not convex: its nearest triangle's normal does not bound the approach to the
    // others. Advance against each triangle the sweep can reach and keep the earliest.
    const MeshData& mesh = *b.mesh;
    const Transform toMesh = inverse(xfB);
    const double angle = startA.orientation.angularDistance(endA.orientation);
    // Any point strays at most 2 angle rMax from the union of its start and end boxes.
    const Aabb sweep = computeAabb(a, compose(toMesh, startA))
                           .merged(computeAabb(a, compose(toMesh, endA)))
                           .fattened(2.0 * angle * rMax + target);
    double earliest = 1.0;
    mesh.queryTriangles(sweep, [&](int tri) {
        std::array<Vec3, 3> v = mesh.triangleVertices(tri);
        for (Vec3& p : v) p = apply(xfB, p);
        const ConvexCore triangle = ConvexCore::triangle(v);
        earliest = advance(startA, endA, rMax, target, earliest, [&](const Transform& xf) {
            return convexDistance(ConvexCore::of(a, xf), triangle, v[0] - xf.position);
        });
        return earliest > 0.0;
    });
    return earliest;
}

}  // namespace anyphys::native
