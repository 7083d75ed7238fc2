#include "anyphys/fields/field_shape.hpp"

#include <cmath>
#include <numbers>

namespace anyphys {

ConvexFaces boxFaces(const Vec3& h) {
    ConvexFaces box;
    for (int i = 0; i < 8; ++i)
        box.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    // +x, -x, +y, -y, +z, -z; each counter-clockwise seen from outside.
    box.faces = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
    return box;
}

double shapeVolume(const FieldShape& s) {
    switch (s.type) {
        case ShapeType::Sphere: return 4.0 / 3.0 * std::numbers::pi * s.radius * s.radius * s.radius;
        case ShapeType::Box: return 8.0 * s.halfExtents.x() * s.halfExtents.y() * s.halfExtents.z();
        case ShapeType::Capsule:
            return std::numbers::pi * s.radius * s.radius * (2.0 * s.halfHeight + 4.0 / 3.0 * s.radius);
        case ShapeType::Convex: {
            if (!s.hull || s.hull->vertices.empty()) return 0.0;
            const Vec3 o = s.hull->vertices[0];
            double v = 0.0;
            for (const auto& f : s.hull->faces)
                for (std::size_t i = 1; i + 1 < f.size(); ++i)
                    v += (s.hull->vertices[f[0]] - o).dot((s.hull->vertices[f[i]] - o).cross(s.hull->vertices[f[i + 1]] - o));
            return v / 6.0;
        }
        default: return 0.0;
    }
}

}  // namespace anyphys
