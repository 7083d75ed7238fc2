#include "ode_gyroscopic.hpp"

#include <Eigen/LU>

namespace anyphys::ode {
namespace {

Mat3 skew(const Vec3& v) {
    Mat3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

}  // namespace

Vec3 solveImplicitGyroscopic(const Vec3& worldOmega, const Quat& orientation, const Vec3& inertia, double h) {
    const Vec3 w0 = orientation.conjugate() * worldOmega;
    const Mat3 I = inertia.asDiagonal();
    Vec3 w = w0;
    // Newton on f(w) = I (w - w0) + h w x (I w); the first iterate is ODE's (and Catto's) one-step
    // update, a few more reach the backward-Euler solution.
    constexpr int kMaxIterations = 8;
    for (int it = 0; it < kMaxIterations; ++it) {
        const Vec3 Iw = I * w;
        const Vec3 f = I * (w - w0) + h * w.cross(Iw);
        const Mat3 jacobian = I + h * (skew(w) * I - skew(Iw));
        const Vec3 delta = jacobian.partialPivLu().solve(f);
        w -= delta;
        if (delta.norm() <= 1e-14 * (1.0 + w.norm())) break;
    }
    return orientation * w;
}

}  // namespace anyphys::ode
