#pragma once
// Friction directions of ODE's Approx1 contacts, which bench/direct/ode_scenes.cpp runs too (it
// changes the physics, so raw ODE must do it for both sides to simulate the same pile).
#include <ode/ode.h>

#include "anyphys/math.hpp"

namespace anyphys::ode {

/// Approx1 bounds each of its two tangent directions by mu N on its own: a pyramid, not a cone.
/// With ODE's directions (chosen from the normal alone) a box sliding diagonally feels up to
/// sqrt(2) mu N and a slope tilted diagonally holds a box it should release. Setting the first
/// direction along the slip the step would produce makes the bound on the slip exactly mu N, in
/// any direction. `relativeVelocity`: geom 1's body's velocity at the contact point minus geom
/// 2's, as the step would leave them without the contact (velocity plus what gravity adds over
/// the ODE step). A slip slower than kSlipDirectionSpeed keeps ODE's directions.
void alignFrictionWithSlip(dContact& contact, const Vec3& relativeVelocity);

/// The velocity of `body`'s point at `point` now; a null body (static geom) does not move.
inline Vec3 pointVelocity(dBodyID body, const Vec3& point) {
    if (!body) return Vec3::Zero();
    dVector3 v;
    dBodyGetPointVel(body, point.x(), point.y(), point.z(), v);
    return Vec3(v[0], v[1], v[2]);
}

/// The velocity of `body`'s point at `point` at the end of an ODE step of `h` without contacts:
/// its velocity plus `gravity` x h (pass zero for a body gravity does not move). A null body
/// (static geom) does not move.
inline Vec3 predictedPointVelocity(dBodyID body, const Vec3& point, const Vec3& gravity, double h) {
    if (!body) return Vec3::Zero();
    return pointVelocity(body, point) + gravity * h;
}

}  // namespace anyphys::ode
