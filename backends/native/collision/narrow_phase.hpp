#pragma once
// The pair routines behind collide(), on shapes already placed in the world. Each writes one
// manifold with its normal from the first shape to the second and returns false when no point
// has separation < speculative.
#include <span>

#include "anyphys/math.hpp"
#include "collision/collide.hpp"
#include "collision/polytope.hpp"
#include "collision/shape.hpp"

namespace anyphys::native {

struct SphereGeom {
    Vec3 center = Vec3::Zero();
    double radius = 0.0;
};

struct CapsuleGeom {
    Vec3 p0 = Vec3::Zero();  // segment ends (local -Y end first)
    Vec3 p1 = Vec3::Zero();
    double radius = 0.0;
};

struct BoxGeom {
    Vec3 center = Vec3::Zero();
    Mat3 rotation = Mat3::Identity();  // columns: the box axes in the world
    Vec3 half = Vec3::Zero();
};

struct PlaneGeom {
    Vec3 normal = Vec3::UnitY();  // unit; the solid side is below
    double offset = 0.0;
};

// Round shapes (collide_round.cpp).
bool collideSpheres(const SphereGeom& a, const SphereGeom& b, double speculative, Manifold& m);
bool collideSphereCapsule(const SphereGeom& a, const CapsuleGeom& b, double speculative, Manifold& m);
bool collideCapsules(const CapsuleGeom& a, const CapsuleGeom& b, double speculative, Manifold& m);

// Boxes (collide_box.cpp).
bool collideSphereBox(const SphereGeom& a, const BoxGeom& b, double speculative, Manifold& m);
// With a cache: the separating axis of the last call is tried first (see CollideCache).
bool collideBoxes(const BoxGeom& a, const BoxGeom& b, double speculative, Manifold& m, CollideCache* cache = nullptr);
// True if the face axis a cache remembers still separates boxes (half sizes, shape poses) by
// more than `speculative`: collideBoxes' test, made from the orientations without building the
// rotation matrices, for pairs that stay apart (neighbours in a pile).
bool boxesStillApart(const Vec3& halfA, const Transform& xfA, const Vec3& halfB, const Transform& xfB,
                     const CollideCache& cache, double speculative);

// Polytopes: hulls, boxes against hulls, mesh triangles (collide_polytope.cpp). A one-sided
// polytope (mesh triangle) must be b: contacts then only push a out of its front.
bool collideSpherePolytope(const SphereGeom& a, const Polytope& b, double speculative, Manifold& m);
bool collideCapsulePolytope(const CapsuleGeom& a, const Polytope& b, double speculative, Manifold& m);
bool collidePolytopes(const Polytope& a, const Polytope& b, double speculative, Manifold& m, CollideCache* cache = nullptr);
// Polytopes found apart by some axis: the distance routine measures them. Sets `apart` false
// (and returns false) when they turn out to touch after all; the caller then clips.
bool collideApartPolytopes(const Polytope& a, const Polytope& b, double speculative, Manifold& m, bool& apart);

// Contact with one face of b only: its normal, and a's part over the face (clipped to it). For
// mesh triangles touched at an internal edge, where an edge normal would be a ghost bump.
bool collideSphereFace(const SphereGeom& a, const Polytope& b, int face, double speculative, Manifold& m);
bool collideCapsuleFace(const CapsuleGeom& a, const Polytope& b, int face, double speculative, Manifold& m);
bool collidePolytopeFace(const Polytope& a, const Polytope& b, int face, double speculative, Manifold& m);

// Planes (collide_plane.cpp): points (sphere centre, segment ends) with a radius, a box's corners
// or a polytope's vertices against the plane b; point i gets feature (Plane, i).
bool collidePointsPlane(std::span<const Vec3> points, double radius, const PlaneGeom& b, double speculative, Manifold& m);
bool collideBoxPlane(const BoxGeom& a, const PlaneGeom& b, double speculative, Manifold& m);
bool collidePolytopePlane(const Polytope& a, const PlaneGeom& b, double speculative, Manifold& m);

// Meshes (collide_mesh.cpp): a convex shape a against every touched triangle of mesh b; one
// manifold per triangle (key = triangle index), normals from a to the mesh.
void collideConvexMesh(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculative,
                       std::vector<Manifold>& out);

}  // namespace anyphys::native
