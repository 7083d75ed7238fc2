#pragma once
// Capsule against a static plane, both ends of the capsule's core segment at once.
//
// Bullet's convex-plane test adds one point per step, the shape's deepest, and leaves round shapes
// out of its perturbation pass (a perturbed ball would get off-centre points and roll for ever).
// A capsule lying on a plane then rests on whichever end was deepest last: the other end's point
// goes stale as the capsule slides, so it tilts and sinks. A capsule sliding at 5 m/s on a plane
// sank 5.6 mm, turned at 0.25 rad/s about its length and spun up 1 to 3 % off mu g r t / k, where
// on a box it was exact. The deepest point of a segment against a plane is always at an end, so
// the two ends are the whole contact: this algorithm adds the point of each end that lies within
// the breaking threshold of the plane.
#include <BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>

class btPersistentManifold;

namespace anyphys::bullet {

class CapsulePlaneAlgorithm final : public btCollisionAlgorithm {
public:
    CapsulePlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                          const btCollisionObjectWrapper* body1, bool planeFirst);
    ~CapsulePlaneAlgorithm() override;
    CapsulePlaneAlgorithm(const CapsulePlaneAlgorithm&) = delete;
    CapsulePlaneAlgorithm& operator=(const CapsulePlaneAlgorithm&) = delete;

    void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                          const btDispatcherInfo& dispatchInfo, btManifoldResult* result) override;
    btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                   btManifoldResult*) override {
        return 1;  // as Bullet's own convex-plane test: no time of impact against a plane
    }
    void getAllContactManifolds(btManifoldArray& manifolds) override;

    /// Creates the algorithm for (capsule, plane), or for (plane, capsule) when `planeFirst`.
    struct CreateFunc final : btCollisionAlgorithmCreateFunc {
        explicit CreateFunc(bool planeFirst) { m_swapped = planeFirst; }
        btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                       const btCollisionObjectWrapper* body0,
                                                       const btCollisionObjectWrapper* body1) override;
    };

private:
    btPersistentManifold* manifold_ = nullptr;  // (capsule, plane), owned
    bool planeFirst_ = false;
};

}  // namespace anyphys::bullet
