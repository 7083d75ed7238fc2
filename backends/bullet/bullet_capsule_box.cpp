#include "bullet_capsule_box.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>

#include <array>
#include <new>

#include "bullet_carry_impulses.hpp"

namespace anyphys::bullet {
namespace {

// The most a capsule lying over a face may lean towards it (the sine of its angle to the face):
// a point on the cylinder between the ends is measured straight down from the core, r (1/cos - 1)
// short of its surface when leaning, 0.25 mm for a 0.2 m radius at this limit. Leaning more (a
// capsule tipping off an edge), it goes to Bullet's test, whose point follows the edge.
constexpr btScalar kMostLean = 0.05;

// The segment e0 + t (e1 - e0), t in [0, 1], clipped to |x_j| <= half_j on the two axes other
// than `normalAxis` (in the box's frame): false when no part of it lies over the face.
bool clipToFace(const btVector3& e0, const btVector3& e1, const btVector3& half, int normalAxis, btScalar& t0, btScalar& t1) {
    t0 = 0;
    t1 = 1;
    const btVector3 along = e1 - e0;
    for (int j = 0; j < 3; ++j) {
        if (j == normalAxis) continue;
        if (btFabs(along[j]) < SIMD_EPSILON) {
            if (btFabs(e0[j]) > half[j]) return false;
            continue;
        }
        btScalar enter = (-half[j] - e0[j]) / along[j];
        btScalar leave = (half[j] - e0[j]) / along[j];
        if (enter > leave) btSwap(enter, leave);
        t0 = btMax(t0, enter);
        t1 = btMin(t1, leave);
    }
    return t0 <= t1;
}

}  // namespace

CapsuleBoxAlgorithm::CapsuleBoxAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                                         const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                         bool boxFirst, btConvexPenetrationDepthSolver* depthSolver)
    : OwnManifoldAlgorithm(info, body0, body1), boxFirst_(boxFirst) {
    if (!manifold_) return;
    // Bullet's defaults: no perturbation (round shapes take none), 3 points before it would start.
    // From the dispatcher's pool, as Bullet makes its algorithms: a member would make this one too
    // large for the pool's blocks.
    void* memory = m_dispatcher->allocateCollisionAlgorithm(sizeof(btConvexConvexAlgorithm));
    general_ = new (memory) btConvexConvexAlgorithm(manifold_, info, body0, body1, depthSolver, 0, 3);
}

CapsuleBoxAlgorithm::~CapsuleBoxAlgorithm() {
    if (general_) {  // before the base releases the manifold it refers to
        general_->~btConvexConvexAlgorithm();
        m_dispatcher->freeCollisionAlgorithm(general_);
    }
}

bool CapsuleBoxAlgorithm::collideOverFace(const btCollisionObjectWrapper* capsuleWrap, const btCollisionObjectWrapper* boxWrap,
                                          btManifoldResult* result) {
    const auto* capsule = static_cast<const btCapsuleShape*>(capsuleWrap->getCollisionShape());
    const auto* box = static_cast<const btBoxShape*>(boxWrap->getCollisionShape());
    const btTransform& boxPose = boxWrap->getWorldTransform();
    const btTransform inBox = boxPose.inverseTimes(capsuleWrap->getWorldTransform());
    const btVector3 half = box->getHalfExtentsWithMargin();
    btVector3 halfSegment(0, 0, 0);
    halfSegment[capsule->getUpAxis()] = capsule->getHalfHeight();
    const btVector3 e0 = inBox * halfSegment, e1 = inBox * -halfSegment;
    const btVector3& centre = inBox.getOrigin();
    const btScalar radius = capsule->getRadius();

    // The face the centre lies farthest outside of; the capsule must lie above it, neither end of
    // its core through the face.
    int axis = 0;
    for (int j = 1; j < 3; ++j)
        if (btFabs(centre[j]) - half[j] > btFabs(centre[axis]) - half[axis]) axis = j;
    const btScalar side = centre[axis] < 0 ? btScalar(-1) : btScalar(1);
    const auto height = [&](const btVector3& p) { return side * p[axis] - half[axis]; };  // of a core point above the face
    if (height(centre) <= 0 || height(e0) <= -radius || height(e1) <= -radius) return false;
    if (btFabs(e1[axis] - e0[axis]) > kMostLean * (e1 - e0).length()) return false;
    btScalar t0 = 0, t1 = 0;
    if (!clipToFace(e0, e1, half, axis, t0, t1)) return false;

    const btScalar threshold = manifold_->getContactBreakingThreshold();
    btVector3 normal(0, 0, 0);
    normal[axis] = side;
    const btVector3 worldNormal = boxPose.getBasis() * normal;  // from the box to the capsule
    struct Found {
        btVector3 pointOnBox;
        btScalar distance;
    };
    std::array<Found, 2> found;
    int count = 0;
    for (const btScalar t : {t0, t1}) {
        if (count == 1 && t1 - t0 < SIMD_EPSILON) break;  // the clipped segment is a point
        const btVector3 core = e0 + t * (e1 - e0);
        const btScalar distance = height(core) - radius;
        if (distance >= threshold) continue;
        if (distance < -threshold) return false;  // deep in: Bullet's penetration test knows better
        btVector3 onFace = core;
        onFace[axis] = side * half[axis];
        found[count++] = {boxPose * onFace, distance};
    }

    result->setPersistentManifold(manifold_);
    std::array<btManifoldPoint, MANIFOLD_CACHE_SIZE> old;
    const bool wholeLine = count == 2;
    const int oldCount = wholeLine ? manifold_->getNumContacts() : 0;
    for (int i = 0; i < oldCount; ++i) old[i] = manifold_->getContactPoint(i);
    if (wholeLine) manifold_->clearManifold();
    // In the manifold's order: the normal on the second body, pointing to the first, and the
    // point on the second body's surface.
    for (int i = 0; i < count; ++i) {
        if (boxFirst_)
            result->addContactPoint(-worldNormal, found[i].pointOnBox + found[i].distance * worldNormal, found[i].distance);
        else
            result->addContactPoint(worldNormal, found[i].pointOnBox, found[i].distance);
    }
    if (oldCount > 0) carryImpulses(*manifold_, old.data(), oldCount);
    return true;
}

void CapsuleBoxAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                           const btDispatcherInfo& dispatchInfo, btManifoldResult* result) {
    if (!manifold_) return;
    const btCollisionObjectWrapper* capsuleWrap = boxFirst_ ? body1 : body0;
    const btCollisionObjectWrapper* boxWrap = boxFirst_ ? body0 : body1;
    if (!collideOverFace(capsuleWrap, boxWrap, result)) general_->processCollision(body0, body1, dispatchInfo, result);
    result->setPersistentManifold(manifold_);
    result->refreshContactPoints();
}

btScalar CapsuleBoxAlgorithm::calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
                                                    const btDispatcherInfo& dispatchInfo, btManifoldResult* result) {
    return general_ ? general_->calculateTimeOfImpact(body0, body1, dispatchInfo, result) : 1;
}

btCollisionAlgorithm* CapsuleBoxAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                                const btCollisionObjectWrapper* body0,
                                                                                const btCollisionObjectWrapper* body1) {
    return newPooledAlgorithm<CapsuleBoxAlgorithm>(info, body0, body1, m_swapped, &depthSolver);
}

}  // namespace anyphys::bullet
