#include "collision/clip.hpp"

#include <utility>

#include "collision/feature_id.hpp"

namespace anyphys::native {
namespace {

// Side plane k of the reference face: through edge k, facing out of the face.
struct SidePlane {
    Vec3 normal;
    double offset;
};

SidePlane sidePlane(const ReferenceFace& ref, std::size_t k) {
    const Vec3& a = ref.corners[k];
    const Vec3& b = ref.corners[(k + 1) % ref.corners.size()];
    const Vec3 n = (b - a).cross(ref.normal).normalized();
    return {n, n.dot(a)};
}

}  // namespace

std::span<const ClipVertex> clipToFace(std::span<ClipVertex> polygon, int count, std::span<ClipVertex> spare,
                                       const ReferenceFace& ref) {
    std::span<ClipVertex> in = polygon, out = spare;
    for (std::size_t k = 0; k < ref.corners.size() && count > 0; ++k) {
        const SidePlane plane = sidePlane(ref, k);
        const std::uint32_t tag = feature::planeTag(static_cast<std::uint32_t>(k));
        int written = 0;
        for (int i = 0; i < count; ++i) {
            const ClipVertex& cur = in[static_cast<std::size_t>(i)];
            const ClipVertex& next = in[static_cast<std::size_t>(i + 1 < count ? i + 1 : 0)];
            const double dc = plane.normal.dot(cur.point) - plane.offset;
            const double dn = plane.normal.dot(next.point) - plane.offset;
            if (dc <= 0) out[static_cast<std::size_t>(written++)] = cur;
            if ((dc <= 0) != (dn <= 0)) {
                const Vec3 p = cur.point + (dc / (dc - dn)) * (next.point - cur.point);
                // Leaving: the boundary now runs along the side plane. Entering: along the edge.
                out[static_cast<std::size_t>(written++)] = {p, feature::combine(cur.edge, tag), dc <= 0 ? tag : cur.edge};
            }
        }
        count = written;
        std::swap(in, out);
    }
    return in.first(static_cast<std::size_t>(count));
}

void addFacePoints(std::span<const ClipVertex> clipped, const ReferenceFace& ref, double radius, double speculative,
                   std::uint32_t idSeed, ManifoldBuilder& out) {
    for (const ClipVertex& v : clipped) {
        const double height = ref.normal.dot(v.point) - ref.offset;
        const double separation = height - radius;
        if (separation >= speculative) continue;
        // Midway between the reference plane (height 0) and the incident surface (height - radius).
        const Vec3 point = v.point - ref.normal * (height - 0.5 * separation);
        out.add(point, separation, feature::combine(idSeed, v.feature));
    }
}

ClippedSegment clipSegmentToFace(const Vec3& p0, const Vec3& p1, const ReferenceFace& ref) {
    double t0 = 0, t1 = 1;
    std::uint32_t f0 = feature::vertexTag(0), f1 = feature::vertexTag(1);
    for (std::size_t k = 0; k < ref.corners.size(); ++k) {
        const SidePlane plane = sidePlane(ref, k);
        const double d0 = plane.normal.dot(p0) - plane.offset, d1 = plane.normal.dot(p1) - plane.offset;
        if (d0 > 0 && d1 > 0) return {};
        if (d0 > 0 || d1 > 0) {
            const double t = d0 / (d0 - d1);
            if (d0 > 0 && t > t0) {
                t0 = t;
                f0 = feature::planeTag(static_cast<std::uint32_t>(k));
            } else if (d1 > 0 && t < t1) {
                t1 = t;
                f1 = feature::planeTag(static_cast<std::uint32_t>(k));
            }
        }
    }
    if (t0 > t1) return {};
    ClippedSegment s;
    s.ends[0] = {p0 + t0 * (p1 - p0), f0, 0};
    s.ends[1] = {p0 + t1 * (p1 - p0), f1, 0};
    s.count = 2;
    return s;
}

}  // namespace anyphys::native
