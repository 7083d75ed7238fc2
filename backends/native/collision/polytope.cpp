#include "collision/polytope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace anyphys::native {
namespace {

double farthestFrom(const Vec3& c, std::span<const Vec3> vertices) {
    double r = 0;
    for (const Vec3& v : vertices) r = std::max(r, (v - c).squaredNorm());
    return std::sqrt(r);
}

// The faces on either side of each edge: the face whose loop walks the edge v0 -> v1 is on its
// left, the face walking it back is on its right.
std::vector<std::array<int, 2>> edgeFacesOf(std::span<const std::vector<int>> faces,
                                            std::span<const std::array<int, 2>> edges) {
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

const std::array<Vec3, 6>& boxNormals() {
    static const std::array<Vec3, 6> normals{Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(),
                                             -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
    return normals;
}

const std::vector<std::array<int, 2>>& boxEdgeFaces() {
    static const std::vector<std::array<int, 2>> edgeFaces = edgeFacesOf(boxFaces(), boxEdges());
    return edgeFaces;
}

}  // namespace

int Polytope::localSupport(const Vec3& d) const {
    // A box's farthest corner has the signs of d; an exact tie keeps the bit clear, as the scan
    // below keeps the lowest index.
    if (isBox) return (d.x() > 0 ? 1 : 0) | (d.y() > 0 ? 2 : 0) | (d.z() > 0 ? 4 : 0);
    int best = 0;
    double bestValue = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < vertexCount(); ++i)
        if (const double v = d.dot(vertices[static_cast<std::size_t>(i)]); v > bestValue) {
            bestValue = v;
            best = i;
        }
    return best;
}

std::array<double, 2> Polytope::localProject(const Vec3& d) const {
    if (isBox) {
        const double extent = d.cwiseAbs().dot(vertices[7]);  // corner 7 holds the half sizes
        return {-extent, extent};
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& v : vertices) {
        const double x = d.dot(v);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    return {lo, hi};
}

double Polytope::size() const {
    if (size_ < 0) size_ = farthestFrom(localCentroid_, vertices);
    return size_;
}

double Polytope::localLowest(const Vec3& d) const {
    if (isBox) return -d.cwiseAbs().dot(vertices[7]);
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& v : vertices) lo = std::min(lo, d.dot(v));
    return lo;
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

Polytope::Polytope(HullTag, const HullData& hull, const Mat3& r, const Vec3& p) {
    rotation = r;
    position = p;
    vertices = hull.vertices;
    faces = hull.faces;
    normals = hull.faceNormals;
    offsets = hull.faceOffsets;
    if (!hull.edges.empty() && hull.edgeFaces.size() == hull.edges.size()) {
        edges = hull.edges;
        edgeFaces = hull.edgeFaces;
    } else {
        // Not precomputed: each edge is walked once each way by its two faces; keep the increasing one.
        for (const std::vector<int>& loop : hull.faces)
            for (std::size_t i = 0; i < loop.size(); ++i) {
                const int a = loop[i], b = loop[(i + 1) % loop.size()];
                if (a < b) ownEdges_.push_back({a, b});
            }
        ownEdgeFaces_ = edgeFacesOf(hull.faces, ownEdges_);
        edges = ownEdges_;
        edgeFaces = ownEdgeFaces_;
        // An edge walked by one face only (a vertex in one face's loop that its neighbour's loop
        // skips; the API fuzzer found such a hull) has no face on one side: the Gauss-map edge
        // query needs both, so such a hull takes the full queries. Precomputed topology never has
        // one (computeEdges leaves edgeFaces empty instead), so only this path checks.
        if (std::any_of(edgeFaces.begin(), edgeFaces.end(), [](const std::array<int, 2>& f) { return f[0] < 0 || f[1] < 0; }))
            edgeFaces = {};
    }
    center = p + r * hull.centroid;
    localCentroid_ = hull.centroid;
}

Polytope::Polytope(BoxTag, const Vec3& h, const Mat3& r, const Vec3& c) {
    rotation = r;
    position = c;
    for (int i = 0; i < 8; ++i)
        ownVertices_[static_cast<std::size_t>(i)] =
            Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    for (std::size_t k = 0; k < 3; ++k) ownOffsets_[2 * k] = ownOffsets_[2 * k + 1] = h[static_cast<int>(k)];
    vertices = ownVertices_;
    faces = boxFaces();
    normals = boxNormals();
    offsets = ownOffsets_;
    edges = boxEdges();
    edgeFaces = boxEdgeFaces();
    center = c;
    size_ = h.norm();
    isBox = true;
}

Polytope::Polytope(TriangleTag, const Vec3& a, const Vec3& b, const Vec3& c) {
    static const std::vector<std::vector<int>> triangleFaces{{0, 1, 2}, {0, 2, 1}};
    static const std::vector<std::array<int, 2>> triangleEdges{{0, 1}, {1, 2}, {0, 2}};
    ownVertices_[0] = a;
    ownVertices_[1] = b;
    ownVertices_[2] = c;
    const Vec3 n = (b - a).cross(c - a).normalized();
    ownNormals_ = {n, -n};
    ownOffsets_[0] = n.dot(a);
    ownOffsets_[1] = -n.dot(a);
    vertices = std::span<const Vec3>(ownVertices_.data(), 3);
    faces = triangleFaces;
    normals = ownNormals_;
    offsets = std::span<const double>(ownOffsets_.data(), 2);
    edges = triangleEdges;
    oneSided = true;
    center = (a + b + c) / 3.0;
    localCentroid_ = center;
}

Polytope makeHullPolytope(const HullData& hull, const Mat3& rotation, const Vec3& position) {
    return Polytope(Polytope::HullTag{}, hull, rotation, position);
}

Polytope makeBoxPolytope(const Vec3& halfExtents, const Mat3& rotation, const Vec3& center) {
    return Polytope(Polytope::BoxTag{}, halfExtents, rotation, center);
}

Polytope makeTrianglePolytope(const Vec3& a, const Vec3& b, const Vec3& c) {
    return Polytope(Polytope::TriangleTag{}, a, b, c);
}

}  // namespace anyphys::native
