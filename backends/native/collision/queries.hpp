#pragma once
// Per-shape geometric queries, one file each: bounds (bounds.cpp), ray casts (raycast.cpp),
// distance and overlap (distance.cpp, on the GJK of gjk.hpp) and time of impact
// (time_of_impact.cpp).
#include <optional>

#include "collision/shape.hpp"

namespace anyphys::native {

/// Tight bounds of a shape at world pose xf (planes: a very large box; meshes: all vertices).
Aabb computeAabb(const Shape& s, const Transform& xf);

struct RayHit {
    double distance = 0.0;  // along the unit direction
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();  // outward surface normal at the hit
};

/// First hit of origin + t dir (dir unit, 0 <= t <= maxDistance) on the shape at pose xf.
/// A ray starting inside a solid shape reports no hit (a plane is solid below its surface).
/// Meshes are two-sided surfaces: the reported normal is the triangle's, turned to face the ray.
std::optional<RayHit> raycast(const Shape& s, const Transform& xf, const Vec3& origin, const Vec3& dir, double maxDistance);

struct DistanceResult {
    double distance = 0.0;     // >= 0; 0 when overlapping
    Vec3 pointA = Vec3::Zero();
    Vec3 pointB = Vec3::Zero();
    Vec3 normal = Vec3::Zero();  // from A to B (unit) when distance > 0
};

/// Closest points between two convex shapes (sphere, capsule, box, convex) or a convex shape
/// and a plane or mesh (either order), including radii. When the shapes overlap only a little
/// (cores apart, radii crossing) or a convex shape sinks into a plane, the points are the two
/// deepest surface points and `normal` is still set; when the cores overlap, both points are one
/// interior witness and `normal` is zero. Two static shapes (plane, mesh) are not supported:
/// the distance is +infinity.
DistanceResult distance(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB);

/// Time of impact of shape a moving from pose startA to endA (linear interpolation of
/// position, slerp of orientation) against shape b fixed at xfB: the first fraction t in [0, 1]
/// at which their distance falls to `target` (> 0), found by conservative advancement.
/// Returns 1 when they do not come that close, 0 when they start within `target`. The distance
/// at the returned fraction lies in [target, 1.05 target] (or, after 30 iterations without
/// converging, above it: the fraction is always safe). `a` must be convex; `b` may be any
/// shape (a mesh is advanced against triangle by triangle).
double timeOfImpact(const Shape& a, const Transform& startA, const Transform& endA, const Shape& b, const Transform& xfB,
                    double target);

/// True if the shapes overlap (distance 0 or penetrating). Meshes are surfaces: a shape wholly
/// inside a closed mesh does not overlap it.
bool overlap(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB);

}  // namespace anyphys::native
