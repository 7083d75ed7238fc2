#pragma once
// The nearest point of a segment to a point, shared by the explosion's occlusion shapes and the
// particles' triangle contacts.
#include <algorithm>

#include "anyphys/math.hpp"

namespace anyphys {

/// Nearest point of segment [a, b] to p; a when the segment has no length.
inline Vec3 nearestOnSegment(const Vec3& a, const Vec3& b, const Vec3& p) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return a + t * ab;
}

}  // namespace anyphys
