#pragma once
// Bullet's sequential impulse solver with friction bounded by each point's final normal impulse.
#include <btBulletDynamicsCommon.h>

namespace anyphys::bullet {

/// Bullet solves a point's friction rows only while its normal impulse is positive. A point that
/// carried load earlier in the iterations (or in the warm start) and none at the end keeps the
/// friction it was given: a box braking at mu = 0.8 pitches forward, its lifted rear corners
/// keep 4.6 N s of friction with no normal impulse, and it stops 21 % short. After each
/// iteration this solver takes such friction back, so no point's friction exceeds mu times its
/// normal impulse.
class AnyphysSequentialImpulseSolver final : public btSequentialImpulseConstraintSolver {
protected:
    btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                  btPersistentManifold** manifolds, int numManifolds, btTypedConstraint** constraints,
                                  int numConstraints, const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;
};

}  // namespace anyphys::bullet
