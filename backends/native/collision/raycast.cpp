// Ray casts (raycast): each shape in its own frame, the result placed back in the world.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "collision/mesh_data.hpp"
#include "collision/query_helpers.hpp"

namespace anyphys::native {
namespace {

// Each routine works in the shape's local frame (dir unit); results are local too.

std::optional<RayHit> raySphere(const Vec3& center, double radius, const Vec3& o, const Vec3& d, double maxT) {
    const Vec3 m = o - center;
    const double b = m.dot(d);
    const double c = m.squaredNorm() - radius * radius;
    if (c < 0.0 || b > 0.0) return std::nullopt;  // starts inside, or outside and leaving
    const double disc = b * b - c;
    if (disc < 0.0) return std::nullopt;
    const double t = std::max(0.0, -b - std::sqrt(disc));
    if (t > maxT) return std::nullopt;
    RayHit hit;
    hit.distance = t;
    hit.point = o + t * d;
    hit.normal = (hit.point - center) / radius;
    return hit;
}

double segmentPointDistance(const Vec3& a, const Vec3& b, const Vec3& p) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

// The capsule is the union of a cylinder and two end spheres: its first hit is the earliest of
// theirs (the origin is outside all of them), the cylinder counting only within the segment.
std::optional<RayHit> rayCapsule(double r, double h, const Vec3& o, const Vec3& d, double maxT) {
    const Vec3 top(0, h, 0);
    const Vec3 bottom(0, -h, 0);
    if (segmentPointDistance(bottom, top, o) < r) return std::nullopt;
    std::optional<RayHit> best;
    auto consider = [&](const std::optional<RayHit>& hit) {
        if (hit && (!best || hit->distance < best->distance)) best = hit;
    };
    const double a = d.x() * d.x() + d.z() * d.z();
    if (a > 1e-300) {
        const double b = o.x() * d.x() + o.z() * d.z();
        const double c = o.x() * o.x() + o.z() * o.z() - r * r;
        const double disc = b * b - a * c;
        if (disc >= 0.0) {
            const double t = std::max(0.0, (-b - std::sqrt(disc)) / a);
            const Vec3 p = o + t * d;
            if (t <= maxT && std::abs(p.y()) <= h && b <= 0.0) {
                RayHit hit;
                hit.distance = t;
                hit.point = p;
                hit.normal = Vec3(p.x(), 0.0, p.z()) / r;
                consider(hit);
            }
        }
    }
    consider(raySphere(top, r, o, d, maxT));
    consider(raySphere(bottom, r, o, d, maxT));
    return best;
}

// Slab test; the entering slab gives the normal.
std::optional<RayHit> rayBox(const Vec3& half, const Vec3& o, const Vec3& d, double maxT) {
    double tEnter = -kInf;
    double tExit = kInf;
    Vec3 normal = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
        if (std::abs(d[i]) < 1e-300) {
            if (o[i] < -half[i] || o[i] > half[i]) return std::nullopt;
            continue;
        }
        const double t1 = (-half[i] - o[i]) / d[i];
        const double t2 = (half[i] - o[i]) / d[i];
        const double tNear = std::min(t1, t2);
        if (tNear > tEnter) {
            tEnter = tNear;
            normal = Vec3::Zero();
            normal[i] = d[i] > 0.0 ? -1.0 : 1.0;
        }
        tExit = std::min(tExit, std::max(t1, t2));
        if (tEnter > tExit) return std::nullopt;
    }
    // tEnter < 0: the origin is inside (or the box is behind it).
    if (tEnter < 0.0 || tEnter > maxT) return std::nullopt;
    return RayHit{tEnter, o + tEnter * d, normal};
}

// Clip the ray by every face plane n.x <= offset; the last plane entered gives the normal.
std::optional<RayHit> rayHull(const HullData& hull, const Vec3& o, const Vec3& d, double maxT) {
    double tEnter = -kInf;
    double tExit = kInf;
    Vec3 normal = Vec3::Zero();
    for (std::size_t f = 0; f < hull.faceNormals.size(); ++f) {
        const Vec3& n = hull.faceNormals[f];
        const double numer = hull.faceOffsets[f] - n.dot(o);  // > 0: origin inside this plane
        const double denom = n.dot(d);
        if (denom == 0.0) {
            if (numer < 0.0) return std::nullopt;
            continue;
        }
        const double t = numer / denom;
        if (denom < 0.0) {
            if (t > tEnter) {
                tEnter = t;
                normal = n;
            }
        } else {
            tExit = std::min(tExit, t);
        }
        if (tEnter > tExit) return std::nullopt;
    }
    if (tEnter < 0.0 || tEnter > maxT) return std::nullopt;
    return RayHit{tEnter, o + tEnter * d, normal};
}

// Möller-Trumbore, two-sided (a mesh is a surface).
std::optional<double> rayTriangle(const std::array<Vec3, 3>& v, const Vec3& o, const Vec3& d, double maxT) {
    const Vec3 e1 = v[1] - v[0];
    const Vec3 e2 = v[2] - v[0];
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-14 * e1.norm() * e2.norm()) return std::nullopt;  // parallel
    const double inv = 1.0 / det;
    const Vec3 s = o - v[0];
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) return std::nullopt;
    const Vec3 q = s.cross(e1);
    const double w = d.dot(q) * inv;
    if (w < 0.0 || u + w > 1.0) return std::nullopt;
    const double t = e2.dot(q) * inv;
    if (t < 0.0 || t > maxT) return std::nullopt;
    return t;
}

