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
//
// Coplanar triangles: the manifolds of triangles whose normals agree are merged into one, as Jolt
// merges a mesh's manifolds of equal normal. Apart, each had its friction at the centre of its own
// points (not of its load), so a box straddling a cell's diagonal was turned about the normal by
// its own friction, the pieces' twist rows fought it and their tangent rows took a share sideways:
// down a tessellated 20 degree slope a 0.5 m box slid 3.5 % too fast and drifted 4 cm sideways in
// 4 s, on one box floor it is exact.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "collision/feature_id.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/mesh_data.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/scratch.hpp"

namespace anyphys::native {
namespace {

// Slack on the edge cone (rad): normals this far outside it still count as inside.
constexpr double kConeSlack = 1e-3;
// Manifolds whose normals differ by less than this angle (rad) lie on one flat stretch of the mesh
// and are merged; a tessellated plane's triangles differ by rounding only (1e-15).
constexpr double kCoplanarAngle = 1e-4;

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

// Per-thread buffers (see scratch.hpp): the triangles met and their neighbours.
struct EdgeUse {
    std::uint32_t lo, hi;
    int local, k;
    bool operator<(const EdgeUse& o) const { return lo != o.lo ? lo < o.lo : hi < o.hi; }
};

struct MeshScratch {
    std::vector<int> candidates;
    std::vector<EdgeUse> uses;
    std::vector<std::array<int, 3>> across;
    std::vector<ManifoldBuilder::Candidate> merged, storage;
    std::vector<char> taken;
};

MeshScratch& meshScratch() {
    thread_local MeshScratch s;
    return s;
}

// For each candidate triangle and edge k (v[k] -> v[k+1]), the candidate across it, or -1. An
// edge used by exactly two candidates joins them; otherwise it counts as an open boundary.
std::span<const std::array<int, 3>> neighbours(const MeshData& mesh, std::span<const int> candidates, MeshScratch& scratch) {
    std::vector<EdgeUse>& uses = scratch.uses;
    uses.clear();
    for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
        const auto& tri = mesh.triangles[static_cast<std::size_t>(candidates[static_cast<std::size_t>(i)])];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = tri[static_cast<std::size_t>(k)], w = tri[static_cast<std::size_t>((k + 1) % 3)];
            uses.push_back({std::min(v, w), std::max(v, w), i, k});
        }
    }
    std::sort(uses.begin(), uses.end());
    const std::span<std::array<int, 3>> across = firstOf(scratch.across, candidates.size());
    std::fill(across.begin(), across.end(), std::array<int, 3>{-1, -1, -1});
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
        if (j - i == 2) {
            across[static_cast<std::size_t>(uses[i].local)][static_cast<std::size_t>(uses[i].k)] =
                candidates[static_cast<std::size_t>(uses[i + 1].local)];
            across[static_cast<std::size_t>(uses[i + 1].local)][static_cast<std::size_t>(uses[i + 1].k)] =
                candidates[static_cast<std::size_t>(uses[i].local)];
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

// Every candidate triangle against the shape placed in the world: `whole(triangle, m)` the shape
// against the triangle, `front(triangle, m)` only against its front face.
template <class Whole, class Front>
void collideTriangles(const MeshData& mesh, const Transform& xfB, std::span<const int> candidates, const Vec3& center,
                      MeshScratch& scratch, Whole whole, Front front, std::vector<Manifold>& out) {
    const Mat3 rb = xfB.orientation.toRotationMatrix();
    const std::span<const std::array<int, 3>> across = neighbours(mesh, candidates, scratch);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const int t = candidates[i];
        const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
        const std::array<Vec3, 3> corners{xfB.position + rb * mesh.vertices[tri[0]],
                                          xfB.position + rb * mesh.vertices[tri[1]],
                                          xfB.position + rb * mesh.vertices[tri[2]]};
        const Vec3 normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        // One-sided: a shape whose centre is behind the triangle, or a degenerate triangle, is skipped.
        if (!(normal.squaredNorm() > 0) || normal.dot(center - corners[0]) < 0) continue;
        const Polytope triangle = makeTrianglePolytope(corners[0], corners[1], corners[2]);
        Manifold m;
        bool hit = whole(triangle, m);
        if (!hit) continue;
        std::array<Vec3, 3> neighbourNormal{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
        for (std::size_t k = 0; k < 3; ++k)
            if (const int other = across[i][k]; other >= 0) neighbourNormal[k] = rb * mesh.normals[static_cast<std::size_t>(other)];
        const Vec3 front0 = triangle.normal(0);
        // A ghost edge: the triangle's own normal, for the part of the shape over it.
        if (!normalOnSurface(-m.normal, corners, front0, neighbourNormal)) hit = front(triangle, m);
        // Keep contacts that push the shape out of the front side (or along the triangle's plane).
        if (hit && m.normal.dot(front0) <= 1e-9) {
            m.key = static_cast<std::uint32_t>(t);
            out.push_back(m);
        }
    }
}

// Whether unit normals n and m are the same direction within kCoplanarAngle.
bool sameNormal(const Vec3& n, const Vec3& m) { return n.cross(m).squaredNorm() < kCoplanarAngle * kCoplanarAngle && n.dot(m) > 0.0; }

// Adds the points of `m` to `candidates`, each id made distinct per triangle (two triangles clip the
// same features of the shape) and stable from step to step (warm starting matches by id). A point
// already there (on an edge the triangles share) keeps the deeper separation.
void addMergeCandidates(const Manifold& m, double tolerance, std::vector<ManifoldBuilder::Candidate>& candidates) {
    for (int i = 0; i < m.pointCount; ++i) {
        const ManifoldPoint& p = m.points[static_cast<std::size_t>(i)];
        const auto same = std::find_if(candidates.begin(), candidates.end(), [&](const ManifoldBuilder::Candidate& c) {
            return (c.point - p.point).squaredNorm() <= tolerance * tolerance;
        });
        if (same != candidates.end()) same->separation = std::min(same->separation, p.separation);
        else candidates.push_back({p.point, p.separation, feature::combine(p.id, m.key)});
    }
}

// Merges the manifolds out[first..] of equal normal into one each: the first one's normal, the
// lowest of their keys (triangle indices) and, of all their points, the four that keep most of the
// area. Points closer than `tolerance` are one.
void mergeCoplanarManifolds(std::vector<Manifold>& out, std::size_t first, double tolerance, MeshScratch& scratch) {
    std::vector<ManifoldBuilder::Candidate>& candidates = scratch.merged;
    std::vector<char>& taken = scratch.taken;
    taken.assign(out.size(), 0);
    std::size_t kept = first;
    for (std::size_t i = first; i < out.size(); ++i) {
        if (taken[i]) continue;
        candidates.clear();
        addMergeCandidates(out[i], tolerance, candidates);
        std::uint32_t key = out[i].key;
        for (std::size_t j = i + 1; j < out.size(); ++j)
            if (!taken[j] && sameNormal(out[i].normal, out[j].normal)) {
                addMergeCandidates(out[j], tolerance, candidates);
                key = std::min(key, out[j].key);
                taken[j] = 1;
            }
        ManifoldBuilder builder(out[i].normal, firstOf(scratch.storage, candidates.size()));
        for (const ManifoldBuilder::Candidate& c : candidates) builder.add(c.point, c.separation, c.id);
        Manifold m;
        builder.finish(m);
        m.key = key;
        out[kept++] = m;
    }
    out.resize(kept);
}

}  // namespace

void collideConvexMesh(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculative,
                       std::vector<Manifold>& out) {
    if (!b.mesh) return;
    const MeshData& mesh = *b.mesh;
    const Quat toMesh = xfB.orientation.conjugate();
    const Transform rel{toMesh * (xfA.position - xfB.position), toMesh * xfA.orientation};
    const Aabb query = boundsIn(a, rel).fattened(std::max(speculative, 0.0));
    MeshScratch& scratch = meshScratch();
    std::vector<int>& candidates = scratch.candidates;
    candidates.clear();
    mesh.queryTriangles(query, [&](int t) {
        candidates.push_back(t);
        return true;
    });
    if (candidates.empty()) return;

    // The shape in the world, made once for all triangles.
    const Mat3 ra = xfA.orientation.toRotationMatrix();
    const std::size_t first = out.size();
    switch (a.type) {
        case ShapeType::Sphere: {
            const SphereGeom sphere{xfA.position, a.radius};
            collideTriangles(
                mesh, xfB, candidates, xfA.position, scratch,
                [&](const Polytope& tri, Manifold& m) { return collideSpherePolytope(sphere, tri, speculative, m); },
                [&](const Polytope& tri, Manifold& m) { return collideSphereFace(sphere, tri, 0, speculative, m); }, out);
            break;
        }
        case ShapeType::Capsule: {
            const Vec3 axis = ra.col(1) * a.halfHeight;
            const CapsuleGeom capsule{xfA.position - axis, xfA.position + axis, a.radius};
            collideTriangles(
                mesh, xfB, candidates, xfA.position, scratch,
                [&](const Polytope& tri, Manifold& m) { return collideCapsulePolytope(capsule, tri, speculative, m); },
                [&](const Polytope& tri, Manifold& m) { return collideCapsuleFace(capsule, tri, 0, speculative, m); }, out);
            break;
        }
        case ShapeType::Box:
        case ShapeType::Convex: {
            const Polytope shape = a.type == ShapeType::Box ? makeBoxPolytope(a.halfExtents, ra, xfA.position)
                                                            : makeHullPolytope(*a.hull, ra, xfA.position);
            collideTriangles(
                mesh, xfB, candidates, shape.center, scratch,
                [&](const Polytope& tri, Manifold& m) { return collidePolytopes(shape, tri, speculative, m); },
                [&](const Polytope& tri, Manifold& m) { return collidePolytopeFace(shape, tri, 0, speculative, m); }, out);
            break;
        }
        default:
            break;
    }
    const double pointTolerance = 1e-6 * (query.max - query.min).norm();
    mergeCoplanarManifolds(out, first, pointTolerance, scratch);
}

}  // namespace anyphys::native
