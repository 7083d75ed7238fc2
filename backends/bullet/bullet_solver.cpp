#include "bullet_solver.hpp"

namespace anyphys::bullet {

btScalar AnyphysSequentialImpulseSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                                              btPersistentManifold** manifolds, int numManifolds,
                                                              btTypedConstraint** constraints, int numConstraints,
                                                              const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
    btScalar residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
        iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
    // Past the contacts' iterations Bullet solves only joint rows (which may ask for 10 x more):
    // no contact or friction row changes, and the last pass left none to take back.
    if (iteration >= info.m_numIterations) return residual;
    // Walked from the contact rows, which the iteration just read: most carry load and are
    // skipped without touching their friction rows. A contact's friction rows are the run from its
    // m_frictionIndex to the next contact's (Bullet appends them as it converts each contact), so
    // the rows are visited in the same order as a walk over the friction pool would.
    const int contacts = m_tmpSolverContactConstraintPool.size();
    const int frictions = m_tmpSolverContactFrictionConstraintPool.size();
    for (int c = 0; c < contacts; ++c) {
        const btSolverConstraint& contact = m_tmpSolverContactConstraintPool[c];
        if (contact.m_appliedImpulse > 0) continue;
        const int end = c + 1 < contacts ? m_tmpSolverContactConstraintPool[c + 1].m_frictionIndex : frictions;
        for (int f = contact.m_frictionIndex; f < end; ++f) {
            btSolverConstraint& friction = m_tmpSolverContactFrictionConstraintPool[f];
            if (friction.m_appliedImpulse == 0) continue;
            friction.m_lowerLimit = 0;  // bound: mu times a zero normal impulse
            friction.m_upperLimit = 0;
            const btScalar change = resolveSingleConstraintRowGeneric(
                m_tmpSolverBodyPool[friction.m_solverBodyIdA], m_tmpSolverBodyPool[friction.m_solverBodyIdB], friction);
            residual = btMax(residual, change * change);
        }
    }
    return residual;
}

}  // namespace anyphys::bullet
