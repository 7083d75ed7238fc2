// Convex shapes against a static triangle mesh: every triangle whose bounds meet the shape's
// (fattened by the speculative distance) is a thin one-sided polyhedron; each touched triangle
// gives its own manifold, keyed by the triangle index.
//
// Internal edges: alone, a triangle would push a shape crossing its edge sideways, although the
// neighbour across that edge continues the surface (the "ghost bump" of a box sliding over a flat
// mesh floor). A normal leaning over an edge is kept only inside the normals the surface really
// has there: between the two faces' normals at a convex edge, none at a flat or concave edge, the
// whole half-circle at an open boundary. Otherwise the triangle's own normal is used, with the part
// of the shape over the triangle. Neighbours are found among the candidate triangles themselves
// (both triangles of an edge the shape touches overlap its bounds), by shared vertex indices.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "collision/mesh_data.hpp"
#include "collision/narrow_phase.hpp"

namespace anyphys::native {
namespace {

// Slack on the edge cone (rad): normals this far outside it still count as inside.
constexpr double kConeSlack = 1e-3;

// Bounds of shape s at pose rel (its pose in the mesh frame).
Aabb boundsIn(const Shape& s, const Transform& rel) {
    const Mat3 r = rel.orientation.toRotationMatrix();
    switch (s.type) {
        case ShapeType::Sphere:
            return {rel.position.array() - s.radius, rel.position.array() + s.radius};
        case ShapeType::Capsule: {
            const Vec3 axis = r.col(1) * s.halfHeight;
            const Vec3 p0 = rel.position - axis, p1 = rel.position + axis;
            return {p0.cwiseMin(p1).array() - s.radius, p0.cwiseMax(p1).array() + s.radius};
        }
        case ShapeType::Box: {
            const Vec3 extent = r.cwiseAbs() * s.halfExtents;
            return {rel.position - extent, rel.position + extent};
        }
        case ShapeType::Convex: {
            Aabb box{Vec3::Constant(std::numeric_limits<double>::infinity()),
                     Vec3::Constant(-std::numeric_limits<double>::infinity())};
            for (const Vec3& v : s.hull->vertices) {
                const Vec3 p = rel.position + r * v;
                box.min = box.min.cwiseMin(p);
                box.max = box.max.cwiseMax(p);
            }
            return box;
        }
        default:
            return {rel.position, rel.position};
    }
}

// For each candidate triangle and edge k (v[k] -> v[k+1]), the candidate across it, or -1. An
// edge used by exactly two candidates joins them; otherwise it counts as an open boundary.
std::vector<std::array<int, 3>> neighbours(const MeshData& mesh, const std::vector<int>& candidates) {
    struct EdgeUse {
        std::uint32_t lo, hi;
        int local, k;
        bool operator<(const EdgeUse& o) const { return lo != o.lo ? lo < o.lo : hi < o.hi; }
    };
    std::vector<EdgeUse> uses;
    uses.reserve(3 * candidates.size());
    for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
        const auto& tri = mesh.triangles[candidates[i]];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = tri[k], w = tri[(k + 1) % 3];
            uses.push_back({std::min(v, w), std::max(v, w), i, k});
        }
    }
    std::sort(uses.begin(), uses.end());
    std::vector<std::array<int, 3>> across(candidates.size(), {-1, -1, -1});
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
        if (j - i == 2) {
            across[uses[i].local][uses[i].k] = candidates[uses[i + 1].local];
            across[uses[i + 1].local][uses[i + 1].k] = candidates[uses[i].local];
        }
        i = j;
    }
    return across;
}

// Whether `t` (unit, from the triangle toward the shape) is a normal the mesh surface has at the
// triangle's boundary feature it leans over. n: the triangle's front; neighbourNormal[k]: the front
// of the triangle across edge k (zero at an open boundary).
bool normalOnSurface(const Vec3& t, const std::array<Vec3, 3>& corners, const Vec3& n, const std::array<Vec3, 3>& neighbourNormal) {
    for (int k = 0; k < 3; ++k) {
        const Vec3 out = (corners[(k + 1) % 3] - corners[k]).cross(n).normalized();  // in-plane, away from the triangle
        const double lean = t.dot(out);
        if (lean <= 1e-9) continue;
        // Angles measured from n toward `out`: the normal's, and the far end of the edge's cone.
        const double phi = std::atan2(lean, t.dot(n));
        const Vec3& m = neighbourNormal[k];
        const double cone = m.isZero() ? std::numbers::pi / 2 : std::max(0.0, std::atan2(m.dot(out), m.dot(n)));
        if (phi > cone + kConeSlack) return false;
    }
    return true;
}

}  // namespace

