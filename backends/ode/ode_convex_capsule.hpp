#pragma once
// ODE's collider for a hull against a capsule, replaced. Debian's ODE 0.16 collides the pair with
// libccd's MPR, whose portal refinement has no iteration bound (the API fuzzer found it looping
// for ever on a hull reaching 1e7 m against a 5 cm capsule), and ODE's own non-libccd version
// of the pair returns no contacts. A capsule is a segment with a radius, so its contacts come
// from the segment against the hull's faces and edges, in walks bounded by their counts.
#include <ode/ode.h>

namespace anyphys::ode {

/// An ODE collider (dColliderFn) for o1 a convex geom made by an OdeShape and o2 a capsule: up
/// to two contacts (a capsule lying on a face touches it along a stretch), with ODE's
/// conventions (the normal points into o1, so moving o1 along it by `depth` parts them).
int collideConvexCapsule(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip);

}  // namespace anyphys::ode
