#pragma once
// Collision shapes of the native backend and the few value types every collision routine shares.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "anyphys/defs.hpp"
#include "anyphys/peers/shape_data.hpp"

namespace anyphys::native {

struct MeshData;  // triangle mesh with its bounding-volume hierarchy (mesh_data.hpp)

/// Axis-aligned bounding box, world frame.
struct Aabb {
    Vec3 min = Vec3::Zero();
    Vec3 max = Vec3::Zero();

    bool overlaps(const Aabb& o) const {
        return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
    }
    bool contains(const Aabb& o) const { return (min.array() <= o.min.array()).all() && (o.max.array() <= max.array()).all(); }
    Aabb merged(const Aabb& o) const { return {min.cwiseMin(o.min), max.cwiseMax(o.max)}; }
    Aabb fattened(double margin) const { return {min.array() - margin, max.array() + margin}; }
    Vec3 center() const { return 0.5 * (min + max); }
    Vec3 extents() const { return 0.5 * (max - min); }
    /// Half the surface area: the cost measure of tree building.
    double perimeter() const {
        const Vec3 d = max - min;
        return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
    }
};

/// One primitive shape of a body. Geometry is in the shape's own frame; `local` places that
/// frame in the body (centre of mass) frame.
struct Shape {
    ShapeType type = ShapeType::Sphere;
    double radius = 0.0;                     // sphere, capsule
    Vec3 halfExtents = Vec3::Zero();         // box
    double halfHeight = 0.0;                 // capsule: segment from (0,-h,0) to (0,h,0)
    Vec3 normal = Vec3::UnitY();             // plane, world frame (planes are static; the owner keeps it placed)
    double offset = 0.0;                     // plane
    Vec3 planeNormalLocal = Vec3::UnitY();   // plane in its shape frame (to re-place it if its body moves)
    double planeOffsetLocal = 0.0;
    std::shared_ptr<const HullData> hull;    // convex
    std::shared_ptr<const MeshData> mesh;    // mesh
    Transform local;                         // shape frame -> body frame
};

/// A contact point of a manifold.
struct ManifoldPoint {
    Vec3 point = Vec3::Zero();     // world, midway between the two surfaces
    double separation = 0.0;       // m, negative when overlapping
    std::uint32_t id = 0;          // feature key: equal ids on consecutive steps mean the same contact
};

/// Up to four points sharing one normal. Persisting points (same id) are warm-started.
struct Manifold {
    Vec3 normal = Vec3::Zero();    // world, unit, from shape A to shape B
    std::array<ManifoldPoint, 4> points{};
    int pointCount = 0;
    std::uint32_t key = 0;         // tells apart several manifolds of one shape pair (mesh triangle index)
};

/// Where a contact's anchor lies on a moving body with this shape, relative to the body's centre
/// of mass (world frame, the body turned by `orientation`), for a contact point at `offset` from
/// that centre whose `inward` direction (unit) points from the contact into the shape. A round
/// shape's anchor lies on its core, where turning the body does not move the surface: a sphere's
/// at its centre whatever the point (a normal impulse through it does not turn the ball), a
/// capsule's at the point moved in by its radius (onto its segment). Any other shape's is the
/// point itself.
inline Vec3 contactAnchor(const Shape& s, const Quat& orientation, const Vec3& offset, const Vec3& inward) {
    if (s.type == ShapeType::Sphere) return orientation * s.local.position;
    const double round = s.type == ShapeType::Capsule ? s.radius : 0.0;
    return offset + round * inward;
}

/// World pose of a shape of a body at `bodyPose`.
inline Transform shapeWorldPose(const Shape& s, const Transform& bodyPose) {
    return {bodyPose.position + bodyPose.orientation * s.local.position, bodyPose.orientation * s.local.orientation};
}

}  // namespace anyphys::native
