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

/// The same collider for o1 a box (any box geom: its hull is made from its lengths). ODE's own
/// box-capsule gives one pair of nearest points, one end of a capsule lying on a face, and the
/// twin-tilting completion (ode_contact_completion.hpp) added the other end with the right depth
/// but at a point carried back from the tilted twin, about half the tilt's travel off the overlap
/// along the normal (1.2 mm above the face while 1.2 mm deep; ODE's point at the other end 1.4 mm
/// below it). The two ends then rolled on radii 2.6 mm apart, like a cone: a capsule rolling across
/// a 30 deg box slope yawed, left its line by 10 cm in 2 s and rolled 1.2 % slow. (Verified: the
/// completion with that point moved to the middle of its overlap left 2 mm, as on a plane.)
int collideBoxCapsule(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip);

}  // namespace anyphys::ode
