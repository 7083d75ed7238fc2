#pragma once
// What the backend's collision algorithms share: a manifold of their own, and a block of
// Bullet's algorithm pool.
#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>

#include <new>
#include <utility>

namespace anyphys::bullet {

/// A collision algorithm with a manifold of its own for (body0, body1), in the dispatcher's order:
/// btManifoldResult takes every point in the manifold's order (body0's point, the normal on
/// body1), as Bullet's own tests give them. No manifold when the pair needs no collision.
class OwnManifoldAlgorithm : public btActivatingCollisionAlgorithm {
public:
    OwnManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                         const btCollisionObjectWrapper* body1)
        : btActivatingCollisionAlgorithm(info, body0, body1) {
        if (m_dispatcher->needsCollision(body0->getCollisionObject(), body1->getCollisionObject()))
            manifold_ = m_dispatcher->getNewManifold(body0->getCollisionObject(), body1->getCollisionObject());
    }
    ~OwnManifoldAlgorithm() override {
        if (manifold_) m_dispatcher->releaseManifold(manifold_);
    }
    OwnManifoldAlgorithm(const OwnManifoldAlgorithm&) = delete;
    OwnManifoldAlgorithm& operator=(const OwnManifoldAlgorithm&) = delete;

    void getAllContactManifolds(btManifoldArray& manifolds) override {
        if (manifold_) manifolds.push_back(manifold_);
    }

protected:
    btPersistentManifold* manifold_ = nullptr;  // owned
};

/// An own-manifold algorithm for the poses it recognises, with Bullet's convex-convex test, on the
/// same manifold, for every other pose and for the time of impact.
class OwnManifoldWithFallback : public OwnManifoldAlgorithm {
public:
    OwnManifoldWithFallback(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                            const btCollisionObjectWrapper* body1, btConvexPenetrationDepthSolver* depthSolver)
        : OwnManifoldAlgorithm(info, body0, body1) {
        if (!manifold_) return;
        // From the dispatcher's pool, as Bullet makes its algorithms (a member would make this one
        // too large for the pool's blocks); Bullet's defaults: no perturbation, 3 points before it
        // would start one.
        void* memory = m_dispatcher->allocateCollisionAlgorithm(sizeof(btConvexConvexAlgorithm));
        fallback_ = new (memory) btConvexConvexAlgorithm(manifold_, info, body0, body1, depthSolver, 0, 3);
    }
    ~OwnManifoldWithFallback() override {
        if (fallback_) {  // before the base releases the manifold it refers to
            fallback_->~btConvexConvexAlgorithm();
            m_dispatcher->freeCollisionAlgorithm(fallback_);
        }
    }

    btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1, const btDispatcherInfo& dispatchInfo,
                                   btManifoldResult* result) override {
        return fallback_ ? fallback_->calculateTimeOfImpact(body0, body1, dispatchInfo, result) : 1;
    }

protected:
    btConvexConvexAlgorithm* fallback_ = nullptr;  // Bullet's test, on manifold_; owned
};

/// `Algorithm` built in a block of the dispatcher's algorithm pool. The pool's blocks are the size
/// of Bullet's largest own algorithm, at least a btConvexConvexAlgorithm, and its allocate checks
/// the size only in debug builds.
template <class Algorithm, class... Args>
btCollisionAlgorithm* newPooledAlgorithm(btCollisionAlgorithmConstructionInfo& info, Args&&... args) {
    static_assert(sizeof(Algorithm) <= sizeof(btConvexConvexAlgorithm), "too large for Bullet's algorithm pool");
    void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(Algorithm));
    return new (memory) Algorithm(info, std::forward<Args>(args)...);
}

}  // namespace anyphys::bullet