void collideConvexMesh(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculative,
                       std::vector<Manifold>& out) {
    if (!b.mesh) return;
    const MeshData& mesh = *b.mesh;
    const Quat toMesh = xfB.orientation.conjugate();
    const Transform rel{toMesh * (xfA.position - xfB.position), toMesh * xfA.orientation};
    const Aabb query = boundsIn(a, rel).fattened(std::max(speculative, 0.0));
    std::vector<int> candidates;
    mesh.queryTriangles(query, [&](int t) {
        candidates.push_back(t);
        return true;
    });
    if (candidates.empty()) return;

    // The shape in the world, built once for all triangles.
    const Mat3 ra = xfA.orientation.toRotationMatrix();
    SphereGeom sphere;
    CapsuleGeom capsule;
    Polytope polytope;
    Vec3 center = xfA.position;
    switch (a.type) {
        case ShapeType::Sphere:
            sphere = {xfA.position, a.radius};
            break;
        case ShapeType::Capsule:
            capsule = {xfA.position - ra.col(1) * a.halfHeight, xfA.position + ra.col(1) * a.halfHeight, a.radius};
            break;
        case ShapeType::Box:
            polytope = makeBoxPolytope(a.halfExtents, xfA);
            break;
        case ShapeType::Convex:
            polytope = makeHullPolytope(*a.hull, xfA);
            center = polytope.center;
            break;
        default:
            return;
    }

    const Mat3 rb = xfB.orientation.toRotationMatrix();
    const std::vector<std::array<int, 3>> across = neighbours(mesh, candidates);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const int t = candidates[i];
        const auto& tri = mesh.triangles[t];
        const std::array<Vec3, 3> corners{xfB.position + rb * mesh.vertices[tri[0]], xfB.position + rb * mesh.vertices[tri[1]],
                                          xfB.position + rb * mesh.vertices[tri[2]]};
        const Vec3 normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        // One-sided: a shape whose centre is behind the triangle, or a degenerate triangle, is skipped.
        if (!(normal.squaredNorm() > 0) || normal.dot(center - corners[0]) < 0) continue;
        const Polytope triangle = makeTrianglePolytope(corners[0], corners[1], corners[2]);
        Manifold m;
        bool hit = false;
        switch (a.type) {
            case ShapeType::Sphere: hit = collideSpherePolytope(sphere, triangle, speculative, m); break;
            case ShapeType::Capsule: hit = collideCapsulePolytope(capsule, triangle, speculative, m); break;
            default: hit = collidePolytopes(polytope, triangle, speculative, m); break;
        }
        if (!hit) continue;
        std::array<Vec3, 3> neighbourNormal{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
        for (int k = 0; k < 3; ++k)
            if (across[i][k] >= 0) neighbourNormal[k] = rb * mesh.normals[across[i][k]];
        if (!normalOnSurface(-m.normal, corners, triangle.normals[0], neighbourNormal)) {
            // A ghost edge: the triangle's own normal, for the part of the shape over it.
            switch (a.type) {
                case ShapeType::Sphere: hit = collideSphereFace(sphere, triangle, 0, speculative, m); break;
                case ShapeType::Capsule: hit = collideCapsuleFace(capsule, triangle, 0, speculative, m); break;
                default: hit = collidePolytopeFace(polytope, triangle, 0, speculative, m); break;
            }
        }
        // Keep contacts that push the shape out of the front side (or along the triangle's plane).
        if (hit && m.normal.dot(triangle.normals[0]) <= 1e-9) {
            m.key = static_cast<std::uint32_t>(t);
            out.push_back(m);
        }
    }
}

}  // namespace anyphys::native
