#include "bullet_box_box.hpp"

#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>

#include <array>
#include <new>

#include "bullet_carry_impulses.hpp"

namespace anyphys::bullet {
namespace {

// What the box-box test found this step, before it reaches the manifold.
struct FoundPoints final : btDiscreteCollisionDetectorInterface::Result {
    struct Found {
        btVector3 normalOnB, pointOnB;
        btScalar depth;
    };
    std::array<Found, 8> points;  // the test reports at most 4 (an edge-edge contact 1)
    int count = 0;

    void setShapeIdentifiersA(int, int) override {}
    void setShapeIdentifiersB(int, int) override {}
    void addContactPoint(const btVector3& normalOnB, const btVector3& pointOnB, btScalar depth) override {
        if (count < static_cast<int>(points.size())) points[count++] = {normalOnB, pointOnB, depth};
    }
};

// Of the manifold's breaking threshold: how far apart the boxes' points still count (4.3 mm for
// a 1 m cube), and at least the touching band.
constexpr btScalar kReachShare = 0.25;

// A whole face: Bullet's test clips one box's face against the other's and keeps up to 4 points.
// Fewer are an edge, or a face with a corner lifted past the reach (a rocking box): those merge
// with the old points as Bullet does, which keeps the lifted corner's point while it is within
// the breaking threshold (taking three as whole set a box resting on a 20 deg slope rocking at
// 0.12 rad/s).
constexpr int kWholeFace = 4;


}  // namespace

// Gives each new point the accumulated impulses of the old point at the same place on either
// body (the sliding box's corner stays put in its own frame; the slope's point stays put in its),
// so resting and sliding contact warm-start as before.
void carryImpulses(btPersistentManifold& manifold, const btManifoldPoint* old, int oldCount) {
    const btScalar reach2 = manifold.getContactBreakingThreshold() * manifold.getContactBreakingThreshold();
    for (int i = 0; i < manifold.getNumContacts(); ++i) {
        btManifoldPoint& fresh = manifold.getContactPoint(i);
        int nearest = -1;
        btScalar best = reach2;
        for (int k = 0; k < oldCount; ++k) {
            const btScalar d2 = btMin((old[k].m_localPointA - fresh.m_localPointA).length2(),
                                      (old[k].m_localPointB - fresh.m_localPointB).length2());
            if (d2 < best) {
                best = d2;
                nearest = k;
            }
        }
        if (nearest < 0) continue;
        const btManifoldPoint& match = old[nearest];
        fresh.m_appliedImpulse = match.m_appliedImpulse;
        fresh.m_prevRHS = match.m_prevRHS;
        fresh.m_appliedImpulseLateral1 = match.m_appliedImpulseLateral1;
        fresh.m_appliedImpulseLateral2 = match.m_appliedImpulseLateral2;
        fresh.m_lateralFrictionDir1 = match.m_lateralFrictionDir1;
        fresh.m_lateralFrictionDir2 = match.m_lateralFrictionDir2;
        fresh.m_contactPointFlags |= match.m_contactPointFlags & BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
        fresh.m_lifeTime = match.m_lifeTime;
    }
}

BoxBoxAlgorithm::BoxBoxAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                                 const btCollisionObjectWrapper* body1, btScalar touchingBand)
    : OwnManifoldAlgorithm(info, body0, body1), touchingBand_(touchingBand) {}

void BoxBoxAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                       const btDispatcherInfo& dispatchInfo, btManifoldResult* result) {
    if (!manifold_) return;
    // The test keeps only overlapping points, and a box resting on another sits at depth zero,
    // where a corner a rounding above the other face is dropped: a box on a 30 deg slope stood on
    // its two lower corners while the upper ones' old points slid away. The first box is tested a
    // reach larger, and the reach taken off every depth: points within it count, as Bullet's
    // other convex tests keep points within the breaking threshold.
    const btScalar reach = btMax(kReachShare * manifold_->getContactBreakingThreshold(), touchingBand_);
    const auto* box0 = static_cast<const btBoxShape*>(body0->getCollisionShape());
    const auto* box1 = static_cast<const btBoxShape*>(body1->getCollisionShape());
    const btBoxShape reachingBox0(box0->getHalfExtentsWithMargin() + btVector3(reach, reach, reach));
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = body0->getWorldTransform();
    input.m_transformB = body1->getWorldTransform();
    FoundPoints found;
    btBoxBoxDetector(&reachingBox0, box1).getClosestPoints(input, found, dispatchInfo.m_debugDraw);

    result->setPersistentManifold(manifold_);
    std::array<btManifoldPoint, MANIFOLD_CACHE_SIZE> old;
    const int oldCount = found.count >= kWholeFace ? manifold_->getNumContacts() : 0;
    for (int i = 0; i < oldCount; ++i) old[i] = manifold_->getContactPoint(i);
    if (found.count >= kWholeFace) manifold_->clearManifold();
    // Bullet's depth is a distance (negative for overlap), deeper by the reach for the larger box.
    // The point is on the second box's surface either way (a point of the first box's face is
    // moved onto the second's face), so only the depth carries the reach.
    for (int i = 0; i < found.count; ++i)
        result->addContactPoint(found.points[i].normalOnB, found.points[i].pointOnB, found.points[i].depth + reach);
    if (oldCount > 0) carryImpulses(*manifold_, old.data(), oldCount);
    result->refreshContactPoints();
}

btCollisionAlgorithm* BoxBoxAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                            const btCollisionObjectWrapper* body0,
                                                                            const btCollisionObjectWrapper* body1) {
    return newPooledAlgorithm<BoxBoxAlgorithm>(info, body0, body1, touchingBand);
}

}  // namespace anyphys::bullet
