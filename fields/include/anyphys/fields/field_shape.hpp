#pragma once
// The geometry a field needs of a body: its primitive shapes placed in a frame of the body, with
// the faces of convex hulls. Built once per body by the world, read by every field.
#include <memory>
#include <vector>

#include "anyphys/enums.hpp"
#include "anyphys/fields/triangle_mesh.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

/// A convex polyhedron: vertices and faces (vertex indices, counter-clockwise seen from outside).
struct ConvexFaces {
    std::vector<Vec3> vertices;
    std::vector<std::vector<int>> faces;
};

/// One primitive (sphere, box, capsule, convex, plane or triangle mesh) placed in the body frame the caller chooses.
struct FieldShape {
    ShapeType type = ShapeType::Sphere;
    double radius = 0.0;                     ///< sphere, capsule
    Vec3 halfExtents = Vec3::Zero();         ///< box
    double halfHeight = 0.0;                 ///< capsule: half the core segment, along the shape's Y
    std::shared_ptr<const ConvexFaces> hull; ///< convex: the hull, in the shape frame
    std::shared_ptr<const TriangleMesh> mesh; ///< mesh: triangles and their culling grid, shape frame
    Vec3 normal = Vec3::UnitY();             ///< plane: unit normal, world frame (a plane is static)
    double offset = 0.0;                     ///< plane: normal . x == offset, world frame
    Transform local;                         ///< the shape's pose in the body frame
    bool sensor = false;                     ///< a compound's sensor child: counts for volume and mass, particles pass it
};

/// The volume of a primitive (m^3).
double shapeVolume(const FieldShape& shape);

/// The box [-h, h] as a polyhedron: vertex i has coordinate k positive when bit k of i is set.
ConvexFaces boxFaces(const Vec3& halfExtents);

}  // namespace anyphys
