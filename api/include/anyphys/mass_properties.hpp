#pragma once
// Mass properties of solid shapes of uniform density, about the centre of mass, in the body frame.
#include <numbers>

#include "anyphys/defs.hpp"

namespace anyphys {

/// Volume in m^3 of a sphere, box or capsule (0 otherwise: planes and meshes are static only,
/// convex hulls and compounds are measured from their built geometry in the layer).
inline double shapeVolume(const ShapeDef& s) {
    constexpr double pi = std::numbers::pi;
    switch (s.type) {
        case ShapeType::Sphere: return 4.0 / 3.0 * pi * s.radius * s.radius * s.radius;
        case ShapeType::Box: return 8.0 * s.halfExtents.x() * s.halfExtents.y() * s.halfExtents.z();
        case ShapeType::Capsule: {
            const double r = s.radius;
            return pi * r * r * (2.0 * s.halfHeight) + 4.0 / 3.0 * pi * r * r * r;
        }
        case ShapeType::Plane:
        case ShapeType::Mesh:
        case ShapeType::Convex:
        case ShapeType::Compound: return 0.0;
    }
    return 0.0;
}

/// Principal moments of inertia per unit mass (m^2), body frame, of a sphere, box or capsule.
inline Vec3 unitInertia(const ShapeDef& s) {
    switch (s.type) {
        case ShapeType::Sphere: {
            const double i = 0.4 * s.radius * s.radius;
            return Vec3(i, i, i);
        }
        case ShapeType::Box: {
            const Vec3 d = 2.0 * s.halfExtents;
            return Vec3(d.y() * d.y() + d.z() * d.z(), d.x() * d.x() + d.z() * d.z(), d.x() * d.x() + d.y() * d.y()) / 12.0;
        }
        case ShapeType::Capsule: {
            // Cylinder of length 2h plus two hemispheres whose centres of mass sit 3r/8 beyond the
            // segment ends (parallel-axis theorem), weighted by volume.
            constexpr double pi = std::numbers::pi;
            const double r = s.radius, h = s.halfHeight;
            const double vc = pi * r * r * 2.0 * h, vs = 4.0 / 3.0 * pi * r * r * r, v = vc + vs;
            const double axialCyl = 0.5 * r * r, axialSph = 0.4 * r * r;
            const double transCyl = (3.0 * r * r + 4.0 * h * h) / 12.0;
            const double transSph = 0.4 * r * r + h * h + 0.75 * h * r;  // about the centre, both caps
            const double axial = (vc * axialCyl + vs * axialSph) / v;
            const double trans = (vc * transCyl + vs * transSph) / v;
            return Vec3(trans, axial, trans);
        }
        case ShapeType::Plane:
        case ShapeType::Mesh:
        case ShapeType::Convex:
        case ShapeType::Compound: return Vec3::Zero();
    }
    return Vec3::Zero();
}

}  // namespace anyphys
