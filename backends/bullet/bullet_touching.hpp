#pragma once
// Pairs closer than the layer's linearSlop touch (the events' rule), on every shape and size.
//
// Bullet keeps a pair's contact points only within its manifold's breaking threshold, 0.02 times
// the shapes' angular motion disc: 17 mm for a box of half extent 0.5, but 1.7 mm for one of 0.05
// and 1 mm for a sphere of radius 0.05. Two small boxes or hulls 1 mm apart (a fifth of the
// default linearSlop) then had no point and never touched. TouchingDispatcher keeps every
// manifold's threshold at least twice linearSlop (points out to the touching band, with as much
// again for Bullet's matching of old and new points). Bullet's sphere-sphere test ignores the
// threshold and reports only overlap, so two spheres 1 mm apart never touched at any size:
// SphereSphereAlgorithm reports their one point within the threshold, as Bullet's other convex
// tests do. A raised threshold would also widen Bullet's matching of a new point to an old one
// (the same spot within the threshold) past a small shape's face: a 1 cm box's four corners
// merged into one point. The dispatcher's results match within the shapes' own spacing too.
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>

#include "bullet_own_manifold.hpp"

namespace anyphys::bullet {

/// Bullet's dispatcher, whose manifolds keep points at least `minimumBreaking` apart.
class TouchingDispatcher final : public btCollisionDispatcher {
public:
    TouchingDispatcher(btCollisionConfiguration* configuration, btScalar minimumBreaking);

    btPersistentManifold* getNewManifold(const btCollisionObject* body0, const btCollisionObject* body1) override;

private:
    btScalar minimumBreaking_;
};

/// Sphere against sphere, with points kept within the manifold's breaking threshold.
class SphereSphereAlgorithm final : public OwnManifoldAlgorithm {
public:
    SphereSphereAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                          const btCollisionObjectWrapper* body1)
        : OwnManifoldAlgorithm(info, body0, body1) {}

    void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                          const btDispatcherInfo& dispatchInfo, btManifoldResult* result) override;
    btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                   btManifoldResult*) override {
        return 1;  // as Bullet's own sphere-sphere algorithm
    }

    struct CreateFunc final : btCollisionAlgorithmCreateFunc {
        btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                       const btCollisionObjectWrapper* body0,
                                                       const btCollisionObjectWrapper* body1) override;
    };
};

}  // namespace anyphys::bullet
