#pragma once
// ODE's collider for a hull against a sphere, replaced. Debian's ODE 0.16 collides the pair with
// libccd's MPR, whose portal refinement has no iteration bound: the API fuzzer found it looping
// for ever on a hull reaching 1e7 m against a 5 cm sphere. The hull is a polytope the layer
// already describes by its faces, so the sphere's contact is found exactly, in a bounded walk
// over them.
#include <ode/ode.h>

namespace anyphys::ode {

/// An ODE collider (dColliderFn) for o1 a convex geom made by an OdeShape and o2 a sphere: at
/// most one contact, the deepest point, with ODE's conventions (the normal points into o1, so
/// moving o1 along it by `depth` parts them).
int collideConvexSphere(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip);

}  // namespace anyphys::ode
