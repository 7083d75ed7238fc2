// Spheres and capsules: a sphere is a point with a radius, a capsule a segment with a radius,
// so each pair reduces to closest points of their cores.
#include <algorithm>
#include <cmath>

#include "collision/feature_id.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/segments.hpp"

namespace anyphys::native {
namespace {

// Segments whose directions differ by less than this sine count as parallel: lying side by
// side they touch along a line, which one point cannot hold still.
constexpr double kParallelSine = 0.05;
// A shared stretch shorter than this fraction of the longer segment is end-to-end contact.
constexpr double kMinOverlap = 1e-3;

// One point between core points ca (radius ra) and cb (radius rb). `fallback` is the normal
// when the cores coincide.
bool roundContact(const Vec3& ca, double ra, const Vec3& cb, double rb, const Vec3& fallback, double speculative,
                  Manifold& m) {
    const Vec3 d = cb - ca;
    const double distance = d.norm();
    const double separation = distance - ra - rb;
    if (separation >= speculative) return false;
    const Vec3 n = distance > 1e-12 * (ra + rb + distance) ? Vec3(d / distance) : fallback;
    ManifoldBuilder builder(n);
    // Surfaces at ca + n ra and cb - n rb; midway between them.
    builder.add(0.5 * (ca + n * ra + cb - n * rb), separation, feature::id(feature::Kind::Round, 0));
    return builder.finish(m);
}

// Two points for parallel capsules sharing a stretch of their length; false if they do not.
bool parallelCapsules(const CapsuleGeom& a, const CapsuleGeom& b, const SegmentPair& closest, double speculative,
                      Manifold& m) {
    const Vec3 dA = a.p1 - a.p0, dB = b.p1 - b.p0;
    const double lenA = dA.norm(), lenB = dB.norm();
    if (lenA <= 0 || lenB <= 0 || dA.cross(dB).norm() > kParallelSine * lenA * lenB) return false;
    const Vec3 u = dA / lenA;
    // B's ends measured along A from a.p0; the shared stretch is [lo, hi] within [0, lenA].
    const double s0 = (b.p0 - a.p0).dot(u), s1 = (b.p1 - a.p0).dot(u);
    const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(lenA, std::max(s0, s1));
    if (hi - lo <= kMinOverlap * std::max(lenA, lenB)) return false;

    // The normal across the two lines, from A toward B.
    Vec3 n = closest.onSecond - closest.onFirst;
    n -= n.dot(u) * u;
    if (n.norm() <= 1e-12 * (lenA + lenB)) {  // touching cores: take B's centre side, else any
        n = 0.5 * (b.p0 + b.p1) - 0.5 * (a.p0 + a.p1);
        n -= n.dot(u) * u;
        if (n.norm() <= 1e-12 * (lenA + lenB)) n = u.unitOrthogonal();
    }
    n.normalize();

    // Which end feature bounds each side of the stretch: an end of A, or an end of B.
    const int bLow = s0 <= s1 ? 0 : 1;
    const int loFeature = std::min(s0, s1) > 0 ? 3 + bLow : 1;
    const int hiFeature = std::max(s0, s1) < lenA ? 4 - bLow : 2;
    ManifoldBuilder builder(n);
    for (const auto& [s, tag] : {std::pair{lo, loFeature}, std::pair{hi, hiFeature}}) {
        const Vec3 pa = a.p0 + s * u;
        const Vec3 pb = b.p0 + closestOnSegment(b.p0, b.p1, pa) * dB;
        const double separation = (pb - pa).dot(n) - a.radius - b.radius;
        if (separation >= speculative) continue;
        builder.add(0.5 * (pa + n * a.radius + pb - n * b.radius), separation, feature::id(feature::Kind::Round, tag));
    }
    return builder.finish(m);
}

}  // namespace

bool collideSpheres(const SphereGeom& a, const SphereGeom& b, double speculative, Manifold& m) {
    return roundContact(a.center, a.radius, b.center, b.radius, Vec3::UnitY(), speculative, m);
}

bool collideSphereCapsule(const SphereGeom& a, const CapsuleGeom& b, double speculative, Manifold& m) {
    const Vec3 q = b.p0 + closestOnSegment(b.p0, b.p1, a.center) * (b.p1 - b.p0);
    const Vec3 axis = b.p1 - b.p0;
    const Vec3 fallback = axis.norm() > 0 ? Vec3(axis.unitOrthogonal()) : Vec3::UnitY();
    return roundContact(a.center, a.radius, q, b.radius, fallback, speculative, m);
}

bool collideCapsules(const CapsuleGeom& a, const CapsuleGeom& b, double speculative, Manifold& m) {
    const SegmentPair closest = closestBetweenSegments(a.p0, a.p1, b.p0, b.p1);
    if ((closest.onSecond - closest.onFirst).norm() - a.radius - b.radius >= speculative) return false;
    if (parallelCapsules(a, b, closest, speculative, m)) return true;
    // Crossing cores: the common perpendicular, oriented from A's centre toward B's.
    Vec3 fallback = (a.p1 - a.p0).cross(b.p1 - b.p0);
    if (fallback.norm() > 0) {
        fallback.normalize();
        if (fallback.dot((b.p0 + b.p1) - (a.p0 + a.p1)) < 0) fallback = -fallback;
    } else {
        fallback = Vec3::UnitY();
    }
    return roundContact(closest.onFirst, a.radius, closest.onSecond, b.radius, fallback, speculative, m);
}

}  // namespace anyphys::native
