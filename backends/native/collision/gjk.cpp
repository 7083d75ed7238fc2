#include "collision/gjk.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace anyphys::native {
namespace {

struct SimplexVertex {
    Vec3 w = Vec3::Zero();  // a[ia] - b[ib]
    int ia = 0, ib = 0;
};

// Up to four vertices with barycentric weights of the point closest to the origin.
struct Simplex {
    std::array<SimplexVertex, 4> v{};
    std::array<double, 4> weight{};
    int count = 0;

    Vec3 closest() const {
        Vec3 p = Vec3::Zero();
        for (int i = 0; i < count; ++i) p += weight[i] * v[i].w;
        return p;
    }
    void keep(std::initializer_list<std::pair<int, double>> kept) {
        std::array<SimplexVertex, 4> nv{};
        std::array<double, 4> nw{};
        int n = 0;
        for (const auto& [i, w] : kept) {
            nv[n] = v[i];
            nw[n++] = w;
        }
        v = nv;
        weight = nw;
        count = n;
    }
};

void solveSegment(Simplex& s, int i, int j) {
    const Vec3 a = s.v[i].w, ab = s.v[j].w - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? -a.dot(ab) / len2 : 0.0;
    if (t <= 0) s.keep({{i, 1.0}});
    else if (t >= 1) s.keep({{j, 1.0}});
    else s.keep({{i, 1 - t}, {j, t}});
}

// Voronoi regions of triangle (i, j, k) for the origin (Ericson, Real-Time Collision Detection 5.1.5).
void solveTriangle(Simplex& s, int i, int j, int k) {
    const Vec3 a = s.v[i].w, b = s.v[j].w, c = s.v[k].w;
    const Vec3 ab = b - a, ac = c - a;
    const double d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0 && d2 <= 0) return s.keep({{i, 1.0}});
    const double d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0 && d4 <= d3) return s.keep({{j, 1.0}});
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double t = d1 / (d1 - d3);
        return s.keep({{i, 1 - t}, {j, t}});
    }
    const double d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0 && d5 <= d6) return s.keep({{k, 1.0}});
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double t = d2 / (d2 - d6);
        return s.keep({{i, 1 - t}, {k, t}});
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return s.keep({{j, 1 - t}, {k, t}});
    }
    const double sum = va + vb + vc;
    if (sum <= 0) {  // degenerate (collinear) triangle: its closest point is on an edge
        Simplex best;
        double bestDistance = std::numeric_limits<double>::infinity();
        for (auto [p, q] : {std::pair{i, j}, std::pair{j, k}, std::pair{i, k}}) {
            Simplex t = s;
            solveSegment(t, p, q);
            if (const double d = t.closest().squaredNorm(); d < bestDistance) {
                bestDistance = d;
                best = t;
            }
        }
        s = best;
        return;
    }
    s.keep({{i, va / sum}, {j, vb / sum}, {k, vc / sum}});
}

// Returns false when the origin is inside the tetrahedron.
bool solveTetrahedron(Simplex& s) {
    static constexpr std::array<std::array<int, 4>, 4> faces{{{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}}};
    bool flat = false, outsideAny = false;
    std::array<bool, 4> outside{};
    for (int f = 0; f < 4; ++f) {
        const auto [i, j, k, l] = faces[f];
        const Vec3 a = s.v[i].w;
        const Vec3 n = (s.v[j].w - a).cross(s.v[k].w - a);
        const Vec3 toL = s.v[l].w - a;
        const double sideL = n.dot(toL), sideO = -n.dot(a);
        if (sideL * sideL <= 1e-20 * n.squaredNorm() * toL.squaredNorm()) flat = true;
        outside[f] = sideO * sideL < 0;
        outsideAny = outsideAny || outside[f];
    }
    if (!outsideAny && !flat) return false;
    Simplex best;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int f = 0; f < 4; ++f) {
        if (!flat && !outside[f]) continue;
        Simplex t = s;
        solveTriangle(t, faces[f][0], faces[f][1], faces[f][2]);
        if (const double d = t.closest().squaredNorm(); d < bestDistance) {
            bestDistance = d;
            best = t;
        }
    }
    s = best;
    return true;
}

int support(std::span<const Vec3> points, const Vec3& d) {
    int best = 0;
    double bestValue = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(points.size()); ++i)
        if (const double v = d.dot(points[i]); v > bestValue) {
            bestValue = v;
            best = i;
        }
    return best;
}

}  // namespace

GjkResult gjkDistance(std::span<const Vec3> a, std::span<const Vec3> b, double tolerance) {
    Simplex s;
    s.v[0] = {a[0] - b[0], 0, 0};
    s.weight[0] = 1;
    s.count = 1;
    bool overlap = false;
    for (int iteration = 0; iteration < 64; ++iteration) {
        const Vec3 v = s.closest();
        const double vv = v.squaredNorm();
        if (vv <= tolerance * tolerance) {
            overlap = true;
            break;
        }
        const int ia = support(a, -v), ib = support(b, v);
        const Vec3 w = a[ia] - b[ib];
        // No vertex reaches meaningfully closer to the origin: v is the closest point.
        if (vv - v.dot(w) <= 1e-12 * vv) break;
        if (std::any_of(s.v.begin(), s.v.begin() + s.count, [&](const SimplexVertex& x) { return x.ia == ia && x.ib == ib; }))
            break;
        s.v[s.count] = {w, ia, ib};
        s.weight[s.count++] = 0;
        if (s.count == 2) solveSegment(s, 0, 1);
        else if (s.count == 3) solveTriangle(s, 0, 1, 2);
        else if (!solveTetrahedron(s)) {
            overlap = true;
            break;
        }
    }

    GjkResult r;
    if (overlap && s.count == 4) {
        // Origin inside: the weights are not meaningful; report the first vertex pair.
        r.onA = a[s.v[0].ia];
        r.onB = r.onA;
    } else {
        for (int i = 0; i < s.count; ++i) {
            r.onA += s.weight[i] * a[s.v[i].ia];
            r.onB += s.weight[i] * b[s.v[i].ib];
        }
    }
    r.distance = overlap ? 0.0 : (r.onA - r.onB).norm();
    for (int i = 0; i < s.count; ++i) {
        r.featureA.push_back(s.v[i].ia);
        r.featureB.push_back(s.v[i].ib);
    }
    for (std::vector<int>* f : {&r.featureA, &r.featureB}) {
        std::sort(f->begin(), f->end());
        f->erase(std::unique(f->begin(), f->end()), f->end());
    }
    return r;
}

}  // namespace anyphys::native
