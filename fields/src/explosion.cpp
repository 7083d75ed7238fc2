#include <algorithm>
#include <cmath>
#include <limits>

#include "anyphys/fields/field_forces.hpp"
#include "nearest_on_segment.hpp"

namespace anyphys {

namespace {

// In the shape frame: the nearest surface point of a primitive to p, or p when inside.
Vec3 nearestLocal(const FieldShape& s, const Vec3& p) {
    switch (s.type) {
        case ShapeType::Sphere: {
            const double d = p.norm();
            return d <= s.radius ? p : Vec3(p * (s.radius / d));
        }
        case ShapeType::Box: return p.cwiseMax(-s.halfExtents).cwiseMin(s.halfExtents);
        case ShapeType::Capsule: {
            const Vec3 core = nearestOnSegment(Vec3(0, -s.halfHeight, 0), Vec3(0, s.halfHeight, 0), p);
            const double d = (p - core).norm();
            return d <= s.radius ? p : Vec3(core + (p - core) * (s.radius / d));
        }
        case ShapeType::Convex: {
            if (!s.hull) return p;
            // The nearest point of a convex polyhedron lies on a face that faces p: on each, the
            // projection of p if it falls inside the polygon, else the nearest point of its edges.
            const auto& v = s.hull->vertices;
            Vec3 best = p;
            double bestDistance = std::numeric_limits<double>::infinity();
            bool outside = false;
            for (const auto& f : s.hull->faces) {
                Vec3 a = Vec3::Zero();
                for (std::size_t i = 0; i < f.size(); ++i) a += v[f[i]].cross(v[f[(i + 1) % f.size()]]);
                const Vec3 n = a.normalized();
                const double height = n.dot(p - v[f[0]]);
                if (height <= 0.0) continue;
                outside = true;
                const Vec3 projected = p - height * n;
                bool inside = true;
                for (std::size_t i = 0; i < f.size() && inside; ++i) {
                    const Vec3& e0 = v[f[i]];
                    const Vec3& e1 = v[f[(i + 1) % f.size()]];
                    inside = (e1 - e0).cross(projected - e0).dot(n) >= 0.0;
                }
                Vec3 candidate = projected;
                if (!inside) {
                    double nearest = std::numeric_limits<double>::infinity();
                    for (std::size_t i = 0; i < f.size(); ++i) {
                        const Vec3 q = nearestOnSegment(v[f[i]], v[f[(i + 1) % f.size()]], p);
                        if ((q - p).squaredNorm() < nearest) {
                            nearest = (q - p).squaredNorm();
                            candidate = q;
                        }
                    }
                }
                if ((candidate - p).squaredNorm() < bestDistance) {
                    bestDistance = (candidate - p).squaredNorm();
                    best = candidate;
                }
            }
            return outside ? best : p;
        }
        default: return p;
    }
}

}  // namespace

Vec3 nearestSurfacePoint(const FieldBody& body, const Transform& pose, const Vec3& point) {
    Vec3 best = point;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (const FieldShape& s : body.shapes) {
        const Quat q = pose.orientation * s.local.orientation;
        const Vec3 origin = pose.position + pose.orientation * s.local.position;
        const Vec3 nearest = origin + q * nearestLocal(s, q.conjugate() * (point - origin));
        const double d = (nearest - point).squaredNorm();
        if (d < bestDistance) {
            bestDistance = d;
            best = nearest;
        }
    }
    return best;
}

double explosionImpulse(const FieldDef& field, double distance) {
    if (distance >= field.radius) return 0.0;
    return field.impulse * (1.0 - std::max(0.0, distance) / field.radius);
}

std::optional<ExplosionHit> explosionHit(const FieldDef& field, const FieldBody& body, const FieldState& state) {
    const Vec3 point = nearestSurfacePoint(body, state.pose, field.center);
    const Vec3 offset = point - field.center;
    const double distance = offset.norm();
    const double magnitude = explosionImpulse(field, distance);
    if (magnitude <= 0.0) return std::nullopt;
    Vec3 direction = offset;
    if (distance <= 0.0) direction = state.pose.position - field.center;  // the centre is inside the body
    if (direction.norm() <= 0.0) direction = Vec3::UnitY();
    return ExplosionHit{direction.normalized() * magnitude, point};
}

}  // namespace anyphys
