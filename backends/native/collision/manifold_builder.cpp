#include "collision/manifold_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "collision/feature_id.hpp"

namespace anyphys::native {

namespace {

using Candidate = ManifoldBuilder::Candidate;
using Point2 = std::array<double, 2>;

// Twice the signed area of triangle (a, b, p).
double area(const Point2& a, const Point2& b, const Point2& p) {
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

// Chooses up to four of the candidates: the deepest, the farthest from it, the one making the
// largest triangle with those, and the one adding the largest triangle outside it. `at(i)`: the
// coordinates of candidate i in the contact plane.
template <class At>
int reduce(std::span<const Candidate> points, At at, std::array<int, 4>& chosen) {
    int count = 0;
    auto isChosen = [&](int i) { return std::find(chosen.begin(), chosen.begin() + count, i) != chosen.begin() + count; };
    // Index maximising score among the candidates not yet chosen; -1 if none scores > 0.
    auto best = [&](auto score) {
        int result = -1;
        double bestScore = 0;
        for (int i = 0; i < static_cast<int>(points.size()); ++i)
            if (const double s = score(at(i)); s > bestScore && !isChosen(i)) {
                bestScore = s;
                result = i;
            }
        return result;
    };
    // Deepest first: it carries the most load.
    chosen[static_cast<std::size_t>(count++)] = static_cast<int>(
        std::min_element(points.begin(), points.end(),
                         [](const Candidate& x, const Candidate& y) { return x.separation < y.separation; }) -
        points.begin());
    const Point2 p1 = at(chosen[0]);
    const int second = best([&](const Point2& p) {
        const double dx = p[0] - p1[0], dy = p[1] - p1[1];
        return dx * dx + dy * dy;
    });
    if (second < 0) return count;
    chosen[static_cast<std::size_t>(count++)] = second;
    const Point2 p2 = at(second);
    const int third = best([&](const Point2& p) { return std::abs(area(p1, p2, p)); });
    if (third < 0) return count;
    chosen[static_cast<std::size_t>(count++)] = third;
    const Point2 p3 = at(third);
    const double side = area(p1, p2, p3) > 0 ? 1.0 : -1.0;
    // The point outside the triangle (p1, p2, p3) that adds the largest triangle to it.
    const int fourth = best([&](const Point2& p) {
        return std::max({-side * area(p1, p2, p), -side * area(p2, p3, p), -side * area(p3, p1, p)});
    });
    if (fourth >= 0) chosen[static_cast<std::size_t>(count++)] = fourth;
    return count;
}

}  // namespace

bool ManifoldBuilder::finish(Manifold& m) const {
    m.normal = normal_;
    m.pointCount = 0;
    if (count_ == 0) return false;
    const std::span<const Candidate> points = points_.first(static_cast<std::size_t>(count_));

    std::array<int, 4> chosen{};
    int count = 0;
    if (count_ <= 4) {
        for (int i = 0; i < count_; ++i) chosen[static_cast<std::size_t>(count++)] = i;
    } else {
        // Areas are measured in the contact plane, on coordinates along two unit vectors spanning
        // it; a few candidates are measured once, many as they are needed.
        const Vec3 u = normal_.unitOrthogonal(), v = normal_.cross(u);
        auto measure = [&](int i) -> Point2 {
            const Vec3& p = points[static_cast<std::size_t>(i)].point;
            return {u.dot(p), v.dot(p)};
        };
        if (count_ <= kInlineCapacity) {
            std::array<Point2, kInlineCapacity> plane;
            for (int i = 0; i < count_; ++i) plane[static_cast<std::size_t>(i)] = measure(i);
            count = reduce(points, [&](int i) -> const Point2& { return plane[static_cast<std::size_t>(i)]; }, chosen);
        } else {
            count = reduce(points, measure, chosen);
        }
    }

    for (int k = 0; k < count; ++k) {
        const Candidate& c = points[static_cast<std::size_t>(chosen[static_cast<std::size_t>(k)])];
        ManifoldPoint p{c.point, c.separation, c.id};
        // Ids must be distinct within a manifold; a hash collision is re-hashed deterministically.
        for (int j = 0; j < m.pointCount; ++j)
            if (m.points[j].id == p.id) {
                p.id = feature::mix(p.id + 1);
                j = -1;
            }
        m.points[m.pointCount++] = p;
    }
    return true;
}

}  // namespace anyphys::native
