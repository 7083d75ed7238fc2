#include "collision/manifold_builder.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "collision/feature_id.hpp"

namespace anyphys::native {
namespace {

// Index in `candidates` maximising score, skipping the already chosen ones; -1 if none scores > 0.
template <class Score>
int best(const std::vector<ManifoldPoint>& candidates, const std::array<int, 4>& chosen, int chosenCount, Score score) {
    int result = -1;
    double bestScore = 0;
    for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
        if (std::find(chosen.begin(), chosen.begin() + chosenCount, i) != chosen.begin() + chosenCount) continue;
        if (const double s = score(candidates[i].point); s > bestScore) {
            bestScore = s;
            result = i;
        }
    }
    return result;
}

}  // namespace

double ManifoldBuilder::deepest() const {
    double d = std::numeric_limits<double>::infinity();
    for (const ManifoldPoint& p : points_) d = std::min(d, p.separation);
    return d;
}

bool ManifoldBuilder::finish(Manifold& m) const {
    m.normal = normal_;
    m.pointCount = 0;
    if (points_.empty()) return false;

    std::array<int, 4> chosen{};
    int count = 0;
    if (points_.size() <= 4) {
        for (int i = 0; i < static_cast<int>(points_.size()); ++i) chosen[count++] = i;
    } else {
        // Deepest first: it carries the most load. Areas are measured in the contact plane.
        chosen[count++] = static_cast<int>(std::min_element(points_.begin(), points_.end(),
                                                            [](const ManifoldPoint& x, const ManifoldPoint& y) {
                                                                return x.separation < y.separation;
                                                            }) -
                                           points_.begin());
        const Vec3 p1 = points_[chosen[0]].point;
        const Vec3& n = normal_;
        auto inPlane = [&](const Vec3& v) { return Vec3(v - n * n.dot(v)); };
        if (int i = best(points_, chosen, count, [&](const Vec3& p) { return inPlane(p - p1).squaredNorm(); }); i >= 0)
            chosen[count++] = i;
        if (count == 2) {
            const Vec3 p2 = points_[chosen[1]].point;
            double side = 0;
            if (int i = best(points_, chosen, count, [&](const Vec3& p) { return std::abs((p2 - p1).cross(p - p1).dot(n)); });
                i >= 0) {
                side = (p2 - p1).cross(points_[i].point - p1).dot(n) > 0 ? 1.0 : -1.0;
                chosen[count++] = i;
            }
            if (count == 3) {
                // The point outside the triangle (p1, p2, p3) that adds the largest triangle to it.
                const Vec3 p3 = points_[chosen[2]].point;
                auto added = [&](const Vec3& p) {
                    const double a = -side * (p2 - p1).cross(p - p1).dot(n);
                    const double b = -side * (p3 - p2).cross(p - p2).dot(n);
                    const double c = -side * (p1 - p3).cross(p - p3).dot(n);
                    return std::max({a, b, c});
                };
                if (int i = best(points_, chosen, count, added); i >= 0) chosen[count++] = i;
            }
        }
    }

    for (int k = 0; k < count; ++k) {
        ManifoldPoint p = points_[chosen[k]];
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
