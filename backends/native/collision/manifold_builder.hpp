#pragma once
// Collects the candidate points of one manifold and reduces them to the four that best keep the
// contact area: the deepest point, the one farthest from it, then the two that add most area.
#include <vector>

#include "collision/shape.hpp"

namespace anyphys::native {

class ManifoldBuilder {
public:
    /// `normal`: the manifold normal, unit, from shape a to shape b.
    explicit ManifoldBuilder(const Vec3& normal) : normal_(normal) {}

    /// A point midway between the surfaces, its separation (negative when overlapping) and id.
    void add(const Vec3& point, double separation, std::uint32_t id) { points_.push_back({point, separation, id}); }

    bool empty() const { return points_.empty(); }
    /// The lowest separation added so far (+infinity when empty).
    double deepest() const;

    /// Writes at most four points, with pairwise distinct ids, into m; false if there are none.
    bool finish(Manifold& m) const;

private:
    Vec3 normal_;
    std::vector<ManifoldPoint> points_;
};

}  // namespace anyphys::native
