#pragma once
// Closest points on line segments.
#include "anyphys/math.hpp"

namespace anyphys::native {

/// Parameter in [0, 1] of the point of segment p0 -> p1 closest to q.
double closestOnSegment(const Vec3& p0, const Vec3& p1, const Vec3& q);

struct SegmentPair {
    double s = 0.0;  // parameter on the first segment, [0, 1]
    double t = 0.0;  // parameter on the second segment, [0, 1]
    Vec3 onFirst = Vec3::Zero();
    Vec3 onSecond = Vec3::Zero();
};

/// Closest points of segments p0 -> p1 and q0 -> q1 (either may be a point). For parallel
/// segments, one of the closest pairs.
SegmentPair closestBetweenSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

}  // namespace anyphys::native
