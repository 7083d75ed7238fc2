#pragma once
// What the backend's own ODE colliders (dColliderFn, installed with dSetColliderOverride) share:
// the room ODE gives them and the way each contact is written, in ODE's conventions.
#include <ode/ode.h>

#include "ode_math.hpp"

namespace anyphys::ode {

/// The room for contacts a collider is given: the low bits of `flags` (ODE's NUMC_MASK).
inline int contactRoom(int flags) { return flags & 0xffff; }

/// Contact c of a collider's output, whose entries lie `skip` bytes apart.
inline dContactGeom& contactAt(dContactGeom* contact, int c, int skip) {
    return *reinterpret_cast<dContactGeom*>(reinterpret_cast<char*>(contact) + c * skip);
}

/// One contact between o1 and o2: `normal` points into o1 (moving o1 along it by `depth` parts
/// them), no sub-shape sides.
inline void writeContact(dContactGeom& out, const Vec3& point, const Vec3& normal, double depth, dGeomID o1,
                         dGeomID o2) {
    for (int k = 0; k < 3; ++k) {
        out.pos[k] = point[k];
        out.normal[k] = normal[k];
    }
    out.pos[3] = out.normal[3] = 0.0;
    out.depth = depth;
    out.g1 = o1;
    out.g2 = o2;
    out.side1 = out.side2 = -1;
}

}  // namespace anyphys::ode
