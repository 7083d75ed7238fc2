// Convex shapes against a (static, infinite) plane: each vertex, segment end or sphere centre
// below the plane or within the speculative distance of it is a point.
#include <vector>

#include "collision/feature_id.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/scratch.hpp"

namespace anyphys::native {
namespace {

// Point i at `height` over the plane (its surface at height - radius): placed midway between the
// plane and the shape's surface.
void addPlanePoint(const Vec3& point, double height, double radius, const PlaneGeom& b, int i, ManifoldBuilder& builder) {
    builder.add(point - b.normal * (0.5 * (height + radius)), height - radius,
                feature::id(feature::Kind::Plane, static_cast<std::uint32_t>(i)));
}

}  // namespace

bool collidePointsPlane(std::span<const Vec3> points, double radius, const PlaneGeom& b, double speculative, Manifold& m) {
    ManifoldBuilder builder(-b.normal);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double height = b.normal.dot(points[i]) - b.offset;
        if (height - radius < speculative) addPlanePoint(points[i], height, radius, b, static_cast<int>(i), builder);
    }
    return builder.finish(m);
}

bool collideBoxPlane(const BoxGeom& a, const PlaneGeom& b, double speculative, Manifold& m) {
    // Corner i's height: the centre's, plus or minus the normal's reach along each box axis.
    const Vec3 reach = (a.rotation.transpose() * b.normal).cwiseProduct(a.half);
    const double centre = b.normal.dot(a.center) - b.offset;
    if (centre - reach.cwiseAbs().sum() >= speculative) return false;  // even the lowest corner is too high
    ManifoldBuilder builder(-b.normal);
    for (int i = 0; i < 8; ++i) {
        const Vec3 sign((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
        const double height = centre + sign.dot(reach);
        if (height < speculative)
            addPlanePoint(a.center + a.rotation * sign.cwiseProduct(a.half), height, 0.0, b, i, builder);
    }
    return builder.finish(m);
}

bool collidePolytopePlane(const Polytope& a, const PlaneGeom& b, double speculative, Manifold& m) {
    thread_local std::vector<ManifoldBuilder::Candidate> candidates;
    const Vec3 along = a.rotation.transpose() * b.normal;
    const double centre = b.normal.dot(a.position) - b.offset;
    if (centre + a.localProject(along)[0] >= speculative) return false;
    ManifoldBuilder builder = a.vertices.size() <= static_cast<std::size_t>(ManifoldBuilder::kInlineCapacity)
                                  ? ManifoldBuilder(-b.normal)
                                  : ManifoldBuilder(-b.normal, firstOf(candidates, a.vertices.size()));
    for (int i = 0; i < a.vertexCount(); ++i) {
        const double height = centre + along.dot(a.vertices[static_cast<std::size_t>(i)]);
        if (height < speculative) addPlanePoint(a.vertex(i), height, 0.0, b, i, builder);
    }
    return builder.finish(m);
}

}  // namespace anyphys::native
