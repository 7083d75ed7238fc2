#include "ode_hull_geometry.hpp"

#include <algorithm>
#include <limits>

namespace anyphys::ode {

Vec3 nearestOnSegment(const Vec3& a, const Vec3& b, const Vec3& p) {
    const Vec3 ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return a + t * ab;
}

// The nearest point lies on a face p is in front of: inside that face, or on one of its edges.
Vec3 nearestOnSurface(const HullData& hull, const Vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    Vec3 nearest = p;
    const auto consider = [&](const Vec3& q) {
        if (const double d2 = (p - q).squaredNorm(); d2 < best) {
            best = d2;
            nearest = q;
        }
    };
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
        const Vec3& n = hull.faceNormals[f];
        const double height = n.dot(p) - hull.faceOffsets[f];
        if (height <= 0.0) continue;
        const std::vector<int>& loop = hull.faces[f];
        bool inside = true;
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const Vec3& a = hull.vertices[loop[k]];
            const Vec3& b = hull.vertices[loop[(k + 1) % loop.size()]];
            if ((b - a).cross(p - a).dot(n) < 0.0) {  // beyond this edge (the loop is counter-clockwise)
                inside = false;
                consider(nearestOnSegment(a, b, p));
            }
        }
        if (inside) consider(p - height * n);
    }
    return nearest;
}

// Minimise |p(s) - q(t)| over s, t in [0, 1]: the unconstrained s for the lines, clamped, then
// t for that s, clamped, then s again for the clamped t (the order that stays on the segments).
SegmentPair nearestBetweenSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    if (a <= 0.0 && e <= 0.0) return {p0, q0};
    if (a <= 0.0) return {p0, nearestOnSegment(q0, q1, p0)};
    if (e <= 0.0) return {nearestOnSegment(p0, p1, q0), q0};
    const double c = d1.dot(r), b = d1.dot(d2);
    const double denominator = a * e - b * b;  // >= 0; zero for parallel segments, where any s will do
    double s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
    double t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
    } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
    }
    return {p0 + s * d1, q0 + t * d2};
}

}  // namespace anyphys::ode
