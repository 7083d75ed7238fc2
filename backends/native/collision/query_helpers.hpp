#pragma once
// Pieces the query files (bounds, distance, time_of_impact, raycast) share.
#include <limits>

#include "collision/gjk.hpp"
#include "collision/queries.hpp"

namespace anyphys::native {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline bool isConvex(ShapeType t) {
    return t == ShapeType::Sphere || t == ShapeType::Capsule || t == ShapeType::Box || t == ShapeType::Convex;
}

inline Transform inverse(const Transform& xf) {
    const Quat qInv = xf.orientation.conjugate();
    return {qInv * (-xf.position), qInv};
}

/// a after b: b's frame placed in a's.
inline Transform compose(const Transform& a, const Transform& b) {
    return {a.position + a.orientation * b.position, a.orientation * b.orientation};
}

inline Vec3 apply(const Transform& xf, const Vec3& p) { return xf.position + xf.orientation * p; }

/// Closest points of two convex shapes given by their cores, radii included (distance.cpp).
/// `initialDir` (from a toward b) seeds GJK.
DistanceResult convexDistance(const ConvexCore& a, const ConvexCore& b, const Vec3& initialDir);

}  // namespace anyphys::native
