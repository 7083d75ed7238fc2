#pragma once
// Convex hulls of point clouds (quickhull) with the mass properties a rigid body needs.
#include <memory>
#include <vector>

#include "anyphys/math.hpp"
#include "anyphys/peers/shape_data.hpp"

namespace anyphys {

/// The convex hull of `points` (shape frame): only the points on the hull are kept, coplanar
/// triangles are merged into polygon faces (counter-clockwise seen from outside), and volume,
/// centroid and inertia per unit mass are computed for uniform density. Tolerances are relative
/// to the extent of the points, so the result does not depend on the unit of length.
/// Throws anyphys::Error when the points do not span a volume (fewer than 4, or all coplanar).
std::shared_ptr<const HullData> buildConvexHull(const std::vector<Vec3>& points);

/// A box with the given half sizes as a hull, centred on the origin. Vertex i has coordinate k
/// positive when bit k of i is set; face 2k + 0 has normal +e_k and face 2k + 1 has -e_k.
HullData makeBoxHull(const Vec3& halfExtents);

}  // namespace anyphys
