#include "collision/gjk.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>

namespace anyphys::native {

ConvexCore ConvexCore::of(const Shape& s, const Transform& xf) {
    ConvexCore c;
    c.rotation_ = xf.orientation.toRotationMatrix();
    c.position_ = xf.position;
    c.posed_ = true;
    switch (s.type) {
        case ShapeType::Sphere:
            c.local_[0] = Vec3::Zero();
            c.count_ = 1;
            c.radius_ = s.radius;
            break;
        case ShapeType::Capsule:
            c.local_[0] = Vec3(0, -s.halfHeight, 0);
            c.local_[1] = Vec3(0, s.halfHeight, 0);
            c.count_ = 2;
            c.radius_ = s.radius;
            break;
        case ShapeType::Box:
            for (int i = 0; i < 8; ++i)
                c.local_[static_cast<std::size_t>(i)] =
                    Vec3(i & 1 ? s.halfExtents.x() : -s.halfExtents.x(), i & 2 ? s.halfExtents.y() : -s.halfExtents.y(),
                         i & 4 ? s.halfExtents.z() : -s.halfExtents.z());
            c.count_ = 8;
            c.isBox_ = true;
            break;
        case ShapeType::Convex:
            if (!s.hull || s.hull->vertices.empty()) throw std::invalid_argument("convex shape without hull");
            c.shared_ = s.hull->vertices;
            c.count_ = static_cast<int>(s.hull->vertices.size());
            break;
        default:
            throw std::invalid_argument("ConvexCore::of: not a convex shape");
    }
    return c;
}

ConvexCore ConvexCore::triangle(const std::array<Vec3, 3>& world) {
    ConvexCore c;
    for (std::size_t i = 0; i < 3; ++i) c.local_[i] = world[i];
    c.count_ = 3;
    return c;
}

ConvexCore ConvexCore::points(std::span<const Vec3> world) {
    if (world.empty()) throw std::invalid_argument("ConvexCore::points: no points");
    ConvexCore c;
    c.shared_ = world;
    c.count_ = static_cast<int>(world.size());
    return c;
}

ConvexCore ConvexCore::posedPoints(std::span<const Vec3> local, const Mat3& rotation, const Vec3& position) {
    ConvexCore c = points(local);
    c.rotation_ = rotation;
    c.position_ = position;
    c.posed_ = true;
    return c;
}

namespace {

struct SimplexVertex {
    Vec3 wA = Vec3::Zero();  // support point on A
    Vec3 wB = Vec3::Zero();  // support point on B
    Vec3 w = Vec3::Zero();   // wB - wA: a point of the Minkowski difference B - A
    int iA = 0;
    int iB = 0;
    double bary = 1.0;
};

struct Simplex {
    std::array<SimplexVertex, 4> v;
    int count = 0;
};

/// Closest point to the origin of a sub-simplex: which vertices (indices into the simplex) and
/// their barycentric weights.
struct Closest {
    std::array<int, 3> index{};
    std::array<double, 3> bary{};
    int count = 0;
    Vec3 point = Vec3::Zero();
};

Closest closestOnSegment(const Simplex& s, int ia, int ib) {
    const Vec3& a = s.v[static_cast<std::size_t>(ia)].w;
    const Vec3& b = s.v[static_cast<std::size_t>(ib)].w;
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? -a.dot(ab) / len2 : 0.0;
    if (t <= 0.0) return {{ia, 0, 0}, {1.0, 0, 0}, 1, a};
    if (t >= 1.0) return {{ib, 0, 0}, {1.0, 0, 0}, 1, b};
    return {{ia, ib, 0}, {1.0 - t, t, 0}, 2, a + t * ab};
}

// Voronoi-region walk (Ericson, Real-Time Collision Detection 5.1.5) with the query point at
// the origin; a degenerate (flat) triangle falls back to its best edge.
Closest closestOnTriangle(const Simplex& s, int ia, int ib, int ic) {
    const Vec3& a = s.v[static_cast<std::size_t>(ia)].w;
    const Vec3& b = s.v[static_cast<std::size_t>(ib)].w;
    const Vec3& c = s.v[static_cast<std::size_t>(ic)].w;
    const Vec3 ab = b - a;
    const Vec3 ac = c - a;
    const double d1 = -ab.dot(a);
    const double d2 = -ac.dot(a);
    if (d1 <= 0.0 && d2 <= 0.0) return {{ia, 0, 0}, {1.0, 0, 0}, 1, a};
    const double d3 = -ab.dot(b);
    const double d4 = -ac.dot(b);
    if (d3 >= 0.0 && d4 <= d3) return {{ib, 0, 0}, {1.0, 0, 0}, 1, b};
    const double d5 = -ab.dot(c);
    const double d6 = -ac.dot(c);
    if (d6 >= 0.0 && d5 <= d6) return {{ic, 0, 0}, {1.0, 0, 0}, 1, c};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) return closestOnSegment(s, ia, ib);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) return closestOnSegment(s, ia, ic);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) return closestOnSegment(s, ib, ic);
    const double denom = va + vb + vc;
    if (!(denom > 1e-300)) {
        Closest best = closestOnSegment(s, ia, ib);
        for (const Closest& e : {closestOnSegment(s, ia, ic), closestOnSegment(s, ib, ic)})
            if (e.point.squaredNorm() < best.point.squaredNorm()) best = e;
        return best;
    }
    const double v = vb / denom;
    const double w = vc / denom;
    return {{ia, ib, ic}, {1.0 - v - w, v, w}, 3, a + v * ab + w * ac};
}

