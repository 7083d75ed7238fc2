#pragma once
// Shapes and poses for the native collision and query tests, built straight in the backend's
// own types (no world needed).
#include <cstdint>
#include <vector>

#include "../../../api/src/geometry/convex_hull.hpp"
#include "collision/mesh_data.hpp"
#include "collision/shape.hpp"

namespace anyphys::native::test {

inline Shape sphere(double r) {
    Shape s;
    s.type = ShapeType::Sphere;
    s.radius = r;
    return s;
}

inline Shape capsule(double r, double halfHeight) {
    Shape s;
    s.type = ShapeType::Capsule;
    s.radius = r;
    s.halfHeight = halfHeight;
    return s;
}

inline Shape box(const Vec3& half) {
    Shape s;
    s.type = ShapeType::Box;
    s.halfExtents = half;
    return s;
}

/// The plane n . x = offset (n is normalised here).
inline Shape plane(const Vec3& n, double offset) {
    Shape s;
    s.type = ShapeType::Plane;
    s.normal = n.normalized();
    s.offset = offset;
    return s;
}

/// The convex hull of `points`, built as the layer builds it.
inline Shape convex(const std::vector<Vec3>& points) {
    Shape s;
    s.type = ShapeType::Convex;
    s.hull = buildConvexHull(points);
    return s;
}

inline Shape mesh(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& indices) {
    Shape s;
    s.type = ShapeType::Mesh;
    s.mesh = MeshData::build(ShapeDef::mesh(vertices, indices));
    return s;
}

inline Transform at(const Vec3& p, const Quat& q = Quat::Identity()) { return {p, q}; }

inline Quat rotation(double angle, const Vec3& axis) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

}  // namespace anyphys::native::test
