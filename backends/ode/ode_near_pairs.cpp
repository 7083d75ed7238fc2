#include "ode_near_pairs.hpp"

#include <cmath>

#include "ode_math.hpp"

namespace anyphys::ode {

NearProbe::~NearProbe() {
    for (dGeomID g : {box_, sphere_, capsule_, plane_})
        if (g) dGeomDestroy(g);
}

dGeomID NearProbe::grown(const OdeShape& shape, double reach) {
    const dGeomID g = shape.geom();
    dGeomID probe = nullptr;
    switch (shape.type()) {
        case ShapeType::Box: {
            dVector3 lengths;
            dGeomBoxGetLengths(g, lengths);
            if (!box_) box_ = dCreateBox(nullptr, 1, 1, 1);
            // A box grown face by face: exact across a face, a little wide at edges and corners
            // (by up to sqrt(3) - 1 of the reach), which only matters for a pair meeting there.
            dGeomBoxSetLengths(box_, lengths[0] + 2 * reach, lengths[1] + 2 * reach, lengths[2] + 2 * reach);
            probe = box_;
            break;
        }
        case ShapeType::Sphere:
            if (!sphere_) sphere_ = dCreateSphere(nullptr, 1);
            dGeomSphereSetRadius(sphere_, dGeomSphereGetRadius(g) + reach);
            probe = sphere_;
            break;
        case ShapeType::Capsule: {
            dReal radius = 0, length = 0;
            dGeomCapsuleGetParams(g, &radius, &length);
            if (!capsule_) capsule_ = dCreateCapsule(nullptr, 1, 1);
            dGeomCapsuleSetParams(capsule_, radius + reach, length);
            probe = capsule_;
            break;
        }
        case ShapeType::Plane: {  // not placeable: its parameters are in the world frame
            dVector4 p;
            dGeomPlaneGetParams(g, p);
            if (!plane_) plane_ = dCreatePlane(nullptr, 0, 1, 0, 0);
            dGeomPlaneSetParams(plane_, p[0], p[1], p[2], p[3] + reach);
            return plane_;
        }
        default: return nullptr;
    }
    const dReal* position = dGeomGetPosition(g);
    dGeomSetPosition(probe, position[0], position[1], position[2]);
    dGeomSetRotation(probe, dGeomGetRotation(g));
    return probe;
}

int NearProbe::collide(const OdeShape& first, const OdeShape& second, double reach, dContactGeom* out, int most) {
    dGeomID a = grown(first, reach);
    dGeomID b = second.geom();
    if (!a) {
        a = first.geom();
        b = grown(second, reach);
        if (!b) return 0;
    }
    const int n = dCollide(a, b, most, out, sizeof(dContactGeom));
    int kept = 0;
    for (int k = 0; k < n; ++k) {
        dContactGeom c = out[k];
        if (!std::isfinite(c.depth + c.pos[0] + c.pos[1] + c.pos[2] + c.normal[0] + c.normal[1] + c.normal[2])) continue;
        c.depth -= reach;
        out[kept++] = c;
    }
    return kept;
}

bool NearProbe::meetsAfter(const OdeShape& moving, const Vec3& pivot, const Vec3& move, const Quat& turn,
                           const OdeShape& other, double reach) {
    if (moving.type() == ShapeType::Plane) return false;  // never moves
    const dGeomID probe = grown(moving, reach);
    if (!probe) return false;
    const Vec3 at = pivot + move + turn * (toVec3(dGeomGetPosition(probe)) - pivot);
    dMatrix3 axes;
    toOde(turn.toRotationMatrix() * toMat3(dGeomGetRotation(probe)), axes);
    dGeomSetPosition(probe, at.x(), at.y(), at.z());
    dGeomSetRotation(probe, axes);
    dContactGeom contact;
    return dCollide(probe, other.geom(), 1, &contact, sizeof(dContactGeom)) > 0;
}

}  // namespace anyphys::ode
