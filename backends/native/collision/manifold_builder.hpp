#pragma once
// Collects the candidate points of one manifold and reduces them to the four that best keep the
// contact area: the deepest point, the one farthest from it, then the two that add most area.
#include <array>
#include <cassert>
#include <limits>
#include <span>

#include "collision/shape.hpp"

namespace anyphys::native {

class ManifoldBuilder {
public:
    struct Candidate {
        Vec3 point;
        double separation;
        std::uint32_t id;
    };
    /// Enough for every pair of boxes, spheres, capsules, planes and triangles; clipping a hull's
    /// faces can make more, and its caller passes storage for them.
    static constexpr int kInlineCapacity = 16;

    /// `normal`: the manifold normal, unit, from shape a to shape b.
    explicit ManifoldBuilder(const Vec3& normal) : normal_(normal), points_(inline_.data(), inline_.size()) {}
    /// The same, keeping the candidates in `storage` (as many as will be added).
    ManifoldBuilder(const Vec3& normal, std::span<Candidate> storage) : normal_(normal), points_(storage) {}
    ManifoldBuilder(const ManifoldBuilder&) = delete;  // points_ may point into this object
    ManifoldBuilder& operator=(const ManifoldBuilder&) = delete;

    /// A point midway between the surfaces, its separation (negative when overlapping) and id.
    void add(const Vec3& point, double separation, std::uint32_t id) {
        assert(count_ < static_cast<int>(points_.size()) && "ManifoldBuilder: storage too small");
        if (count_ == static_cast<int>(points_.size())) return;
        points_[static_cast<std::size_t>(count_++)] = {point, separation, id};
        deepest_ = std::min(deepest_, separation);
    }

    bool empty() const { return count_ == 0; }
    /// The lowest separation added so far (+infinity when empty).
    double deepest() const { return deepest_; }

    /// Writes at most four points, with pairwise distinct ids, into m; false if there are none.
    bool finish(Manifold& m) const;

private:
    std::array<Candidate, kInlineCapacity> inline_;  // left uninitialised: filled by add()
    Vec3 normal_;
    std::span<Candidate> points_;
    int count_ = 0;
    double deepest_ = std::numeric_limits<double>::infinity();
};

}  // namespace anyphys::native
