// Closest points between shapes (distance, overlap): GJK on the convex cores with the radii added
// afterwards, a closed form against planes, and a growing search among a mesh's triangles.
#include <algorithm>
#include <array>
#include <limits>
#include <utility>

#include "collision/mesh_data.hpp"
#include "collision/query_helpers.hpp"

namespace anyphys::native {

// When the cores are closer than the radii, the points are the two deepest surface points
// (they have crossed).
DistanceResult convexDistance(const ConvexCore& a, const ConvexCore& b, const Vec3& initialDir) {
    const GjkResult g = gjk(a, b, initialDir);
    DistanceResult r;
    if (g.overlap || g.distance <= 0.0) {
        r.pointA = r.pointB = 0.5 * (g.pointA + g.pointB);
        return r;
    }
    const Vec3 n = (g.pointB - g.pointA) / g.distance;
    r.normal = n;
    r.pointA = g.pointA + a.radius() * n;
    r.pointB = g.pointB - b.radius() * n;
    r.distance = std::max(0.0, g.distance - a.radius() - b.radius());
    return r;
}

namespace {

// Closed form: the deepest point of A along -n decides.
DistanceResult planeDistance(const ConvexCore& a, const Shape& plane) {
    const Vec3& n = plane.normal;
    const Vec3 deepest = a.vertex(a.support(-n)) - a.radius() * n;
    const double separation = n.dot(deepest) - plane.offset;
    DistanceResult r;
    r.distance = std::max(0.0, separation);
    r.pointA = deepest;
    r.pointB = deepest - separation * n;  // its projection on the plane
    r.normal = -n;
    return r;
}

// Min over triangles near A. The search box grows until it holds a triangle at most as far as
// its margin (then no unseen triangle can be closer).
DistanceResult meshDistance(const Shape& a, const Transform& xfA, const Shape& meshShape, const Transform& xfB) {
    const MeshData& mesh = *meshShape.mesh;
    const ConvexCore core = ConvexCore::of(a, xfA);
    const Aabb local = computeAabb(a, compose(inverse(xfB), xfA));
    const Aabb meshBox = mesh.tree.rootAabb();
    DistanceResult best;
    best.distance = kInf;
    double margin = std::max(1e-3, 0.5 * local.extents().maxCoeff());
    while (true) {
        bool found = false;
        const Aabb searchBox = local.fattened(margin);
        mesh.queryTriangles(searchBox, [&](int tri) {
            found = true;
            std::array<Vec3, 3> v = mesh.triangleVertices(tri);
            for (Vec3& p : v) p = apply(xfB, p);
            const DistanceResult r = convexDistance(core, ConvexCore::triangle(v), v[0] - xfA.position);
            if (r.distance < best.distance) best = r;
            return best.distance > 0.0;
        });
        if (found && best.distance <= margin) return best;
        if (found) {
            // The next pass sees every triangle that could be closer (a hair more for rounding).
            margin = best.distance * (1.0 + 1e-9) + 1e-12;
        } else if (searchBox.contains(meshBox)) {
            return best;  // an empty mesh: nothing to be near
        } else {
            margin *= 4.0;
        }
    }
}

}  // namespace

DistanceResult distance(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
    const bool convexA = isConvex(a.type);
    const bool convexB = isConvex(b.type);
    if (convexA && convexB)
        return convexDistance(ConvexCore::of(a, xfA), ConvexCore::of(b, xfB), xfB.position - xfA.position);
    if (convexA && b.type == ShapeType::Plane) return planeDistance(ConvexCore::of(a, xfA), b);
    if (convexA && b.type == ShapeType::Mesh) return meshDistance(a, xfA, b, xfB);
    if (convexB) {  // plane or mesh first: answer the swapped question, swap back
        DistanceResult r = distance(b, xfB, a, xfA);
        std::swap(r.pointA, r.pointB);
        r.normal = -r.normal;
        return r;
    }
    // Two static shapes: never asked by the pipeline; they are "infinitely" apart.
    DistanceResult r;
    r.distance = kInf;
    return r;
}

bool overlap(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
    return distance(a, xfA, b, xfB).distance <= 0.0;
}

}  // namespace anyphys::native
