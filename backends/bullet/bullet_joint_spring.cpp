#include "bullet_joint_spring.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace anyphys::bullet {
namespace {

// The joint rows J_i M^-1 J_j^T, as the solver applies impulses (factors mask directions).
double coupling(const btRigidBody& a, const btRigidBody& b, const JointRow& i, const JointRow& j) {
    return static_cast<double>(i.l1.dot(j.l1 * a.getInvMass() * a.getLinearFactor()) +
                               i.a1.dot((a.getInvInertiaTensorWorld() * j.a1) * a.getAngularFactor()) +
                               i.l2.dot(j.l2 * b.getInvMass() * b.getLinearFactor()) +
                               i.a2.dot((b.getInvInertiaTensorWorld() * j.a2) * b.getAngularFactor()));
}

// J v with the substep's forces applied (the solver's external force impulse).
double rate(const btRigidBody& a, const btRigidBody& b, const JointRow& row, btScalar h) {
    const auto of = [h](const btRigidBody& body, const btVector3& l, const btVector3& w) {
        const btVector3 v = body.getLinearVelocity() + body.getTotalForce() * body.getInvMass() * body.getLinearFactor() * h;
        const btVector3 omega =
            body.getAngularVelocity() + (body.getInvInertiaTensorWorld() * body.getTotalTorque()) * body.getAngularFactor() * h;
        return l.dot(v) + w.dot(omega);
    };
    return static_cast<double>(of(a, row.l1, row.a1) + of(b, row.l2, row.a2));
}

// Row s applies exactly `impulse`: an infinite target speed its way, bounded by the impulse
// (bounds lo == hi stall the MLCP solver).
void writeImpulse(btTypedConstraint::btConstraintInfo2* info, int s, double impulse) {
    const auto p = static_cast<btScalar>(std::isfinite(impulse) ? impulse : 0.0);
    info->m_constraintError[s] = p < 0 ? -SIMD_INFINITY : SIMD_INFINITY;
    info->cfm[s] = 0;
    info->m_lowerLimit[s] = std::min(p, btScalar(0));
    info->m_upperLimit[s] = std::max(p, btScalar(0));
}

}  // namespace

void writeSpringRow(btTypedConstraint::btConstraintInfo2* info, int s, const btRigidBody& a, const btRigidBody& b,
                    const SpringRowInput& in) {
    const JointRow& row = in.spring;
    for (int k = 0; k < 3; ++k) {
        info->m_J1linearAxis[s + k] = row.l1[k];
        info->m_J1angularAxis[s + k] = row.a1[k];
        if (info->m_J2linearAxis != nullptr) info->m_J2linearAxis[s + k] = row.l2[k];
        if (info->m_J2angularAxis != nullptr) info->m_J2angularAxis[s + k] = row.a2[k];
    }
    const auto hs = static_cast<btScalar>(in.h);
    // The spring axis' inverse effective mass K and rate v with the rigid rows r solved
    // alongside: K = K_ss - K_sr K_rr^-1 K_rs and v = J_s v0 + K_sr K_rr^-1 (target_r - J_r v0)
    // (the Schur complement), so that its rate after an impulse P is v + K P.
    const double alone = coupling(a, b, row, row);
    double K = alone;
    double v = rate(a, b, row, hs);
    if (in.rigidCount > 0) {
        constexpr int kMax = 6;
        using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;
        using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1>;
        const int n = std::min(in.rigidCount, kMax);
        Matrix Krr(n, n);
        Vector Krs(n), free(n);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) Krr(i, j) = coupling(a, b, in.rigid[i], in.rigid[j]);
            Krs(i) = coupling(a, b, in.rigid[i], row);
            free(i) = static_cast<double>(in.rigidTargets[i]) - rate(a, b, in.rigid[i], hs);
        }
        // Rows may be dependent (a locked axis of a static pair): the least-squares solution.
        const Eigen::CompleteOrthogonalDecomposition<Matrix> solve(Krr);
        const Vector x = solve.solve(Krs);
        if (x.allFinite()) {
            K -= Krs.dot(x);
            v += x.dot(free);
        }
    }
    K = std::max(K, 0.0);
    const double h = in.h, k = in.stiffness, c = in.damping, hkc = h * k + c;
    if (h * hkc * K * in.springsOnBusierBody <= 1.5) {
        // Soft: the force at the substep's start (semi-implicit Euler: a free spring keeps its
        // energy; stable while (omega h)^2 + 2 h c K < 4).
        writeImpulse(info, s, -h * (k * in.stretch + c * rate(a, b, row, 0)));
    } else if (in.softRows && alone > 0.0) {
        // Stiff, implicit, coupled: sequential impulses settle a row at J v' = error - K' cfm P
        // (K' = `alone`, the row's own inverse mass: Bullet adds no CFM to it), and the spring
        // wants J v' = -k C / (h k + c) - P / (h (h k + c)). cfm = 1 / (h (h k + c) K') < 2/3, so
        // the row's own iteration converges (it does not below 1).
        info->m_constraintError[s] = static_cast<btScalar>(-k * in.stretch / hkc);
        info->cfm[s] = static_cast<btScalar>(1.0 / (h * hkc * alone));
        info->m_lowerLimit[s] = -SIMD_INFINITY;
        info->m_upperLimit[s] = SIMD_INFINITY;
    } else {
        // Stiff, implicit, the joint alone: from P = -h (k (C + h v') + c v') with v' = v + K P.
        writeImpulse(info, s, -h * (k * in.stretch + hkc * v) / (1.0 + h * hkc * K));
    }
}

}  // namespace anyphys::bullet
