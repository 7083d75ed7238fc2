#pragma once
// Box against box: Bullet's own box-box test, with a manifold that follows a sliding box.
//
// Bullet's box-box algorithm keeps its manifold's points from step to step and matches each new
// point to an old one within the breaking threshold (0.02 times the box's bounding radius: 6.9 mm
// for a 0.4 m cube) in the first box's frame. Two things left a box sliding on a static box on two
// or three points, rocking, hopping and turning: its test keeps only overlapping points, and a
// box resting on another sits at depth zero, so corners a rounding above the other face were
// dropped while their old points slid away; and past 0.41 m/s (6.9 mm per 1/60 s step) no new
// corner matched an old point, so the new and old points competed for the four places. A 0.4 m
// cube sliding down a 30 deg box slope (mu 0.5) accelerated at 0.59 m/s^2 instead of 0.657,
// where on a plane, and on native and ODE, it was exact. Here the first box is tested a little
// larger (a quarter of the breaking threshold, and at least the layer's linearSlop, so that boxes
// closer than that touch at every size; taken off every depth), and when the test finds
// a whole face (four points) they replace the manifold's, each keeping the impulses of the old
// point at the same place on either box, so resting contact still warm-starts. A partial result
// (an edge's single point, a face with a corner lifted) merges with the old points as Bullet does.
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>

#include "bullet_own_manifold.hpp"

class btPersistentManifold;

namespace anyphys::bullet {

class BoxBoxAlgorithm final : public OwnManifoldAlgorithm {
public:
    /// `touchingBand`: the layer's linearSlop; points at least that far apart are found.
    BoxBoxAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                    const btCollisionObjectWrapper* body1, btScalar touchingBand);

    void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                          const btDispatcherInfo& dispatchInfo, btManifoldResult* result) override;
    btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                   btManifoldResult*) override {
        return 1;  // as Bullet's own box-box algorithm
    }

    struct CreateFunc final : btCollisionAlgorithmCreateFunc {
        explicit CreateFunc(btScalar band) : touchingBand(band) {}
        btScalar touchingBand;
        btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                       const btCollisionObjectWrapper* body0,
                                                       const btCollisionObjectWrapper* body1) override;
    };

private:
    btScalar touchingBand_;
};

}  // namespace anyphys::bullet
