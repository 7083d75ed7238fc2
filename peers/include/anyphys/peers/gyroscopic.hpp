#pragma once
// The gyroscopic term of Euler's rigid-body equations, I dw/dt = tau - w x (I w) (body frame),
// as the layer defines GyroscopicMode: shared by every backend that applies it itself rather than
// through its engine (native always; ODE, whose own implicit step can let |L| grow).
#include <Eigen/LU>

#include "anyphys/math.hpp"

namespace anyphys::gyroscopic {

/// Whether the term can matter: it vanishes identically when all principal moments are equal.
inline bool isAnisotropic(const Vec3& inertia) {
    return inertia.maxCoeff() - inertia.minCoeff() > 1e-12 * inertia.maxCoeff();
}

/// Explicit term: the angular acceleration -I^-1 (w x I w) in the world frame, for world-frame w,
/// principal moments `inertia` and orientation q.
inline Vec3 acceleration(const Vec3& worldOmega, const Quat& q, const Vec3& inertia) {
    const Vec3 w = q.conjugate() * worldOmega;
    return q * Vec3(-(w.cross(inertia.cwiseProduct(w))).cwiseQuotient(inertia));
}

/// Implicit (backward Euler) update of torque-free rotation over h: solves
///   I (w1 - w0) + h w1 x (I w1) = 0   in the body frame by Newton's method,
/// and returns w1 in the world frame. Unconditionally stable; |L| is kept closely and kinetic
/// energy never grows. The first Newton iterate is Catto's one-step update (and ODE's); a few
/// more make it the true backward-Euler solution.
inline Vec3 solveImplicit(const Vec3& worldOmega, const Quat& q, const Vec3& inertia, double h) {
    const auto skew = [](const Vec3& v) {
        Mat3 m;
        m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
        return m;
    };
    const Vec3 w0 = q.conjugate() * worldOmega;
    const Mat3 I = inertia.asDiagonal();
    Vec3 w = w0;
    constexpr int kMaxIterations = 8;
    for (int it = 0; it < kMaxIterations; ++it) {
        const Vec3 Iw = I * w;
        const Vec3 f = I * (w - w0) + h * w.cross(Iw);
        const Mat3 jacobian = I + h * (skew(w) * I - skew(Iw));
        const Vec3 delta = jacobian.partialPivLu().solve(f);
        w -= delta;
        if (delta.norm() <= 1e-14 * (1.0 + w.norm())) break;
    }
    return q * w;
}

}  // namespace anyphys::gyroscopic
