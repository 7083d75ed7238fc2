#pragma once
// The solver's integration of its bodies within a substep (semi-implicit Euler, as every
// sequential-impulse solver): velocities first (forces, gyroscopic term, damping), then
// positions from the new velocities. Each works on a range of solver bodies, so workers can
// share the bodies out.
#include "solver/solver_body.hpp"

namespace anyphys::native {

/// v += h a, w += h alpha, gyroscopic term, damping (exact factor exp(-c h), half before and half
/// after the forces). Dynamic bodies only.
void integrateVelocities(const SolverBody* bodies, SolverState* states, int begin, int end, double h);
/// dp += h v; dq = exp(h w / 2) dq, and turn from dq. Dynamic and kinematic bodies.
void integratePositions(SolverState* states, int begin, int end, double h);
/// Moves a body by `move` and turns it by the rotation vector `turn` (dp, dq and turn kept
/// together): integratePositions' update, and the joint position pass's (joint_solver.hpp).
void displaceBody(SolverState& s, const Vec3& move, const Vec3& turn);

/// Rotation by the rotation vector r (angle |r| about r / |r|), exact for every angle.
Quat rotationFromVector(const Vec3& r);
/// q scaled back to unit length: cheap for a quaternion already unit to rounding (a product of
/// unit quaternions), exact normalisation otherwise.
Quat renormalized(const Quat& q);

}  // namespace anyphys::native
