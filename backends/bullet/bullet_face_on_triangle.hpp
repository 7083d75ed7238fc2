#pragma once
// A box, a hull, a capsule or a sphere lying on a mesh triangle: the whole face (line, point) of
// support, each step, on the mesh's shared manifold.
//
// Bullet collides a convex body with a triangle mesh one overlapping triangle at a time
// (btConvexTriangleCallback), each with a convex-triangle algorithm made for that step alone and
// writing into ONE manifold shared by all the triangles. Its convex-triangle test is GJK: one point
// per triangle per step. A body sliding farther per step than the manifold's breaking threshold
// (8.7 mm for a 0.5 m cube; at 5 m/s it slides 83 mm per 1/60 s step) has its old points dropped
// by refreshContactPoints, so after each step it stood on the one or two new GJK points and rocked:
// set sliding without friction at 5 m/s across a floor of 1 m triangles, a 0.5 m cube moved
// 0.51 m/s off its slide, a 0.1 m cube 1.6 m/s (thrown 1.5 cm up), hulls and capsules 0.26 to
// 0.46 m/s, where on a box all slid exact. A sphere rolling along the internal edges got Bullet's
// edge and vertex points (0.05 m/s).
//
// Here, when the body's face (a capsule's axis) lies within 10 deg of the triangle's plane, on its
// front side (the mesh is single-sided), the face is clipped by the triangle's three edge planes
// and every clipped point within the breaking threshold of the plane is added with the triangle's
// normal; a sphere's face is its lowest point. Each step so gives the face's whole support, as the
// box-box and hull-pair algorithms do (bullet_box_box.hpp, bullet_hull_pairs.hpp). The triangles
// of one flat region cut the face into pieces whose inner corners (where the face crosses an edge
// shared with a coplanar neighbour, and the triangle's corners inside the face) carry no support
// the face's own corners do not: they are left out, so on a flat mesh the manifold's four places
// hold the face's corners, which persist from step to step (each matches its old point on the
// body, keeping its impulses) as on one box; Bullet's reduction to four (deepest point, largest
// area) only sees more where the mesh bends or ends. Where a neighbour bends or there is none, the
// crossing is the edge of support and is kept. Every other pose (an edge or a corner down, the body
// behind the triangle, a face beside a triangle that bounds its flat region) goes to Bullet's own
// convex-triangle test.
//
// The points go through btManifoldResult as Bullet's test's do, so the contact-added callback
// still corrects normals at the mesh's internal edges (correctMeshEdge, bullet_dynamics_world.cpp).
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h>

class btPersistentManifold;

namespace anyphys::bullet {

class FaceOnTriangleAlgorithm final : public btCollisionAlgorithm {
public:
    /// `bullets`: Bullet's own create function for the pair (the fallback).
    FaceOnTriangleAlgorithm(const btCollisionAlgorithmConstructionInfo& info, btCollisionAlgorithmCreateFunc* bullets);

    void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                          const btDispatcherInfo& dispatchInfo, btManifoldResult* result) override;
    btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                   btManifoldResult*) override {
        return 1;  // the mesh's algorithm sweeps the body against the whole mesh, never per triangle
    }
    void getAllContactManifolds(btManifoldArray&) override {}  // the shared manifold is the mesh algorithm's

    /// Registered for (box, triangle), (hull, triangle), (capsule, triangle) and (sphere, triangle): the order in which
    /// btConvexTriangleCallback asks for them.
    struct CreateFunc final : btCollisionAlgorithmCreateFunc {
        btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                       const btCollisionObjectWrapper* body0,
                                                       const btCollisionObjectWrapper* body1) override;
        btCollisionAlgorithmCreateFunc* bullets = nullptr;  // Bullet's, from the configuration
    };

private:
    /// False when the pose is not a face (or line) on the triangle's front: Bullet's test runs.
    bool collideFace(const btCollisionObjectWrapper* body, const btCollisionObjectWrapper* triangle, btManifoldResult* result);

    btPersistentManifold* manifold_;  // the mesh's shared manifold (not owned)
    btCollisionAlgorithmCreateFunc* bullets_;
};

}  // namespace anyphys::bullet