/// Closest point of a tetrahedron's boundary faces that the origin lies beyond (each tested
/// against the opposite vertex; a flat tetrahedron puts every face under test); nullopt when the
/// origin is inside.
std::optional<Closest> closestOnTetrahedron(const Simplex& s) {
    constexpr int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
    std::optional<Closest> best;
    for (const auto& f : faces) {
        const Vec3& p = s.v[static_cast<std::size_t>(f[0])].w;
        const Vec3 n = (s.v[static_cast<std::size_t>(f[1])].w - p).cross(s.v[static_cast<std::size_t>(f[2])].w - p);
        const double sideOrigin = -n.dot(p);
        const double sideOpposite = n.dot(s.v[static_cast<std::size_t>(f[3])].w - p);
        if (sideOrigin * sideOpposite > 0.0) continue;
        const Closest c = closestOnTriangle(s, f[0], f[1], f[2]);
        if (!best || c.point.squaredNorm() < best->point.squaredNorm()) best = c;
    }
    return best;
}

/// Reduces the simplex to the vertices supporting its closest point to the origin; returns
/// false when the origin is inside the tetrahedron (the shapes overlap).
bool solveSimplex(Simplex& s, Vec3& closest) {
    std::optional<Closest> c;
    switch (s.count) {
        case 1: c = Closest{{0, 0, 0}, {1.0, 0, 0}, 1, s.v[0].w}; break;
        case 2: c = closestOnSegment(s, 0, 1); break;
        case 3: c = closestOnTriangle(s, 0, 1, 2); break;
        default: c = closestOnTetrahedron(s); break;
    }
    if (!c) return false;
    std::array<SimplexVertex, 3> kept;
    for (std::size_t i = 0; i < static_cast<std::size_t>(c->count); ++i) {
        kept[i] = s.v[static_cast<std::size_t>(c->index[i])];
        kept[i].bary = c->bary[i];
    }
    std::copy(kept.begin(), kept.begin() + c->count, s.v.begin());
    s.count = c->count;
    closest = c->point;
    return true;
}

SimplexVertex makeVertex(const ConvexCore& a, const ConvexCore& b, int iA, int iB) {
    SimplexVertex v;
    v.iA = iA;
    v.iB = iB;
    v.wA = a.vertex(iA);
    v.wB = b.vertex(iB);
    v.w = v.wB - v.wA;
    return v;
}

