#pragma once
// ODE's collider for a box against a plane, replaced so a resting face keeps all its corners.
// ODE's own reports only corners at or below the plane. A box resting on the ground sits at depth
// 0 give or take the solver's rounding, so each step some corners lie a micrometre above it and
// drop out: a 100 kg box rested on three corners, then on one, in the step a ball landed on it,
// tipped and sank 4.5 mm at 0.13 m/s, and the ball rose 80 % of its share.
#include <ode/ode.h>

namespace anyphys::ode {

/// Corners this close above the plane still touch it, at depth 0 (m). ODE holds such a corner
/// from closing, so a box may rest this high; the solver's rounding lifted corners by up to
/// 1.1e-6 m in that step. ODE calls the collider only while the bounds meet (an axis-aligned
/// plane's end at its surface), so a box with every corner above the plane is not held.
inline constexpr double kBoxPlaneReach = 1e-5;

/// An ODE collider (dColliderFn) for o1 a box and o2 a plane: the corners within kBoxPlaneReach
/// of the plane or below it, the deepest first, at most four and at most the room in `flags`.
/// ODE's conventions: the normal is the plane's (into o1), depths are positive, and a
/// hovering corner has depth 0.
int collideBoxPlane(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip);

}  // namespace anyphys::ode
