#include "collision/segments.hpp"

#include <algorithm>

namespace anyphys::native {

double closestOnSegment(const Vec3& p0, const Vec3& p1, const Vec3& q) {
    const Vec3 d = p1 - p0;
    const double dd = d.squaredNorm();
    return dd > 0 ? std::clamp((q - p0).dot(d) / dd, 0.0, 1.0) : 0.0;
}

// Minimise |p0 + s d1 - q0 - t d2|^2 over the unit square: the unconstrained optimum clamped
// to [0, 1] in s, then t recomputed for that s and clamped, then s recomputed for that t
// (the standard closed form for segments, e.g. Ericson, Real-Time Collision Detection 5.1.9).
SegmentPair closestBetweenSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    SegmentPair out;
    if (a <= 0 && e <= 0) {
        out.s = out.t = 0;
    } else if (a <= 0) {
        out.s = 0;
        out.t = std::clamp(f / e, 0.0, 1.0);
    } else {
        const double c = d1.dot(r);
        if (e <= 0) {
            out.t = 0;
            out.s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            const double b = d1.dot(d2), denom = a * e - b * b;
            // Parallel (denom ~ 0 relative to a e): any s works; take the first end.
            out.s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
            out.t = (b * out.s + f) / e;
            if (out.t < 0) {
                out.t = 0;
                out.s = std::clamp(-c / a, 0.0, 1.0);
            } else if (out.t > 1) {
                out.t = 1;
                out.s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    out.onFirst = p0 + out.s * d1;
    out.onSecond = q0 + out.t * d2;
    return out;
}

}  // namespace anyphys::native