std::optional<RayHit> rayMesh(const MeshData& mesh, const Vec3& o, const Vec3& d, double maxT) {
    std::optional<RayHit> best;
    mesh.rayCastTriangles(o, d, maxT, [&](int tri, double clip) {
        const auto t = rayTriangle(mesh.triangleVertices(tri), o, d, clip);
        if (!t) return clip;
        const Vec3& n = mesh.normals[static_cast<std::size_t>(tri)];
        best = RayHit{*t, o + *t * d, n.dot(d) > 0.0 ? Vec3(-n) : n};
        return *t > 0.0 ? *t : 0.0;  // a hit at 0 cannot be beaten: stop
    });
    return best;
}

}  // namespace

std::optional<RayHit> raycast(const Shape& s, const Transform& xf, const Vec3& origin, const Vec3& dir, double maxDistance) {
    if (s.type == ShapeType::Plane) {  // world frame
        const double height = s.normal.dot(origin) - s.offset;
        const double denom = s.normal.dot(dir);
        if (height < 0.0 || denom >= 0.0) return std::nullopt;  // inside, or not heading down to it
        const double t = -height / denom;
        if (t > maxDistance) return std::nullopt;
        return RayHit{t, origin + t * dir, s.normal};
    }
    const Quat qInv = xf.orientation.conjugate();
    const Vec3 o = qInv * (origin - xf.position);
    const Vec3 d = qInv * dir;
    std::optional<RayHit> hit;
    switch (s.type) {
        case ShapeType::Sphere: hit = raySphere(Vec3::Zero(), s.radius, o, d, maxDistance); break;
        case ShapeType::Capsule: hit = rayCapsule(s.radius, s.halfHeight, o, d, maxDistance); break;
        case ShapeType::Box: hit = rayBox(s.halfExtents, o, d, maxDistance); break;
        case ShapeType::Convex: hit = rayHull(*s.hull, o, d, maxDistance); break;
        case ShapeType::Mesh: hit = rayMesh(*s.mesh, o, d, maxDistance); break;
        default: break;
    }
    if (hit) {
        hit->point = apply(xf, hit->point);
        hit->normal = xf.orientation * hit->normal;
    }
    return hit;
}

}  // namespace anyphys::native
