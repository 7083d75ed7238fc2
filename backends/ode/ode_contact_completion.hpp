#pragma once
// ODE 0.16 (Debian's, whose hull pairs go through libccd's MPR) gives one contact point for a hull
// against a box or a hull (a capsule against a hull or a box is the backend's own collider,
// ode_convex_capsule.hpp, with two where it lies on a face; one where it leans off it, which
// this still completes): a face resting on a face is
// then held at one corner per step and rocks from corner to corner for ever (a unit cube hull on
// a box: its corners at 0.5 m/s after 2 s, 1.2 cm deep; a 2 m one 1.8 cm deep). The backend completes such a manifold
// with ODE's own collider: it tilts a twin of the moving geom slightly about axes across the
// normal, collides the twin, and carries each new deepest point back onto the untilted geom.
// The cube hull then rests like a box (2.7 mm/s, 1.2 mm deep; ShapePairsTest).
#include <ode/ode.h>

#include "ode_shapes.hpp"

namespace anyphys::ode {

/// With `contacts[0]` ODE's one contact of geom 1 (`first`) against geom 2 (`second`): where one
/// of the two can rest a face or a straight side on a face of the other and ODE's collider gives
/// one point for such a pair, adds the points found by colliding that shape's twin at poses
/// tilted about axes across the normal. Only where the normal is a face normal of the other
/// shape: the depth of a point carried back is measured to that face's plane. Returns the new
/// count, at most `capacity`; the contacts keep ODE's orientation (normal into geom 1).
int completeOnePointContact(const OdeShape& first, const OdeShape& second, dContact* contacts, int capacity);

}  // namespace anyphys::ode
