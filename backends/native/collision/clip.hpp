#pragma once
// Reference-face clipping: the incident face (a polygon, or a capsule's segment) is clipped to the
// prism standing on the reference face; the parts within the speculative distance of the
// reference plane become contact points.
#include <cstdint>
#include <vector>

#include "anyphys/math.hpp"
#include "collision/manifold_builder.hpp"

namespace anyphys::native {

struct ClipVertex {
    Vec3 point = Vec3::Zero();
    std::uint32_t feature = 0;  // what made this vertex (feature::vertexTag, or edge x plane)
    std::uint32_t edge = 0;     // what the polygon edge leaving this vertex lies on
};

struct ReferenceFace {
    std::vector<Vec3> corners;     // world, counter-clockwise about normal
    Vec3 normal = Vec3::Zero();    // outward, toward the incident shape
    double offset = 0.0;           // normal.dot(x) == offset on the face
};

/// The incident polygon corners[loop[i]] with features naming vertex loop[i] and the edge that
/// leaves it.
std::vector<ClipVertex> incidentPolygon(const std::vector<Vec3>& corners, const std::vector<int>& loop);

/// Clips `polygon` to the side planes of the reference face (Sutherland-Hodgman). A point made by
/// cutting an edge with side plane k gets the feature (edge, k), so it keeps its id while the
/// same edge crosses the same side.
std::vector<ClipVertex> clipToFace(std::vector<ClipVertex> polygon, const ReferenceFace& ref);

/// Adds the clipped polygon's points with separation < speculative (measured from the reference
/// plane, `radius` subtracted for a rounded incident shape), each placed midway between the two
/// surfaces, with id combine(idSeed, feature).
void addFacePoints(const std::vector<ClipVertex>& clipped, const ReferenceFace& ref, double radius, double speculative,
                   std::uint32_t idSeed, ManifoldBuilder& out);

/// Clips segment p0 -> p1 to the side planes of the reference face. Ends keep feature
/// vertexTag(0 or 1) unless cut, then planeTag(k) of the cutting side. Empty if it misses.
std::vector<ClipVertex> clipSegmentToFace(const Vec3& p0, const Vec3& p1, const ReferenceFace& ref);

}  // namespace anyphys::native
