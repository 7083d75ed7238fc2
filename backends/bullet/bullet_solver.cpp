#include "bullet_solver.hpp"

namespace anyphys::bullet {

// Bullet's setupContactConstraint gives a point `penetration` = distance + linearSlop deep (< 0)
// the push -penetration erp / h, erp the point's own where it has one (a bouncing point's 0),
// else erp2, times the row's effective mass: in m_rhsPenetration (split impulse, beyond its
// depth) or added into m_rhs (Baumgarte) with the velocity target.
void capContactPush(btAlignedObjectArray<btSolverConstraint>& contacts, const btContactSolverInfo& info, btScalar maxPush) {
    const int count = contacts.size();
    for (int c = 0; c < count; ++c) {
        btSolverConstraint& row = contacts[c];
        const btScalar most = maxPush * row.m_jacDiagABInv;
        if (row.m_rhsPenetration > most) row.m_rhsPenetration = most;
    }
    // With split impulse on, Baumgarte pushes only points shallower than its depth: at most
    // depth erp2 / h (0.48 m/s at 60 Hz), under the cap unless the step is short or the cap low.
    const btScalar invStep = btScalar(1) / info.m_timeStep;
    if (info.m_splitImpulse && -info.m_splitImpulsePenetrationThreshold * info.m_erp2 * invStep <= maxPush) return;
    for (int c = 0; c < count; ++c) {
        btSolverConstraint& row = contacts[c];
        if (row.m_rhsPenetration != 0) continue;  // split impulse's, capped above
        const auto* point = static_cast<const btManifoldPoint*>(row.m_originalContactPoint);
        const btScalar depth = -(point->getDistance() + info.m_linearSlop);
        if (depth <= 0) continue;
        const btScalar erp = (point->m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) != 0 ? point->m_contactERP : info.m_erp2;
        const btScalar excess = depth * erp * invStep - maxPush;
        if (excess > 0) row.m_rhs -= excess * row.m_jacDiagABInv;
    }
}

void AnyphysSequentialImpulseSolver::convertContacts(btPersistentManifold** manifolds, int numManifolds,
                                                     const btContactSolverInfo& info) {
    btSequentialImpulseConstraintSolver::convertContacts(manifolds, numManifolds, info);
    capContactPush(m_tmpSolverContactConstraintPool, info, maxPush_);
}

void AnyphysMlcpSolver::convertContacts(btPersistentManifold** manifolds, int numManifolds, const btContactSolverInfo& info) {
    btMLCPSolver::convertContacts(manifolds, numManifolds, info);
    capContactPush(m_tmpSolverContactConstraintPool, info, maxPush_);
}

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
