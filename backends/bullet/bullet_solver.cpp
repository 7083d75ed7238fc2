#include "bullet_solver.hpp"

namespace anyphys::bullet {

btScalar AnyphysSequentialImpulseSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                                              btPersistentManifold** manifolds, int numManifolds,
                                                              btTypedConstraint** constraints, int numConstraints,
                                                              const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
    btScalar residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
        iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
    for (int i = 0; i < m_tmpSolverContactFrictionConstraintPool.size(); ++i) {
        btSolverConstraint& friction = m_tmpSolverContactFrictionConstraintPool[i];
        if (friction.m_appliedImpulse == 0) continue;
        if (m_tmpSolverContactConstraintPool[friction.m_frictionIndex].m_appliedImpulse > 0) continue;
        friction.m_lowerLimit = 0;  // bound: mu times a zero normal impulse
        friction.m_upperLimit = 0;
        const btScalar change = resolveSingleConstraintRowGeneric(m_tmpSolverBodyPool[friction.m_solverBodyIdA],
                                                                  m_tmpSolverBodyPool[friction.m_solverBodyIdB], friction);
        residual = btMax(residual, change * change);
    }
    return residual;
}

}  // namespace anyphys::bullet
