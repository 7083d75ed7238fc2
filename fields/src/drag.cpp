#include <cmath>
#include <numbers>

#include "anyphys/fields/field_forces.hpp"

namespace anyphys {

double projectedArea(const FieldShape& shape, const Quat& bodyOrientation, const Vec3& d) {
    const Vec3 l = (bodyOrientation * shape.local.orientation).conjugate() * d;  // d in the shape frame
    const double pi = std::numbers::pi;
    switch (shape.type) {
        case ShapeType::Sphere: return pi * shape.radius * shape.radius;
        case ShapeType::Box: {
            const Vec3& h = shape.halfExtents;
            return 4.0 * (h.y() * h.z() * std::abs(l.x()) + h.x() * h.z() * std::abs(l.y()) + h.x() * h.y() * std::abs(l.z()));
        }
        case ShapeType::Capsule: {
            const double sine = std::sqrt(std::max(0.0, 1.0 - l.y() * l.y()));
            return pi * shape.radius * shape.radius + 4.0 * shape.radius * shape.halfHeight * sine;
        }
        case ShapeType::Convex: {
            if (!shape.hull) return 0.0;
            double area = 0.0;
            for (const auto& f : shape.hull->faces) {
                Vec3 a = Vec3::Zero();  // twice the face's area along its normal
                for (std::size_t i = 0; i < f.size(); ++i)
                    a += shape.hull->vertices[f[i]].cross(shape.hull->vertices[f[(i + 1) % f.size()]]);
                area += std::abs(a.dot(l));
            }
            return 0.25 * area;  // half the sum of |n_f . d| A_f, with A_f = |a| / 2
        }
        default: return 0.0;
    }
}

double projectedArea(const FieldBody& body, const Quat& bodyOrientation, const Vec3& d) {
    double area = 0.0;
    for (const FieldShape& s : body.shapes) area += projectedArea(s, bodyOrientation, d);
    return area;
}

FieldForce quadraticDrag(const FieldBody& body, const Quat& bodyOrientation, const Vec3& v, double rho) {
    const double speed = v.norm();
    if (speed <= 0.0) return {};
    const double area = projectedArea(body, bodyOrientation, v / speed);
    return {-0.5 * rho * body.dragCoefficient * area * speed * v, Vec3::Zero()};
}

FieldForce dragForce(const FieldDef& field, const FieldBody& body, const FieldState& state) {
    return quadraticDrag(body, state.pose.orientation, state.linearVelocity, field.airDensity);
}

}  // namespace anyphys
