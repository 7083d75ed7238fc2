// Particles against rigid shapes: the signed distance of a point to each primitive and the push
// that takes a particle of some radius out of it. Planes bound a half-space. A triangle mesh is a
// surface with no inside, so the side a particle belongs on is the side of each triangle it
// started the substep on: a path from there that crossed a triangle is moved back to that side,
// and a particle within its radius of a triangle is pushed out to the radius on that side.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "anyphys/fields/particles.hpp"
#include "nearest_on_segment.hpp"

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

// ---- triangle meshes ----------------------------------------------------------------------

using Triangle = TriangleMesh::Triangle;

// Whether q, in the triangle's plane, lies inside it or on its edges. Inclusive, with a little
// slack: a point on the edge two triangles share must count for one of them, or a particle could
// slip through the crack between them.
bool inTriangle(const Triangle& t, const Vec3& q) {
    const Vec3* corners[3] = {&t.a, &t.b, &t.c};
    for (int k = 0; k < 3; ++k) {
        const Vec3& u = *corners[k];
        const Vec3& v = *corners[(k + 1) % 3];
        if (t.normal.dot((v - u).cross(q - u)) < -1e-9 * (v - u).squaredNorm()) return false;
    }
    return true;
}

// The point of the triangle nearest p, and whether it is inside the face (not on an edge or a
// corner): the foot of the perpendicular when that falls inside, else the nearest of the edges.
struct Nearest {
    Vec3 point;
    bool face;
};
Nearest nearestOnTriangle(const Triangle& t, const Vec3& p) {
    const Vec3 foot = p - t.normal.dot(p - t.a) * t.normal;
    if (inTriangle(t, foot)) return {foot, true};
    Vec3 best = nearestOnSegment(t.a, t.b, p);
    for (const Vec3& q : {nearestOnSegment(t.b, t.c, p), nearestOnSegment(t.c, t.a, p)})
        if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return {best, false};
}

// +1 or -1: the side of the triangle's plane the particle started on (`from`); a start exactly in
// the plane takes the side it is now on, and the front (counter-clockwise) side if that is too.
double sideOf(const Triangle& t, const Vec3& from, const Vec3& now) {
    const double start = t.normal.dot(from - t.a);
    if (start != 0.0) return start > 0.0 ? 1.0 : -1.0;
    return t.normal.dot(now - t.a) < 0.0 ? -1.0 : 1.0;
}

// Where along the path from x to p (0 to 1) it passes through the triangle, or -1 if it does
// not: the path's ends on strictly opposite sides of the plane, the crossing point inside.
double pathCrossing(const Triangle& t, const Vec3& x, const Vec3& p) {
    const double dx = t.normal.dot(x - t.a), dp = t.normal.dot(p - t.a);
    if (!(dx * dp < 0.0)) return -1.0;
    const double f = dx / (dx - dp);
    return inTriangle(t, x + f * (p - x)) ? f : -1.0;
}

// A path that went through the mesh ends at its radius on the start's side of the first triangle
// it crossed (moved along that triangle's normal, keeping its motion along the surface).
Vec3 backAcross(const TriangleMesh& mesh, const std::vector<std::uint32_t>& near, const Vec3& x, const Vec3& p,
                double radius) {
    double first = 2.0;
    const Triangle* crossed = nullptr;
    for (std::uint32_t k : near) {
        const double f = pathCrossing(mesh.triangles()[k], x, p);
        if (f >= 0.0 && f < first) {
            first = f;
            crossed = &mesh.triangles()[k];
        }
    }
    if (!crossed) return p;
    const Vec3 n = sideOf(*crossed, x, p) * crossed->normal;
    return p + (radius - n.dot(p - crossed->a)) * n;
}

// The deepest push that takes a particle at q out to `radius` from the mesh's triangles: over a
// face, along the normal on the side it started on (also when it is behind the face: it has not
// crossed it, so it belongs in front); beyond an edge or a corner, straight away from the nearest
// point, so particles round the mesh's open edges instead of jumping onto them.
Vec3 outOfTriangles(const TriangleMesh& mesh, const std::vector<std::uint32_t>& near, const Vec3& x, const Vec3& q,
                    double radius) {
    double deepest = 0.0;
    Vec3 push = Vec3::Zero();
    for (std::uint32_t k : near) {
        const Triangle& t = mesh.triangles()[k];
        const Nearest c = nearestOnTriangle(t, q);
        const Vec3 away = q - c.point;
        const double d = away.norm();
        if (d >= radius) continue;
        Vec3 direction;
        double depth;
        if (c.face || d == 0.0) {
            direction = sideOf(t, x, q) * t.normal;
            depth = radius - direction.dot(q - t.a);
        } else {
            direction = away / d;
            depth = radius - d;
        }
        if (depth > deepest) {
            deepest = depth;
            push = depth * direction;
        }
    }
    return push;
}

// The displacement that keeps a particle on its side of the mesh (shape frame): back across any
// triangle its path from `from` went through, then out of the triangles it overlaps, deepest
// first. A few passes: in a concave fold (a valley, a bowl's bottom) the push out of one face
// goes into the other, which separate shapes would each have pushed within the same call.
Vec3 meshPush(const TriangleMesh& mesh, const Vec3& from, const Vec3& p, double radius) {
    thread_local std::vector<std::uint32_t> near;
    const Vec3 reach = Vec3::Constant(radius);
    mesh.candidates(from.cwiseMin(p) - reach, from.cwiseMax(p) + reach, near);
    if (near.empty()) return Vec3::Zero();
    Vec3 q = backAcross(mesh, near, from, p, radius);
    for (int pass = 0; pass < 4; ++pass) {
        const Vec3 out = outOfTriangles(mesh, near, from, q, radius);
        if (out.isZero(0)) break;
        q += out;
    }
    return q - p;
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
        Vec3 centre = c.pose.position + c.pose.orientation * s.local.position;
        Vec3 reach = Vec3::Constant(boundingRadius(s));
        const Mat3 R = (c.pose.orientation * s.local.orientation).toRotationMatrix();
        if (s.type == ShapeType::Box) reach = R.cwiseAbs() * s.halfExtents;  // much tighter for long thin walls
        if (s.type == ShapeType::Mesh) {  // the box around its triangles, turned with it
            if (!s.mesh || s.mesh->triangles().empty()) continue;
            centre += R * (0.5 * (s.mesh->boundsMin() + s.mesh->boundsMax()));
            reach = R.cwiseAbs() * (0.5 * (s.mesh->boundsMax() - s.mesh->boundsMin()));
        }
        c.boundsMin = c.boundsMin.cwiseMin(centre - reach);
        c.boundsMax = c.boundsMax.cwiseMax(centre + reach);
    }
}

Vec3 colliderPush(const ParticleCollider& c, const Vec3& from, const Vec3& point, double radius) {
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
        if (s.type == ShapeType::Mesh) {  // its pose is the step's throughout: meshes are static
            if (!s.mesh) continue;
            const Vec3 local = meshPush(*s.mesh, q.conjugate() * (from - origin), q.conjugate() * (point - origin), radius);
            const double depth = local.norm();
            if (depth > deepest) {
                deepest = depth;
                push = q * local;
            }
            continue;
        }
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
