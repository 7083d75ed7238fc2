#pragma once
// Closest-point geometry in a hull's own frame, shared by the backend's replacement colliders
// (ode_convex_sphere.hpp, ode_convex_capsule.hpp). Every walk is bounded by the hull's faces and
// edges: no iteration here depends on convergence.
#include "anyphys/math.hpp"
#include "anyphys/peers/shape_data.hpp"

namespace anyphys::ode {

/// The point of segment ab nearest to p.
Vec3 nearestOnSegment(const Vec3& a, const Vec3& b, const Vec3& p);

/// The point of the hull's surface nearest to p, a point outside the hull.
Vec3 nearestOnSurface(const HullData& hull, const Vec3& p);

/// The nearest points of segments p0p1 (onP) and q0q1 (onQ).
struct SegmentPair {
    Vec3 onP, onQ;
};
SegmentPair nearestBetweenSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

}  // namespace anyphys::ode
