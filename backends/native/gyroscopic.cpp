#include "gyroscopic.hpp"

namespace anyphys::native {
namespace {

Mat3 skew(const Vec3& v) {
    Mat3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

}  // namespace

Vec3 gyroscopicAcceleration(const Vec3& worldOmega, const Quat& q, const Vec3& inertia) {
    const Vec3 w = q.conjugate() * worldOmega;
    const Vec3 alpha = -(w.cross(inertia.cwiseProduct(w))).cwiseQuotient(inertia);
    return q * alpha;
}

Vec3 solveImplicitGyroscopic(const Vec3& worldOmega, const Quat& q, const Vec3& inertia, double h) {
    const Vec3 w0 = q.conjugate() * worldOmega;
    const Mat3 I = inertia.asDiagonal();
    Vec3 w = w0;
    // Newton on f(w) = I (w - w0) + h w x (I w). The first iterate is Catto's one-step update;
    // a few more make it the true backward-Euler solution ("solved per body").
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

}  // namespace anyphys::native
