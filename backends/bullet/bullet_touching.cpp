#include "bullet_touching.hpp"

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <new>

namespace anyphys::bullet {
namespace {

// Half the least spacing between the points a shape can hold in one manifold: a box's corners
// lie two half extents apart, a capsule's line ends two half heights, a hull's face points at
// least about its inner radius. A shape with one point per pair (sphere) or no size of its own
// (plane, mesh, triangle) sets no limit.
btScalar sameSpotSpacing(const btCollisionShape* shape) {
    switch (shape->getShapeType()) {
        case BOX_SHAPE_PROXYTYPE: {
            const btVector3 half = static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin();
            return half[half.minAxis()];
        }
        case CAPSULE_SHAPE_PROXYTYPE:
            return static_cast<const btCapsuleShape*>(shape)->getHalfHeight();
        case CONVEX_HULL_SHAPE_PROXYTYPE: {
            const auto* hull = static_cast<const btConvexHullShape*>(shape);
            if (const btConvexPolyhedron* core = hull->getConvexPolyhedron()) return core->m_radius + hull->getMargin();
            return BT_LARGE_FLOAT;
        }
        default:
            return BT_LARGE_FLOAT;
    }
}

// Bullet's btManifoldResult, except for how near a new point must lie to an old one to replace
// it. Bullet takes the breaking threshold for both that and the gap out to which points are kept;
// the threshold is at least twice linearSlop here (10 mm), wider than a 1 cm box's face, so each
// of the box-box test's four corners replaced the one before and a small box stood on a single
// corner: it tipped, sank 2 cm into a static box, and fell through a 1 cm slab. While a touching
// or nearly touching point is added, the manifold's threshold is narrowed to both shapes' spacing,
// so a face's points stay apart at every size; shapes at least twice linearSlop across, and points
// farther off than the spacing, keep Bullet's rule.
class SameSpotResult final : public btManifoldResult {
public:
    using btManifoldResult::btManifoldResult;

    void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override {
        btPersistentManifold* manifold = m_manifoldPtr;
        const btScalar breaking = manifold->getContactBreakingThreshold();
        const btScalar spot = btMin(sameSpotSpacing(m_body0Wrap->getCollisionShape()), sameSpotSpacing(m_body1Wrap->getCollisionShape()));
        if (spot >= breaking || depth > spot) {
            btManifoldResult::addContactPoint(normalOnBInWorld, pointInWorld, depth);
            return;
        }
        manifold->setContactBreakingThreshold(spot);  // Bullet's match radius while this point is added
        btManifoldResult::addContactPoint(normalOnBInWorld, pointInWorld, depth);
        manifold->setContactBreakingThreshold(breaking);
    }
};

// Bullet's default near callback, with SameSpotResult for the pair's points.
void sameSpotNearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info) {
    auto* object0 = static_cast<btCollisionObject*>(pair.m_pProxy0->m_clientObject);
    auto* object1 = static_cast<btCollisionObject*>(pair.m_pProxy1->m_clientObject);
    if (!dispatcher.needsCollision(object0, object1)) return;
    const btCollisionObjectWrapper wrap0(nullptr, object0->getCollisionShape(), object0, object0->getWorldTransform(), -1, -1);
    const btCollisionObjectWrapper wrap1(nullptr, object1->getCollisionShape(), object1, object1->getWorldTransform(), -1, -1);
    if (!pair.m_algorithm) pair.m_algorithm = dispatcher.findAlgorithm(&wrap0, &wrap1, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    if (!pair.m_algorithm) return;
    SameSpotResult result(&wrap0, &wrap1);
    if (info.m_dispatchFunc == btDispatcherInfo::DISPATCH_DISCRETE) {
        pair.m_algorithm->processCollision(&wrap0, &wrap1, info, &result);
    } else {
        const btScalar toi = pair.m_algorithm->calculateTimeOfImpact(object0, object1, info, &result);
        if (info.m_timeOfImpact > toi) info.m_timeOfImpact = toi;
    }
}

}  // namespace

TouchingDispatcher::TouchingDispatcher(btCollisionConfiguration* configuration, btScalar minimumBreaking)
    : btCollisionDispatcher(configuration), minimumBreaking_(minimumBreaking) {
    setNearCallback(&sameSpotNearCallback);
}

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
