#pragma once
// Reference-face clipping: the incident face (a polygon, or a capsule's segment) is clipped to the
// prism standing on the reference face; the parts within the speculative distance of the
// reference plane become contact points. Nothing here allocates: polygons live in the caller's
// buffers.
#include <array>
#include <cstdint>
#include <span>

#include "anyphys/math.hpp"
#include "collision/feature_id.hpp"
#include "collision/manifold_builder.hpp"

namespace anyphys::native {

struct ClipVertex {
    Vec3 point;
    std::uint32_t feature;  // what made this vertex (feature::vertexTag, or edge x plane)
    std::uint32_t edge;     // what the polygon edge leaving this vertex lies on
};

struct ReferenceFace {
    std::span<const Vec3> corners;  // world, counter-clockwise about normal (the caller's storage)
    Vec3 normal = Vec3::Zero();     // outward, toward the incident shape
    double offset = 0.0;            // normal.dot(x) == offset on the face
};

/// The incident polygon vertex: corner `v` of its shape, with features naming vertex v and the
/// edge that leaves it.
inline ClipVertex incidentVertex(const Vec3& corner, int v) {
    return {corner, feature::vertexTag(static_cast<std::uint32_t>(v)), feature::edgeTag(static_cast<std::uint32_t>(v))};
}

/// Clips the polygon in the first `count` entries of `polygon` to the side planes of the
/// reference face (Sutherland-Hodgman), with `spare` as the second buffer. Both buffers must
/// hold count + ref.corners.size() vertices. Returns the clipped polygon, in one of the two. A
/// point made by cutting an edge with side plane k gets the feature (edge, k), so it keeps its id
/// while the same edge crosses the same side.
std::span<const ClipVertex> clipToFace(std::span<ClipVertex> polygon, int count, std::span<ClipVertex> spare,
                                       const ReferenceFace& ref);

/// Adds the clipped polygon's points with separation < speculative (measured from the reference
/// plane, `radius` subtracted for a rounded incident shape), each placed midway between the two
/// surfaces, with id combine(idSeed, feature).
void addFacePoints(std::span<const ClipVertex> clipped, const ReferenceFace& ref, double radius, double speculative,
                   std::uint32_t idSeed, ManifoldBuilder& out);

/// A segment clipped to a reference face: zero or two ends.
struct ClippedSegment {
    std::array<ClipVertex, 2> ends;
    int count = 0;
    std::span<const ClipVertex> view() const {
        return std::span<const ClipVertex>(ends.data(), static_cast<std::size_t>(count));
    }
};

/// Clips segment p0 -> p1 to the side planes of the reference face. Ends keep feature
/// vertexTag(0 or 1) unless cut, then planeTag(k) of the cutting side. Empty if it misses.
ClippedSegment clipSegmentToFace(const Vec3& p0, const Vec3& p1, const ReferenceFace& ref);

}  // namespace anyphys::native
