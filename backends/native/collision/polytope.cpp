#include "collision/polytope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace anyphys::native {
namespace {

double farthestFrom(const Vec3& c, const std::vector<Vec3>& vertices) {
    double r = 0;
    for (const Vec3& v : vertices) r = std::max(r, (v - c).squaredNorm());
    return std::sqrt(r);
}

// The faces on either side of each edge: the face whose loop walks the edge v0 -> v1 is on its
// left, the face walking it back is on its right.
std::vector<std::array<int, 2>> edgeFacesOf(const std::vector<std::vector<int>>& faces,
                                            const std::vector<std::array<int, 2>>& edges) {
    struct Directed {
        int from, to, face;
        bool operator<(const Directed& o) const { return from != o.from ? from < o.from : to < o.to; }
    };
    std::vector<Directed> walked;
    for (int f = 0; f < static_cast<int>(faces.size()); ++f)
        for (std::size_t i = 0; i < faces[f].size(); ++i)
            walked.push_back({faces[f][i], faces[f][(i + 1) % faces[f].size()], f});
    std::sort(walked.begin(), walked.end());
    auto faceWalking = [&](int from, int to) {
        const auto it = std::lower_bound(walked.begin(), walked.end(), Directed{from, to, 0});
        return it != walked.end() && it->from == from && it->to == to ? it->face : -1;
    };
    std::vector<std::array<int, 2>> result;
    result.reserve(edges.size());
    for (const auto& [v, w] : edges) result.push_back({faceWalking(v, w), faceWalking(w, v)});
    return result;
}

}  // namespace

int Polytope::support(const Vec3& d) const {
    int best = 0;
    double bestValue = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(vertices.size()); ++i)
        if (const double v = d.dot(vertices[i]); v > bestValue) {
            bestValue = v;
            best = i;
        }
    return best;
}

std::array<double, 2> Polytope::project(const Vec3& d) const {
    std::array<double, 2> range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const Vec3& v : vertices) {
        const double x = d.dot(v);
        range[0] = std::min(range[0], x);
        range[1] = std::max(range[1], x);
    }
    return range;
}

const std::vector<std::array<int, 2>>& boxEdges() {
    // Corner pairs differing in one bit: 4 edges along each axis.
    static const std::vector<std::array<int, 2>> edges = [] {
        std::vector<std::array<int, 2>> e;
        for (int axis = 0; axis < 3; ++axis)
            for (int v = 0; v < 8; ++v)
                if (!(v & (1 << axis))) e.push_back({v, v | (1 << axis)});
        return e;
    }();
    return edges;
}

const std::vector<std::vector<int>>& boxFaces() {
    static const std::vector<std::vector<int>> faces{{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3},
                                                     {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
    return faces;
}

namespace {
const std::vector<std::array<int, 2>>& boxEdgeFaces() {
    static const std::vector<std::array<int, 2>> edgeFaces = edgeFacesOf(boxFaces(), boxEdges());
    return edgeFaces;
}
}  // namespace

Polytope makeHullPolytope(const HullData& hull, const Transform& xf) {
    Polytope p;
    const Mat3 r = xf.orientation.toRotationMatrix();
    p.vertices.reserve(hull.vertices.size());
    for (const Vec3& v : hull.vertices) p.vertices.push_back(xf.position + r * v);
    p.faces = &hull.faces;
    p.normals.reserve(hull.faces.size());
    p.offsets.reserve(hull.faces.size());
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
        const Vec3 n = r * hull.faceNormals[f];
        p.normals.push_back(n);
        p.offsets.push_back(hull.faceOffsets[f] + n.dot(xf.position));
    }
    if (!hull.edges.empty() && hull.edgeFaces.size() == hull.edges.size()) {
        p.sharedEdges = &hull.edges;
        p.sharedEdgeFaces = &hull.edgeFaces;
    } else {
        // Not precomputed: each edge is walked once each way by its two faces; keep the increasing one.
        for (const std::vector<int>& loop : hull.faces)
            for (std::size_t i = 0; i < loop.size(); ++i) {
                const int a = loop[i], b = loop[(i + 1) % loop.size()];
                if (a < b) p.ownEdges.push_back({a, b});
            }
        p.ownEdgeFaces = edgeFacesOf(hull.faces, p.ownEdges);
    }
    p.center = xf.position + r * hull.centroid;
    p.size = farthestFrom(p.center, p.vertices);
    return p;
}

Polytope makeBoxPolytope(const Vec3& halfExtents, const Transform& xf) {
    return makeBoxPolytope(halfExtents, xf.position, xf.orientation.toRotationMatrix());
}

Polytope makeBoxPolytope(const Vec3& halfExtents, const Vec3& center, const Mat3& r) {
    Polytope p;
    p.vertices.reserve(8);
    for (int i = 0; i < 8; ++i) {
        const Vec3 local((i & 1) ? halfExtents.x() : -halfExtents.x(), (i & 2) ? halfExtents.y() : -halfExtents.y(),
                         (i & 4) ? halfExtents.z() : -halfExtents.z());
        p.vertices.push_back(center + r * local);
    }
    p.faces = &boxFaces();
    for (int k = 0; k < 3; ++k) {
        const Vec3 axis = r.col(k);
        p.normals.push_back(axis);
        p.offsets.push_back(axis.dot(center) + halfExtents[k]);
        p.normals.push_back(-axis);
        p.offsets.push_back(-axis.dot(center) + halfExtents[k]);
    }
    p.sharedEdges = &boxEdges();
    p.sharedEdgeFaces = &boxEdgeFaces();
    p.center = center;
    p.size = halfExtents.norm();
    return p;
}

Polytope makeTrianglePolytope(const Vec3& a, const Vec3& b, const Vec3& c) {
    static const std::vector<std::vector<int>> faces{{0, 1, 2}, {0, 2, 1}};
    static const std::vector<std::array<int, 2>> edges{{0, 1}, {1, 2}, {0, 2}};
    Polytope p;
    p.vertices = {a, b, c};
    p.faces = &faces;
    const Vec3 n = (b - a).cross(c - a).normalized();
    p.normals = {n, -n};
    p.offsets = {n.dot(a), -n.dot(a)};
    p.sharedEdges = &edges;
    p.oneSided = true;
    p.center = (a + b + c) / 3.0;
    p.size = farthestFrom(p.center, p.vertices);
    return p;
}

}  // namespace anyphys::native
