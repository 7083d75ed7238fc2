// collide(): places both shapes in the world and dispatches to the pair routine, with the pair
// ordered sphere < capsule < box < convex < plane < mesh; a swapped pair gets its normals flipped
// back so they always point from a to b.
#include "collision/collide.hpp"

#include "collision/narrow_phase.hpp"

namespace anyphys::native {
namespace {

int rank(ShapeType t) {
    switch (t) {
        case ShapeType::Sphere: return 0;
        case ShapeType::Capsule: return 1;
        case ShapeType::Box: return 2;
        case ShapeType::Convex: return 3;
        case ShapeType::Plane: return 4;
        case ShapeType::Mesh: return 5;
        case ShapeType::Compound: return 6;
    }
    return 6;
}

SphereGeom sphereOf(const Shape& s, const Transform& xf) { return {xf.position, s.radius}; }

CapsuleGeom capsuleOf(const Shape& s, const Transform& xf) {
    const Vec3 axis = xf.orientation * Vec3(0, s.halfHeight, 0);
    return {xf.position - axis, xf.position + axis, s.radius};
}

BoxGeom boxOf(const Shape& s, const Transform& xf) { return {xf.position, xf.orientation.toRotationMatrix(), s.halfExtents}; }

PlaneGeom planeOf(const Shape& s) { return {s.normal.normalized(), s.offset}; }

Polytope polytopeOf(const Shape& s, const Transform& xf) {
    return s.type == ShapeType::Box ? makeBoxPolytope(s.halfExtents, xf) : makeHullPolytope(*s.hull, xf);
}

// The points a plane sees: sphere centre, capsule ends, polyhedron vertices.
std::vector<Vec3> planeProbes(const Shape& s, const Transform& xf) {
    switch (s.type) {
        case ShapeType::Sphere: return {xf.position};
        case ShapeType::Capsule: {
            const CapsuleGeom c = capsuleOf(s, xf);
            return {c.p0, c.p1};
        }
        case ShapeType::Box: {
            const Mat3 r = xf.orientation.toRotationMatrix();
            std::vector<Vec3> corners;
            corners.reserve(8);
            for (int i = 0; i < 8; ++i)
                corners.push_back(xf.position + r * s.halfExtents.cwiseProduct(Vec3((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1)));
            return corners;
        }
        case ShapeType::Convex: return polytopeOf(s, xf).vertices;
        default: return {};
    }
}

// a ranks no higher than b.
void collideOrdered(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculative,
                    std::vector<Manifold>& out) {
    if (b.type == ShapeType::Mesh) {
        if (a.type != ShapeType::Plane && a.type != ShapeType::Mesh) collideConvexMesh(a, xfA, b, xfB, speculative, out);
        return;
    }
    Manifold m;
    bool hit = false;
    if (b.type == ShapeType::Plane) {
        if (a.type == ShapeType::Plane) return;
        const double radius = (a.type == ShapeType::Sphere || a.type == ShapeType::Capsule) ? a.radius : 0.0;
        hit = collidePointsPlane(planeProbes(a, xfA), radius, planeOf(b), speculative, m);
    } else if (a.type == ShapeType::Sphere) {
        const SphereGeom s = sphereOf(a, xfA);
        switch (b.type) {
            case ShapeType::Sphere: hit = collideSpheres(s, sphereOf(b, xfB), speculative, m); break;
            case ShapeType::Capsule: hit = collideSphereCapsule(s, capsuleOf(b, xfB), speculative, m); break;
            case ShapeType::Box: hit = collideSphereBox(s, boxOf(b, xfB), speculative, m); break;
            case ShapeType::Convex: hit = collideSpherePolytope(s, polytopeOf(b, xfB), speculative, m); break;
            default: break;
        }
    } else if (a.type == ShapeType::Capsule) {
        const CapsuleGeom c = capsuleOf(a, xfA);
        if (b.type == ShapeType::Capsule) hit = collideCapsules(c, capsuleOf(b, xfB), speculative, m);
        else if (b.type == ShapeType::Box || b.type == ShapeType::Convex)
            hit = collideCapsulePolytope(c, polytopeOf(b, xfB), speculative, m);
    } else if (a.type == ShapeType::Box && b.type == ShapeType::Box) {
        hit = collideBoxes(boxOf(a, xfA), boxOf(b, xfB), speculative, m);
    } else if ((a.type == ShapeType::Box || a.type == ShapeType::Convex) && b.type == ShapeType::Convex) {
        hit = collidePolytopes(polytopeOf(a, xfA), polytopeOf(b, xfB), speculative, m);
    }
    if (hit) out.push_back(m);
}

}  // namespace

void collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculativeDistance,
             std::vector<Manifold>& out) {
    if (rank(a.type) <= rank(b.type)) {
        collideOrdered(a, xfA, b, xfB, speculativeDistance, out);
        return;
    }
    const std::size_t first = out.size();
    collideOrdered(b, xfB, a, xfA, speculativeDistance, out);
    for (std::size_t i = first; i < out.size(); ++i) out[i].normal = -out[i].normal;
}

}  // namespace anyphys::native
