#pragma once
// Distance between the convex hulls of two small point sets (GJK with the closest-point
// sub-algorithm on the simplex; Gilbert, Johnson, Keerthi 1988).
#include <span>
#include <vector>

#include "anyphys/math.hpp"

namespace anyphys::native {

struct GjkResult {
    double distance = 0.0;        // 0 when the hulls overlap (or are within `tolerance`)
    Vec3 onA = Vec3::Zero();      // closest point of hull(a)
    Vec3 onB = Vec3::Zero();      // closest point of hull(b)
    std::vector<int> featureA;    // indices of the a points spanning the closest feature, increasing
    std::vector<int> featureB;    // same for b
};

/// Closest points of hull(a) and hull(b) (both non-empty). Distances below `tolerance` count as
/// overlap: the caller must then use another method for the contact normal.
GjkResult gjkDistance(std::span<const Vec3> a, std::span<const Vec3> b, double tolerance);

}  // namespace anyphys::native
