#pragma once
// Boxes and capsules against triangle meshes. ODE's box-trimesh and capsule-trimesh colliders
// (OPCODE; collision_trimesh_box.cpp, collision_trimesh_ccylinder.cpp) test every touched triangle
// as if it stood alone, and a body sliding over a flat mesh of 1 m squares at 5 m/s did not slide
// as on a box: a 0.5 m box bounced at 0.1 m/s, a 0.1 m one sliding diagonally spun at 39 rad/s
// and lost 14 % of its speed, a capsule lost 2 % (docs/architecture.md). Three causes:
// - Internal edges ("ghost collisions"): where a body crosses the shared edge of two coplanar
//   triangles, the new triangle overlaps it by a sliver, along which the box's axes or the
//   crossings of its edges with the triangle's separate less than the face normal: the contact
//   pushes sideways or tips the body. ODE's remedy, the per-triangle use flags of
//   dGeomTriMeshDataPreprocess2 (dTRIDATAPREPROCESS_BUILD_CONCAVE_EDGES, set in ode_shapes.cpp),
//   is read only by the capsule collider, and drops only concave edges there (a flat edge is
//   still tested, once); the face angles (dTRIDATAPREPROCESS_BUILD_FACE_ANGLES) serve only the
//   convex-trimesh collider, a pair this backend never collides. So the backend classifies each
//   mesh's edges once (MeshEdges) and moves a contact that leans off its triangle's normal away
//   from a real edge onto the face.
// - The points kept: given room for four, the box collider keeps the deepest of the points it
//   clips per triangle, which crowd where the box leans in (it then rocks), and the capsule
//   collider stops at the first triangles that fill the room. ODE gets room for more, and the
//   backend keeps the most spread-out four.
// - Rounding: a face lying on the mesh at depth 0 keeps a corner or loses it by rounding (ODE
//   clips at the triangle's plane). The shape is collided grown by a 0.1 mm skin, depths measured
//   back to its true surface, so that every corner a rounding above the face is kept.
#include <ode/ode.h>

#include <cstdint>
#include <vector>

#include "anyphys/math.hpp"

namespace anyphys::ode {

class NearProbe;
class OdeShape;

/// Which edges and corners of a mesh's triangles are real: on the mesh's border, shared by more
/// than two triangles or by two wound against each other, or where the surface folds outwards
/// (convex) by more than 1 degree. The others (flat, or folding inwards) lie inside a
/// surface that a body resting on either triangle meets only along the triangle's face normal.
class MeshEdges {
public:
    /// `indices`: three per triangle, counter-clockwise seen from outside (the layer's ShapeDef).
    MeshEdges(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& indices);

    /// Bit k: the edge from corner k to corner k + 1 of `triangle` is real; bit 3 + k: corner k
    /// ends a real edge (of this or another triangle).
    std::uint8_t realFeatures(int triangle) const { return real_[static_cast<std::size_t>(triangle)]; }
    int triangleCount() const { return static_cast<int>(real_.size()); }
    /// Whether any edge is internal: a mesh without one needs no correction.
    bool hasInternalEdges() const { return hasInternal_; }

private:
    std::vector<std::uint8_t> real_;
    bool hasInternal_ = false;
};

/// Collides `shape` (its geom `o1`) with the static mesh `mesh` (geom `o2`) into out[0..capacity),
/// normals into `o1`, as dCollide would. Boxes and capsules: grown by the skin (`probe`), with
/// room for kMeshContacts points; none unless one touches (depth >= 0: a shape held within the
/// skin above a flat mesh would hover there until ODE's broad phase missed the pair); a contact
/// that leans off its triangle's normal away from the triangle's real edges and corners goes onto
/// the face (its depth how far the shape reaches below the face there, by a ray cast up through
/// it; dropped where it does not); the most spread-out `capacity` kept, the deepest first. Other
/// shapes: dCollide. Returns the number of contacts.
int collideWithMesh(dGeomID o1, dGeomID o2, const OdeShape& shape, const OdeShape& mesh, NearProbe& probe, dContact* out,
                    int capacity);

}  // namespace anyphys::ode
