// Bounding boxes of shapes (computeAabb).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "anyphys/limits.hpp"
#include "collision/mesh_data.hpp"
#include "collision/query_helpers.hpp"

namespace anyphys::native {
namespace {

// Half size of the box standing in for an infinite plane: finite so that tree arithmetic
// (perimeters, merges) stays finite, and past every coordinate a world admits, so a body anywhere
// on the plane meets it in the broad phase (at 1e6 m a box resting 3e6 m out fell through).
constexpr double kPlaneExtent = 2.0 * kMaxCoordinate;

Aabb pointsAabb(const std::vector<Vec3>& points, const Transform& xf) {
    const Mat3 r = xf.orientation.toRotationMatrix();
    Aabb box{Vec3::Constant(kInf), Vec3::Constant(-kInf)};
    for (const Vec3& p : points) {
        const Vec3 w = r * p;
        box.min = box.min.cwiseMin(w);
        box.max = box.max.cwiseMax(w);
    }
    box.min += xf.position;
    box.max += xf.position;
    return box;
}

// Exact bounds of the solid half-space n.p <= offset within the cube |p_i| <= kPlaneExtent: along
// axis i the half-space reaches at most (offset + L * sum_{j != i} |n_j|) / n_i.
Aabb planeAabb(const Vec3& n, double offset) {
    const double l = kPlaneExtent;
    Aabb box{Vec3::Constant(-l), Vec3::Constant(l)};
    const double sumAbs = n.cwiseAbs().sum();
    for (int i = 0; i < 3; ++i) {
        if (std::abs(n[i]) < 1e-12) continue;
        const double reach = (offset + l * (sumAbs - std::abs(n[i]))) / n[i];
        if (n[i] > 0.0) {
            box.max[i] = std::clamp(reach, -l, l);
        } else {
            box.min[i] = std::clamp(reach, -l, l);
        }
    }
    return box;
}

}  // namespace

Aabb computeAabb(const Shape& s, const Transform& xf) {
    switch (s.type) {
        case ShapeType::Sphere: return {xf.position.array() - s.radius, xf.position.array() + s.radius};
        case ShapeType::Capsule: {
            const Vec3 axis = (xf.orientation * Vec3(0, s.halfHeight, 0)).cwiseAbs();
            return {xf.position - axis - Vec3::Constant(s.radius), xf.position + axis + Vec3::Constant(s.radius)};
        }
        case ShapeType::Box: {
            const Vec3 e = xf.orientation.toRotationMatrix().cwiseAbs() * s.halfExtents;
            return {xf.position - e, xf.position + e};
        }
        case ShapeType::Plane: return planeAabb(s.normal, s.offset);
        case ShapeType::Convex: return pointsAabb(s.hull->vertices, xf);
        case ShapeType::Mesh: return pointsAabb(s.mesh->vertices, xf);
        case ShapeType::Compound: break;
    }
    throw std::invalid_argument("computeAabb: compound shapes are flattened before they reach the backend");
}

}  // namespace anyphys::native
