#include "bullet_capsule_plane.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <new>

#include "bullet_own_manifold.hpp"

namespace anyphys::bullet {

CapsulePlaneAlgorithm::CapsulePlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                                             const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                             bool planeFirst)
    : btCollisionAlgorithm(info), planeFirst_(planeFirst) {
    const btCollisionObject* capsule = (planeFirst ? body1 : body0)->getCollisionObject();
    const btCollisionObject* plane = (planeFirst ? body0 : body1)->getCollisionObject();
    if (m_dispatcher->needsCollision(capsule, plane)) manifold_ = m_dispatcher->getNewManifold(capsule, plane);
}

CapsulePlaneAlgorithm::~CapsulePlaneAlgorithm() {
    if (manifold_) m_dispatcher->releaseManifold(manifold_);
}

void CapsulePlaneAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                             const btDispatcherInfo&, btManifoldResult* result) {
    if (!manifold_) return;
    const btCollisionObjectWrapper* capsuleWrap = planeFirst_ ? body1 : body0;
    const btCollisionObjectWrapper* planeWrap = planeFirst_ ? body0 : body1;
    const auto* capsule = static_cast<const btCapsuleShape*>(capsuleWrap->getCollisionShape());
    const auto* plane = static_cast<const btStaticPlaneShape*>(planeWrap->getCollisionShape());
    const btTransform& planePose = planeWrap->getWorldTransform();
    const btTransform& capsulePose = capsuleWrap->getWorldTransform();
    const btVector3 normal = planePose.getBasis() * plane->getPlaneNormal();  // world, out of the plane
    const btVector3 onPlane = planePose * (plane->getPlaneNormal() * plane->getPlaneConstant());
    const int up = capsule->getUpAxis();
    btVector3 halfSegment(0, 0, 0);
    halfSegment[up] = capsule->getHalfHeight();
    const btScalar radius = capsule->getRadius();
    result->setPersistentManifold(manifold_);
    for (const btScalar side : {btScalar(1), btScalar(-1)}) {
        const btVector3 end = capsulePose * (side * halfSegment);
        const btScalar distance = normal.dot(end - onPlane) - radius;
        if (distance >= manifold_->getContactBreakingThreshold()) continue;
        // The point on the plane (B's surface), under the end; Bullet's result sorts out the order.
        result->addContactPoint(normal, end - (distance + radius) * normal, distance);
    }
    result->refreshContactPoints();
}

void CapsulePlaneAlgorithm::getAllContactManifolds(btManifoldArray& manifolds) {
    if (manifold_) manifolds.push_back(manifold_);
}

btCollisionAlgorithm* CapsulePlaneAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                                  const btCollisionObjectWrapper* body0,
                                                                                  const btCollisionObjectWrapper* body1) {
    return newPooledAlgorithm<CapsulePlaneAlgorithm>(info, body0, body1, m_swapped);
}

}  // namespace anyphys::bullet
