#include "bullet_touching.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <new>

namespace anyphys::bullet {

btPersistentManifold* TouchingDispatcher::getNewManifold(const btCollisionObject* body0, const btCollisionObject* body1) {
    btPersistentManifold* manifold = btCollisionDispatcher::getNewManifold(body0, body1);
    if (manifold->getContactBreakingThreshold() < minimumBreaking_) manifold->setContactBreakingThreshold(minimumBreaking_);
    return manifold;
}

void SphereSphereAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                             const btDispatcherInfo&, btManifoldResult* result) {
    if (!manifold_) return;
    result->setPersistentManifold(manifold_);
    const btScalar radius0 = static_cast<const btSphereShape*>(body0->getCollisionShape())->getRadius();
    const btScalar radius1 = static_cast<const btSphereShape*>(body1->getCollisionShape())->getRadius();
    const btVector3& center0 = body0->getWorldTransform().getOrigin();
    const btVector3& center1 = body1->getWorldTransform().getOrigin();
    const btVector3 between = center0 - center1;
    const btScalar length = between.length();
    const btScalar distance = length - radius0 - radius1;  // negative: overlapping
    if (distance < manifold_->getContactBreakingThreshold()) {
        // Concentric spheres have no normal of their own: any direction pushes them apart.
        const btVector3 normalOnB = length > SIMD_EPSILON ? between / length : btVector3(1, 0, 0);
        result->addContactPoint(normalOnB, center1 + radius1 * normalOnB, distance);
    }
    // Without a new point the old one is kept only while it is still within the threshold.
    result->refreshContactPoints();
}

btCollisionAlgorithm* SphereSphereAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                                  const btCollisionObjectWrapper* body0,
                                                                                  const btCollisionObjectWrapper* body1) {
    return newPooledAlgorithm<SphereSphereAlgorithm>(info, body0, body1);
}

}  // namespace anyphys::bullet
