#include "ode_convex_sphere.hpp"

#include <cmath>
#include <limits>

#include "ode_collider_output.hpp"
#include "ode_hull_geometry.hpp"
#include "ode_math.hpp"
#include "ode_shapes.hpp"

namespace anyphys::ode {

int collideConvexSphere(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int /*skip: one contact*/) {
    const OdeShape* shape = shapeOfGeom(o1);
    if (contactRoom(flags) == 0 || !shape || !shape->hull()) return 0;
    const HullData& hull = *shape->hull();
    const Vec3 origin = toVec3(dGeomGetPosition(o1));
    const Mat3 rotation = toMat3(dGeomGetRotation(o1));
    const double radius = dGeomSphereGetRadius(o2);
    const Vec3 centre = rotation.transpose() * (toVec3(dGeomGetPosition(o2)) - origin);  // hull frame
    // The face the centre is farthest in front of (or, inside, least deep behind).
    std::size_t face = 0;
    double height = -std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < hull.faces.size(); ++f)
        if (const double h = hull.faceNormals[f].dot(centre) - hull.faceOffsets[f]; h > height) {
            height = h;
            face = f;
        }
    if (!(height <= radius)) return 0;  // apart (and a NaN centre is never a contact)
    Vec3 surface, outward;  // hull frame: the hull's nearest surface point, the way to the sphere
    double distance;        // signed: negative with the centre inside
    if (height <= 0.0) {
        outward = hull.faceNormals[face];
        surface = centre - height * outward;
        distance = height;
    } else {
        surface = nearestOnSurface(hull, centre);
        distance = (centre - surface).norm();
        if (distance > radius) return 0;
        outward = distance > 0.0 ? Vec3((centre - surface) / distance) : hull.faceNormals[face];
    }
    const double depth = radius - distance;
    // Midway between the hull's surface and the sphere's deepest point, as ODE's own colliders.
    const Vec3 point = origin + rotation * (surface + 0.5 * (distance - radius) * outward);
    const Vec3 normal = -(rotation * outward);  // into o1: moving the hull along it parts them
    writeContact(*contact, point, normal, depth, o1, o2);
    return 1;
}

}  // namespace anyphys::ode
