// Particles against rigid shapes: the signed distance of a point to each primitive and the push
// that takes a particle of some radius out of it. Planes bound a half-space; triangle meshes are
// not collided with (a particle has no inside to be pushed out of).
#include <algorithm>
#include <cmath>
#include <limits>

#include "anyphys/fields/particles.hpp"

namespace anyphys {

namespace {

struct Distance {
    double d = std::numeric_limits<double>::infinity();  // signed: negative inside
    Vec3 normal = Vec3::UnitY();                         // outward, shape frame
};

Distance roundPoint(const Vec3& offset, double radius) {
    const double n = offset.norm();
    return {n - radius, n > 0.0 ? Vec3(offset / n) : Vec3::UnitY()};
}

Distance boxDistance(const Vec3& h, const Vec3& p) {
    const Vec3 q = p.cwiseAbs() - h;
    if (q.maxCoeff() > 0.0) {  // outside: to the nearest point of the box
        const Vec3 outside = q.cwiseMax(0.0);
        const double d = outside.norm();
        return {d, Vec3(outside.cwiseProduct(p.cwiseSign()) / d)};
    }
    int axis = 0;  // inside: out through the nearest face
    q.maxCoeff(&axis);
    Vec3 n = Vec3::Zero();
    n[axis] = p[axis] >= 0.0 ? 1.0 : -1.0;
    return {q[axis], n};
}

// A hull: the largest signed distance to its face planes. Exact inside and over a face; beyond
// an edge or a vertex it is at most the true distance, so particles there keep a little farther.
Distance hullDistance(const ConvexFaces& hull, const Vec3& p) {
    Distance best{-std::numeric_limits<double>::infinity(), Vec3::UnitY()};
    const auto& v = hull.vertices;
    for (const auto& f : hull.faces) {
        Vec3 a = Vec3::Zero();
        for (std::size_t i = 0; i < f.size(); ++i) a += v[f[i]].cross(v[f[(i + 1) % f.size()]]);
        const Vec3 n = a.normalized();
        const double d = n.dot(p - v[f[0]]);
        if (d > best.d) best = {d, n};
    }
    return best;
}

Distance shapeDistance(const FieldShape& s, const Vec3& p) {
    switch (s.type) {
        case ShapeType::Sphere: return roundPoint(p, s.radius);
        case ShapeType::Box: return boxDistance(s.halfExtents, p);
        case ShapeType::Capsule: {
            const double y = std::clamp(p.y(), -s.halfHeight, s.halfHeight);
            return roundPoint(p - Vec3(0, y, 0), s.radius);
        }
        case ShapeType::Convex: return s.hull ? hullDistance(*s.hull, p) : Distance{};
        default: return {};
    }
}

double boundingRadius(const FieldShape& s) {
    switch (s.type) {
        case ShapeType::Sphere: return s.radius;
        case ShapeType::Box: return s.halfExtents.norm();
        case ShapeType::Capsule: return s.halfHeight + s.radius;
        case ShapeType::Convex: {
            double r = 0.0;
            if (s.hull)
                for (const Vec3& v : s.hull->vertices) r = std::max(r, v.norm());
            return r;
        }
        default: return 0.0;
    }
}

}  // namespace

void colliderBounds(ParticleCollider& c) {
    const double inf = std::numeric_limits<double>::infinity();
    c.boundsMin = Vec3::Constant(inf);
    c.boundsMax = Vec3::Constant(-inf);
    for (const FieldShape& s : c.body->shapes) {
        if (s.sensor) continue;  // particles pass through sensor children
        if (s.type == ShapeType::Plane) {  // unbounded
            c.boundsMin = Vec3::Constant(-inf);
            c.boundsMax = Vec3::Constant(inf);
            continue;
        }
        const Vec3 centre = c.pose.position + c.pose.orientation * s.local.position;
        Vec3 reach = Vec3::Constant(boundingRadius(s));
        if (s.type == ShapeType::Box) {  // a box's own extent is much tighter for long thin walls
            const Mat3 R = (c.pose.orientation * s.local.orientation).toRotationMatrix();
            reach = R.cwiseAbs() * s.halfExtents;
        }
        c.boundsMin = c.boundsMin.cwiseMin(centre - reach);
        c.boundsMax = c.boundsMax.cwiseMax(centre + reach);
    }
}

Vec3 colliderPush(const ParticleCollider& c, const Vec3& point, double radius) {
    double deepest = 0.0;
    Vec3 push = Vec3::Zero();
    for (const FieldShape& s : c.body->shapes) {
        if (s.sensor) continue;
        if (s.type == ShapeType::Plane) {  // the half-space below it, in world coordinates
            const double depth = radius - (s.normal.dot(point) - s.offset);
            if (depth > deepest) {
                deepest = depth;
                push = s.normal * depth;
            }
            continue;
        }
        const Quat q = c.pose.orientation * s.local.orientation;
        const Vec3 origin = c.pose.position + c.pose.orientation * s.local.position;
        const Distance d = shapeDistance(s, q.conjugate() * (point - origin));
        const double depth = radius - d.d;
        if (depth > deepest) {
            deepest = depth;
            push = q * d.normal * depth;
        }
    }
    return push;
}

}  // namespace anyphys
