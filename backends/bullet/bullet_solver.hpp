#pragma once
// Bullet's constraint solvers with the layer's contact rules: friction bounded by each point's
// final normal impulse (sequential impulses), and every contact's push-out capped (both solvers).
#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>

namespace anyphys::bullet {

/// Caps the speed at which each contact row pushes its overlap apart at `maxPush` (m/s,
/// settings.contactPushMaxVelocity). Bullet pushes a point d deep at erp d / h, through the
/// velocity (Baumgarte) or, beyond the split-impulse depth, through the positions alone, and
/// bounds neither: a 0.1 m box 1 000 m inside a larger box left it 998 m away in 0.5 s, and one
/// 1e7 m inside was thrown past the coordinate range. `contacts` are the rows just converted.
void capContactPush(btAlignedObjectArray<btSolverConstraint>& contacts, const btContactSolverInfo& info, btScalar maxPush);

/// Bullet solves a point's friction rows only while its normal impulse is positive. A point that
/// carried load earlier in the iterations (or in the warm start) and none at the end keeps the
/// friction it was given: a box braking at mu = 0.8 pitches forward, its lifted rear corners
/// keep 4.6 N s of friction with no normal impulse, and it stops 21 % short. After each
/// iteration this solver takes such friction back, so no point's friction exceeds mu times its
/// normal impulse.
class AnyphysSequentialImpulseSolver final : public btSequentialImpulseConstraintSolver {
public:
    explicit AnyphysSequentialImpulseSolver(btScalar maxPush) : maxPush_(maxPush) {}

protected:
    void convertContacts(btPersistentManifold** manifolds, int numManifolds, const btContactSolverInfo& info) override;
    btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                  btPersistentManifold** manifolds, int numManifolds, btTypedConstraint** constraints,
                                  int numConstraints, const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;

private:
    btScalar maxPush_;
};

/// Bullet's MLCP (Dantzig) solver with the contacts' push-out capped as above.
class AnyphysMlcpSolver final : public btMLCPSolver {
public:
    AnyphysMlcpSolver(btMLCPSolverInterface* lcp, btScalar maxPush) : btMLCPSolver(lcp), maxPush_(maxPush) {}

protected:
    void convertContacts(btPersistentManifold** manifolds, int numManifolds, const btContactSolverInfo& info) override;

private:
    btScalar maxPush_;
};

}  // namespace anyphys::bullet
