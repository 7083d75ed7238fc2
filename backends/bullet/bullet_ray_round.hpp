#pragma once
// Where a ray enters a capsule (or a sphere: a capsule of one point), in closed form. Bullet casts
// a ray at a convex shape with an iterative convex cast whose tolerance left a capsule's hit
// millimetres off (3.7 mm late on a 1 cm capsule, 7.8 mm on a 10 m one) and a sphere's normal 4.6e-5
// off (3.5e-4 on a 1 cm one), where the layer's other backends are exact to rounding; its GJK cast
// is exact for capsules but not for spheres. The queries keep Bullet's cast for finding the shape
// and take the hit from here.
#include <optional>

#include "anyphys/math.hpp"

namespace anyphys::bullet {

struct RayEntry {
    double distance;  ///< along the unit direction
    Vec3 normal;      ///< outward unit normal where the ray enters
};

/// The first point at which the ray origin + t direction (unit direction, 0 <= t <= maxDistance)
/// enters the capsule of axis segment a-b (a sphere when a == b) and `radius`; none if it misses, or if the origin is
/// inside the capsule (a shape that holds the ray's origin is not hit).
std::optional<RayEntry> rayIntoCapsule(const Vec3& origin, const Vec3& direction, double maxDistance, const Vec3& a,
                                       const Vec3& b, double radius);

}  // namespace anyphys::bullet
