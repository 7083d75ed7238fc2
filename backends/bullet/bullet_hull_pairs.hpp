#pragma once
// A hull against a box or a hull: Bullet's polyhedral test, with a manifold that follows a sliding
// hull.
//
// Bullet collides two polyhedra (hulls, and boxes given polyhedral features, bullet_shapes.cpp)
// by GJK for a normal and then clips one's face against the other's, adding every clipped point
// to the manifold, whose points persist from step to step: a new point takes the place of the old
// one within the breaking threshold. As for box-box (bullet_box_box.hpp), past the threshold per
// step no new point matched an old one, the new and old points competed for the four places and
// the old ones were then dropped: a cube hull (half size 0.25 m) sliding at 5 m/s on a box floor
// went from four points to one within 70 steps, tipped (0.39 rad/s) and kept rocking (0.27 m/s off
// the slide), where a box slid exact. Bullet also clips only while the hulls' cores (the hulls
// without their margins) overlap, and a hull resting on a face sits with its core at depth zero:
// on the steps its core ended a hair above, only GJK's single point was added. Here the faces are
// clipped whenever the cores are within the breaking threshold (the points Bullet keeps anyway),
// along whichever of GJK's normal and a few face normals the two lie farthest apart along (GJK's
// normal is arbitrary where the cores just touch: a cube hull sliding on a hull slab was thrown
// up), and when the clipping finds a whole face (four points or more) they replace the manifold's,
// each keeping the impulses of the old point at the same place on either body, so resting contact
// still warm-starts. A partial result (an edge, a corner) merges with the old points, after GJK's
// point, as Bullet does. Shapes without polyhedral features go to Bullet's convex-convex test.
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h>

#include "bullet_own_manifold.hpp"

namespace anyphys::bullet {

class HullPairAlgorithm final : public OwnManifoldWithFallback {
public:
    /// What the world's hull-pair algorithms reuse from pair to pair (the dispatcher tests one
    /// pair at a time), so a steady step allocates nothing.
    struct Scratch {
        struct Found {
            btVector3 normalOnB, pointOnB;
            btScalar distance;
        };
        btAlignedObjectArray<Found> found;  // the clipped face's points
        btVertexArray clipIn, clipOut;      // the clipping's polygons
    };

    HullPairAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                      const btCollisionObjectWrapper* body1, btConvexPenetrationDepthSolver* depthSolver, Scratch* scratch);

    void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                          const btDispatcherInfo& dispatchInfo, btManifoldResult* result) override;

    /// Registered for (box, hull), (hull, box) and (hull, hull).
    struct CreateFunc final : btCollisionAlgorithmCreateFunc {
        btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                       const btCollisionObjectWrapper* body0,
                                                       const btCollisionObjectWrapper* body1) override;
        btGjkEpaPenetrationDepthSolver depthSolver;  // the convex-convex test's, as Bullet's default
        Scratch scratch;
    };

private:
    /// False when a shape has no polyhedral features (then Bullet's test runs).
    bool collidePolyhedra(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                          const btDispatcherInfo& dispatchInfo, btManifoldResult* result);

    btConvexPenetrationDepthSolver* depthSolver_;
    Scratch* scratch_;
};

}  // namespace anyphys::bullet