// The vertex minimising dir . (wB - wA).
SimplexVertex supportVertex(const ConvexCore& a, const ConvexCore& b, const Vec3& dir) {
    return makeVertex(a, b, a.support(dir), b.support(-dir));
}

// The distinct, increasing core indices of the simplex vertices that carry weight: the feature
// of one side that the closest point lies on.
template <class IndexOf>
CoreFeature featureOf(const Simplex& s, IndexOf indexOf) {
    CoreFeature f;
    for (int i = 0; i < s.count; ++i) {
        const SimplexVertex& sv = s.v[static_cast<std::size_t>(i)];
        if (sv.bary == 0.0) continue;
        const int k = indexOf(sv);
        if (std::find(f.begin(), f.end(), k) != f.end()) continue;
        // Insertion keeps the (at most four) indices sorted.
        std::size_t j = static_cast<std::size_t>(f.count++);
        for (; j > 0 && f.index[j - 1] > k; --j) f.index[j] = f.index[j - 1];
        f.index[j] = k;
    }
    return f;
}

GjkResult run(const ConvexCore& a, const ConvexCore& b, const SimplexVertex& first, double overlapTolerance) {
    Simplex s;
    s.v[0] = first;
    s.count = 1;

    GjkResult out;
    const double touching2 = overlapTolerance * overlapTolerance;
    constexpr int kMaxIterations = 64;
    for (int iter = 0;; ++iter) {
        // The vertices before reduction: a support point among them means no progress is
        // possible (the main termination test, as in Box2D; it also stops cycling).
        const Simplex before = s;
        Vec3 v;
        if (!solveSimplex(s, v)) {
            // Origin inside the tetrahedron: report its centroid as the (meaningless) witness.
            for (SimplexVertex& sv : s.v) sv.bary = 0.25;
            out.overlap = true;
            break;
        }
        const double vv = v.squaredNorm();
        if (vv < touching2) {
            out.overlap = true;
            break;
        }
        if (iter == kMaxIterations) break;
        const SimplexVertex next = supportVertex(a, b, v);
        bool repeated = false;
        double scale = next.w.squaredNorm();
        for (int i = 0; i < before.count; ++i) {
            const SimplexVertex& sv = before.v[static_cast<std::size_t>(i)];
            repeated = repeated || (sv.iA == next.iA && sv.iB == next.iB);
            scale = std::max(scale, sv.w.squaredNorm());
        }
        // No new vertex, or no progress toward the origin beyond rounding (v carries an error
        // of about 1e-16 times the simplex's size, so v.w does too): v is the answer.
        if (repeated || vv - v.dot(next.w) <= 1e-12 * vv + 1e-14 * scale) break;
        s.v[static_cast<std::size_t>(s.count++)] = next;
    }
    for (int i = 0; i < s.count; ++i) {
        const SimplexVertex& sv = s.v[static_cast<std::size_t>(i)];
        out.pointA += sv.bary * sv.wA;
        out.pointB += sv.bary * sv.wB;
    }
    out.distance = out.overlap ? 0.0 : (out.pointB - out.pointA).norm();
    out.featureA = featureOf(s, [](const SimplexVertex& sv) { return sv.iA; });
    out.featureB = featureOf(s, [](const SimplexVertex& sv) { return sv.iB; });
    return out;
}

}  // namespace

GjkResult gjk(const ConvexCore& a, const ConvexCore& b, const Vec3& initialDir, double overlapTolerance) {
    return run(a, b, supportVertex(a, b, initialDir.squaredNorm() > 0.0 ? initialDir : Vec3::UnitX()), overlapTolerance);
}

GjkResult gjkFromFirstVertices(const ConvexCore& a, const ConvexCore& b, double overlapTolerance) {
    return run(a, b, makeVertex(a, b, 0, 0), overlapTolerance);
}

}  // namespace anyphys::native
