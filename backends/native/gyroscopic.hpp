#pragma once
// The gyroscopic term of Euler's rigid-body equations, I dw/dt = tau - w x (I w), body frame.
#include "anyphys/math.hpp"

namespace anyphys::native {

/// Explicit term: the angular acceleration -I^-1 (w x I w) in the world frame, for world-frame w,
/// principal moments `inertia` and orientation q.
Vec3 gyroscopicAcceleration(const Vec3& worldOmega, const Quat& q, const Vec3& inertia);

/// Implicit (backward Euler) update of torque-free rotation over h: solves
///   I (w1 - w0) + h w1 x (I w1) = 0   in the body frame by Newton's method,
/// and returns w1 in the world frame. Unconditionally stable; the angular momentum magnitude
/// is kept closely and kinetic energy never grows.
Vec3 solveImplicitGyroscopic(const Vec3& worldOmega, const Quat& q, const Vec3& inertia, double h);

}  // namespace anyphys::native
