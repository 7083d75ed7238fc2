#include "shape_bounds.hpp"

#include <limits>
#include <span>

namespace anyphys {
namespace {

/// The box holding every point of `points` (shape frame) placed at `pose`.
std::optional<Aabb> pointBounds(std::span<const Vec3> points, const Transform& pose) {
    if (points.empty()) return std::nullopt;
    Aabb box{Vec3::Constant(std::numeric_limits<double>::infinity()),
             Vec3::Constant(-std::numeric_limits<double>::infinity())};
    for (const Vec3& p : points) {
        const Vec3 world = pose.position + pose.orientation * p;
        box.min = box.min.cwiseMin(world);
        box.max = box.max.cwiseMax(world);
    }
    return box;
}

/// Half sizes along the world axes of a box with `half` sizes turned by `rotation`: each world
/// axis sees |R| times the half sizes.
Vec3 rotatedHalfExtents(const Quat& rotation, const Vec3& half) {
    return rotation.toRotationMatrix().cwiseAbs() * half;
}

}  // namespace

std::optional<Aabb> shapeBounds(const ShapeDef& shape, const Transform& pose) {
    switch (shape.type) {
        case ShapeType::Sphere: {
            const Vec3 r = Vec3::Constant(shape.radius);
            return Aabb{pose.position - r, pose.position + r};
        }
        case ShapeType::Box: {
            const Vec3 h = rotatedHalfExtents(pose.orientation, shape.halfExtents);
            return Aabb{pose.position - h, pose.position + h};
        }
        case ShapeType::Capsule: {
            // The core segment along the shape's Y, swept by the radius.
            const Vec3 tip = (pose.orientation * Vec3(0, shape.halfHeight, 0)).cwiseAbs();
            const Vec3 h = tip + Vec3::Constant(shape.radius);
            return Aabb{pose.position - h, pose.position + h};
        }
        case ShapeType::Convex: return pointBounds(shape.points, pose);
        case ShapeType::Mesh: return pointBounds(shape.vertices, pose);
        case ShapeType::Plane:
        case ShapeType::Compound: return std::nullopt;
    }
    return std::nullopt;
}

}  // namespace anyphys
