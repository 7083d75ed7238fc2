// Convex shapes against a (static, infinite) plane: each vertex, segment end or sphere centre
// below the plane or within the speculative distance of it is a point.
#include "collision/feature_id.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/narrow_phase.hpp"

namespace anyphys::native {

bool collidePointsPlane(const std::vector<Vec3>& points, double radius, const PlaneGeom& b, double speculative,
                        Manifold& m) {
    const Vec3& n = b.normal;
    ManifoldBuilder builder(-n);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double height = n.dot(points[i]) - b.offset;
        const double separation = height - radius;
        if (separation >= speculative) continue;
        // Plane surface at height 0 under the point, the shape's surface at height - radius.
        builder.add(points[i] - n * (0.5 * (height + radius)), separation,
                    feature::id(feature::Kind::Plane, static_cast<std::uint32_t>(i)));
    }
    return builder.finish(m);
}

}  // namespace anyphys::native
