#pragma once
// The exact part of a shape below a plane (the fluid is { x : normal . x < offset }, normal unit):
// its volume and centroid, the centre of buoyancy.
//
// Boxes and convex hulls are clipped as polyhedra (exact up to rounding); spheres use the
// spherical cap (exact); capsules are integrated along their axis over discs cut by the plane's
// trace, whose areas and centroids are exact (circular segments), with Gauss-Legendre quadrature
// split where the integrand has kinks: relative error below 1e-9 of the capsule's volume in the
// unit tests (tests/unit/test_submerged_volume.cpp). A shape wholly above or below the plane is
// recognised first, exactly and cheaply.
#include <vector>

#include "anyphys/fields/field_shape.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

/// The fluid's side of a plane: points with normal . x < offset (normal unit, pointing out of the fluid).
struct FluidPlane {
    Vec3 normal = Vec3(0, 1, 0);
    double offset = 0.0;
    double height(const Vec3& x) const { return normal.dot(x) - offset; }
};

struct SubmergedVolume {
    double volume = 0.0;              ///< m^3
    Vec3 centroid = Vec3::Zero();     ///< the centre of buoyancy (meaningless when volume is 0)

    /// Adds another part (volume-weighted centroid).
    SubmergedVolume& operator+=(const SubmergedVolume& other);
};

/// A sphere of radius r centred at `center` (world frame).
SubmergedVolume submergedSphere(double radius, const Vec3& center, const FluidPlane& fluid);
/// A box with these half sizes at `pose` (world frame).
SubmergedVolume submergedBox(const Vec3& halfExtents, const Transform& pose, const FluidPlane& fluid);
/// A capsule (core segment along the pose's Y, from -halfHeight to +halfHeight) at `pose`.
SubmergedVolume submergedCapsule(double radius, double halfHeight, const Transform& pose, const FluidPlane& fluid);
/// A convex polyhedron (faces counter-clockwise seen from outside) placed at `pose`.
SubmergedVolume submergedConvex(const ConvexFaces& hull, const Transform& pose, const FluidPlane& fluid);
/// One primitive of a body whose frame is at `bodyPose`.
SubmergedVolume submergedShape(const FieldShape& shape, const Transform& bodyPose, const FluidPlane& fluid);
/// Every primitive of a body (a compound's children one by one).
SubmergedVolume submergedShapes(const std::vector<FieldShape>& shapes, const Transform& bodyPose, const FluidPlane& fluid);

}  // namespace anyphys
