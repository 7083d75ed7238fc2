#pragma once
// Capsule against a box or a hull: a capsule lying on a face touches it along a line, both ends
// at once.
//
// Bullet collides a capsule with a box or a hull by GJK, one point per step, and keeps older points
// in the manifold while they stay within the breaking threshold. A capsule sliding along its length
// down a box slope (0.1 m radius, 30 deg, mu 0.5) outran the point it had left behind each step: it
// stood on one point at a time, rocked at up to 0.47 rad/s, sank 2.8 mm and slid 4 % fast, where
// on a plane (bullet_capsule_plane.*) and on native and ODE it was exact; on a slab made as a hull
// the same (0.465 rad/s, 2.8 mm, 4 % fast). A capsule landing tilted (8 deg) stood on the one
// point under the end that landed first, and its other end, swinging down, was 6.3 cm deep before
// it had one (ODE 1.6 cm). When the capsule's centre lies outside one face of the shape and its
// core segment lies above that face, over it whole at any lean or, clipped at the face's edge,
// nearly parallel to it (within 3 deg), this algorithm clips the segment to the face and adds the
// point under each end of the clipped segment that lies within the breaking threshold, however
// deep: a line over the face's edge ends at the edge. Two points replace the manifold's, keeping
// the impulses of the old points at the same place; one merges as Bullet's test does. Any other
// pose (the core through the face, a capsule beside the shape touching an edge, one tipping over
// an edge, one reaching over an edge onto a face nearly in line with this one) is left to Bullet's
// convex-convex test, on the same manifold.
//
// A box's faces are its full half extents (the box's margin lies inside them). A hull is Bullet's
// hull shrunk by its margin (bullet_shapes.cpp), so its faces are those of the shrunk polyhedron
// (initializePolyhedralFeatures) pushed out by the margin; a line is clipped to the shrunk face,
// which ends at most the margin (1 mm) short of the hull's edge, where the rounding begins.
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>

#include "bullet_own_manifold.hpp"

class btPersistentManifold;

namespace anyphys::bullet {

class CapsulePolyhedronAlgorithm final : public OwnManifoldWithFallback {
public:
    CapsulePolyhedronAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                               const btCollisionObjectWrapper* body1, bool polyhedronFirst,
                               btConvexPenetrationDepthSolver* depthSolver);

    void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                          const btDispatcherInfo& dispatchInfo, btManifoldResult* result) override;

    /// Creates the algorithm for (capsule, box or hull), or for (box or hull, capsule) when
    /// `polyhedronFirst`.
    struct CreateFunc final : btCollisionAlgorithmCreateFunc {
        explicit CreateFunc(bool polyhedronFirst) { m_swapped = polyhedronFirst; }
        btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                       const btCollisionObjectWrapper* body0,
                                                       const btCollisionObjectWrapper* body1) override;
        btGjkEpaPenetrationDepthSolver depthSolver;  // the convex-convex test's, as Bullet's default
    };

private:
    /// Whether the capsule lies over a face of the box or hull; if so its points are in the manifold.
    bool collideOverFace(const btCollisionObjectWrapper* capsuleWrap, const btCollisionObjectWrapper* polyhedronWrap,
                         btManifoldResult* result);

    bool polyhedronFirst_ = false;
};

}  // namespace anyphys::bullet
