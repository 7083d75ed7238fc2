#pragma once
// Narrow phase: contact manifolds between two shapes.
#include <vector>

#include "collision/shape.hpp"

namespace anyphys::native {

/// Appends the manifolds of shapes a and b at world poses xfA and xfB (shape frames, i.e.
/// shapeWorldPose(...)): one for a pair of convex shapes, one per touched triangle against a
/// mesh. Only points with separation < speculativeDistance are produced; a manifold without
/// points is not appended. Normals point from a to b whatever order the routine used inside.
/// Planes and meshes are static: a pair of two static shapes never reaches this function.
void collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculativeDistance,
             std::vector<Manifold>& out);

}  // namespace anyphys::native
