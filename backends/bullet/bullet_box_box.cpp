#include "bullet_box_box.hpp"

#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

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

// The box-box test with the first box `reach` larger, the reach taken off every depth: each
// point's distance (negative for overlap), on the second box's surface.
FoundPoints findWithin(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1, btScalar reach,
                       const btDispatcherInfo& dispatchInfo) {
    const auto* box0 = static_cast<const btBoxShape*>(body0->getCollisionShape());
    const auto* box1 = static_cast<const btBoxShape*>(body1->getCollisionShape());
    const btBoxShape reachingBox0(box0->getHalfExtentsWithMargin() + btVector3(reach, reach, reach));
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = body0->getWorldTransform();
    input.m_transformB = body1->getWorldTransform();
    FoundPoints found;
    btBoxBoxDetector(&reachingBox0, box1).getClosestPoints(input, found, dispatchInfo.m_debugDraw);
    for (int i = 0; i < found.count; ++i) found.points[i].depth += reach;
    return found;
}

// The velocity of the body's material point at `point` (zero for a static body).
btVector3 velocityAt(const btCollisionObjectWrapper* wrap, const btVector3& point) {
    const btRigidBody* body = btRigidBody::upcast(wrap->getCollisionObject());
    if (!body) return btVector3(0, 0, 0);
    return body->getVelocityInLocalPoint(point - body->getCenterOfMassPosition());
}

// An upper bound on how far the boxes close on each other over a step of `dt`: their relative
// speed plus each one's spin at its farthest corner.
btScalar stepApproach(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1, btScalar dt) {
    btVector3 relative(0, 0, 0);
    btScalar spin = 0;
    for (const auto* wrap : {body0, body1}) {
        const btRigidBody* body = btRigidBody::upcast(wrap->getCollisionObject());
        if (!body) continue;
        relative += wrap == body0 ? body->getLinearVelocity() : -body->getLinearVelocity();
        spin += body->getAngularVelocity().length() *
                static_cast<const btBoxShape*>(wrap->getCollisionShape())->getHalfExtentsWithMargin().length();
    }
    return (relative.length() + spin) * dt;
}

// The points a pair still apart will meet within the step, found out to its approach: each kept
// only if its own closing speed along the normal covers its gap (less the touching band), and
// moved along the second box's face into the first box's true extent (the grown box's face
// reaches past it by the reach). None when the pair does not close that fast.
FoundPoints speculativePoints(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1, btScalar approach,
                              btScalar band, btScalar dt, const btDispatcherInfo& dispatchInfo) {
    const FoundPoints ahead = findWithin(body0, body1, approach, dispatchInfo);
    const btTransform& frame0 = body0->getWorldTransform();
    const btVector3 half0 = static_cast<const btBoxShape*>(body0->getCollisionShape())->getHalfExtentsWithMargin();
    FoundPoints kept;
    for (int i = 0; i < ahead.count; ++i) {
        const auto& p = ahead.points[i];
        // normalOnB points from the second box to the first: the gap closes at (v1 - v0) . n.
        const btScalar closing = (velocityAt(body1, p.pointOnB) - velocityAt(body0, p.pointOnB)).dot(p.normalOnB);
        if (p.depth <= 0 || closing * dt < p.depth - band) continue;
        btVector3 local = frame0.invXform(p.pointOnB);
        local.setMax(-half0);
        local.setMin(half0);
        const btVector3 shift = frame0(local) - p.pointOnB;
        kept.addContactPoint(p.normalOnB, p.pointOnB + shift - shift.dot(p.normalOnB) * p.normalOnB, p.depth);
    }
    return kept;
}

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
    if (baseBreaking_ == 0) baseBreaking_ = manifold_->getContactBreakingThreshold();
    const btScalar reach = btMax(kReachShare * baseBreaking_, touchingBand_);
    FoundPoints found = findWithin(body0, body1, reach, dispatchInfo);
    // A pair found only once it overlaps has Bullet push the overlap out with a velocity (below
    // its split-impulse depth), which nothing takes back: a box sliding into a wall at 1 m/s with
    // no restitution bounced off at up to 0.12 m/s. A pair apart that closes faster gets the points
    // it will meet within the step, still apart: Bullet's solver lets such a speculative point
    // close exactly its gap. The manifold keeps them (its breaking threshold) for this step only.
    btScalar keepWithin = baseBreaking_;
    const btScalar dt = dispatchInfo.m_timeStep;
    if (const btScalar approach = found.count == 0 ? stepApproach(body0, body1, dt) : 0; approach > reach) {
        found = speculativePoints(body0, body1, approach, touchingBand_, dt, dispatchInfo);
        for (int i = 0; i < found.count; ++i) keepWithin = btMax(keepWithin, 2 * found.points[i].depth);
    }
    manifold_->setContactBreakingThreshold(keepWithin);

    result->setPersistentManifold(manifold_);
    std::array<btManifoldPoint, MANIFOLD_CACHE_SIZE> old;
    const int oldCount = found.count >= kWholeFace ? manifold_->getNumContacts() : 0;
    for (int i = 0; i < oldCount; ++i) old[i] = manifold_->getContactPoint(i);
    if (found.count >= kWholeFace) manifold_->clearManifold();
    // The point is on the second box's surface either way (a point of the first box's face is
    // moved onto the second's face), so only the depth carried the reach (findWithin).
    for (int i = 0; i < found.count; ++i)
        result->addContactPoint(found.points[i].normalOnB, found.points[i].pointOnB, found.points[i].depth);
    if (oldCount > 0) carryImpulses(*manifold_, old.data(), oldCount);
    result->refreshContactPoints();
}

btCollisionAlgorithm* BoxBoxAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                            const btCollisionObjectWrapper* body0,
                                                                            const btCollisionObjectWrapper* body1) {
    return newPooledAlgorithm<BoxBoxAlgorithm>(info, body0, body1, touchingBand);
}

}  // namespace anyphys::bullet
