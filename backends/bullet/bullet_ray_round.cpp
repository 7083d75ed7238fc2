#include "bullet_ray_round.hpp"

#include <algorithm>
#include <cmath>

namespace anyphys::bullet {

namespace {

// Entering root of |o + t d - c|^2 = r^2 (unit d), if the origin is outside the sphere.
std::optional<double> rayIntoSphere(const Vec3& o, const Vec3& d, const Vec3& c, double r) {
    const Vec3 m = o - c;
    const double b = m.dot(d), q = m.squaredNorm() - r * r;
    if (q <= 0.0) return std::nullopt;  // inside (or on) the sphere: the capsule decides below
    const double disc = b * b - q;
    if (disc < 0.0 || b > 0.0) return std::nullopt;  // misses, or points away
    return -b - std::sqrt(disc);
}

}  // namespace

std::optional<RayEntry> rayIntoCapsule(const Vec3& origin, const Vec3& direction, double maxDistance, const Vec3& a,
                                       const Vec3& b, double radius) {
    const Vec3 axis = b - a;
    const double length2 = axis.squaredNorm();
    // The origin's nearest point on the axis segment: inside the capsule, nothing is hit.
    const double along = length2 > 0.0 ? std::clamp((origin - a).dot(axis) / length2, 0.0, 1.0) : 0.0;
    if ((origin - (a + along * axis)).squaredNorm() < radius * radius) return std::nullopt;

    std::optional<RayEntry> best;
    const auto consider = [&](double t, const Vec3& centre) {
        if (!(t >= 0.0 && t <= maxDistance) || (best && best->distance <= t)) return;
        best = RayEntry{t, (origin + t * direction - centre).normalized()};
    };
    // The side: |(p - a) x axis|^2 = r^2 |axis|^2 with p = o + t d, entering where the axis
    // parameter lies between the ends.
    if (length2 > 0.0) {
        const Vec3 m = origin - a;
        const double md = m.dot(axis), dd = direction.dot(axis);
        const double qa = length2 - dd * dd;
        const double qb = length2 * m.dot(direction) - md * dd;
        const double qc = length2 * (m.squaredNorm() - radius * radius) - md * md;
        const double disc = qb * qb - qa * qc;
        if (qa > 1e-12 * length2 && disc >= 0.0) {
            const double t = (-qb - std::sqrt(disc)) / qa;
            const double s = (md + t * dd) / length2;  // where along the axis, 0 at a, 1 at b
            if (s >= 0.0 && s <= 1.0) consider(t, a + s * axis);
        }
    }
    // The end caps.
    for (const Vec3& end : {a, b})
        if (const std::optional<double> t = rayIntoSphere(origin, direction, end, radius)) consider(*t, end);
    return best;
}

}  // namespace anyphys::bullet
