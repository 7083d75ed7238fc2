#include "solver/body_integration.hpp"

#include <cmath>

#include "anyphys/peers/gyroscopic.hpp"

namespace anyphys::native {

Quat rotationFromVector(const Vec3& r) {
    const double angleSquared = r.squaredNorm();
    double c, s;  // cos(half), sin(half) / angle
    if (angleSquared < 4e-4) {
        // half < 1e-2: series to the 1e-17 level in half^2, so no square root. A resting body
        // turns by micro-radians per substep, and the library sin / cos, or even the root and the
        // division that normalising costs, took more than the rest of its integration (perf:
        // displaceBody was 10 % of the 1 000-box drop, most of it waiting on sqrt and div).
        const double h2 = 0.25 * angleSquared;
        c = 1.0 - h2 / 2.0 * (1.0 - h2 / 12.0 * (1.0 - h2 / 30.0));
        s = 0.5 * (1.0 - h2 / 6.0 * (1.0 - h2 / 20.0));
    } else {
        const double angle = std::sqrt(angleSquared);
        c = std::cos(0.5 * angle);
        s = std::sin(0.5 * angle) / angle;
    }
    return Quat(c, s * r.x(), s * r.y(), s * r.z());
}

Quat renormalized(const Quat& q) {
    const double n2 = q.squaredNorm();
    // The product of two unit quaternions is unit to rounding: one Newton step towards
    // 1 / sqrt(n2) restores it to rounding too (its error is quadratic in n2 - 1), with no root
    // or division. Farther off (never from the products here) the full normalisation.
    if (std::abs(n2 - 1.0) > 1e-6) return q.normalized();
    const double scale = 1.5 - 0.5 * n2;
    return Quat(scale * q.w(), scale * q.x(), scale * q.y(), scale * q.z());
}

void integrateVelocities(const SolverBody* bodies, SolverState* states, int begin, int end, double h) {
    for (int i = begin; i < end; ++i) {
        const SolverBody& b = bodies[i];
        if (!b.dynamic) continue;
        SolverState& s = states[i];
        Vec3 v(s.v[0], s.v[1], s.v[2]), w(s.w[0], s.w[1], s.w[2]);
        // Damping in two halves around the forces (Strang splitting): exact decay with no other
        // force, and a terminal speed a / c to second order in c h, where one whole factor after
        // (or before) the forces is off by c h / 2 either way.
        v *= b.linearHalfDampingFactor;
        w *= b.angularHalfDampingFactor;
        v += h * b.linearAcceleration;
        w += h * b.angularAcceleration;
        if (b.gyroscopic != GyroscopicMode::None) {
            const Quat q = (Quat(s.dq[0], s.dq[1], s.dq[2], s.dq[3]) * b.orientation0).normalized();
            if (b.gyroscopic == GyroscopicMode::Implicit)
                w = gyroscopic::solveImplicit(w, q, b.inertia, h);
            else
                w += h * gyroscopic::acceleration(w, q, b.inertia);
        }
        v *= b.linearHalfDampingFactor;
        w *= b.angularHalfDampingFactor;
        for (int k = 0; k < 3; ++k) {
            s.v[k] = v[k];
            s.w[k] = w[k];
        }
    }
}

void displaceBody(SolverState& s, const Vec3& move, const Vec3& turn) {
    for (int k = 0; k < 3; ++k) s.dp[k] += move[k];
    const Quat dq = renormalized(rotationFromVector(turn) * Quat(s.dq[0], s.dq[1], s.dq[2], s.dq[3]));
    s.dq[0] = dq.w();
    s.dq[1] = dq.x();
    s.dq[2] = dq.y();
    s.dq[3] = dq.z();
    // As a turn about Z, dq = (cos t/2, 0, 0, sin t/2): cos t = 1 - 2 z^2, sin t = 2 w z.
    s.turn[0] = 1.0 - 2.0 * dq.z() * dq.z();
    s.turn[1] = 2.0 * dq.w() * dq.z();
}

void integratePositions(SolverState* states, int begin, int end, double h) {
    for (int i = begin; i < end; ++i) {
        SolverState& s = states[i];
        displaceBody(s, h * Vec3(s.v[0], s.v[1], s.v[2]), h * Vec3(s.w[0], s.w[1], s.w[2]));
    }
}

}  // namespace anyphys::native
