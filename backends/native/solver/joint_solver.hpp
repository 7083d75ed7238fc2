#pragma once
// Joint constraints in the native solver, in the same stages as contacts (joints are solved
// first in each pass, so contacts have the last word). Each pass rebuilds a joint's rows from the
// bodies' current poses (the step-start pose moved by the solver's displacement and rotation),
// so position errors are always current; impulses accumulate per row and warm start the next
// substep and step. Soft step: rigid rows correct their position error softly in the solve pass
// and hold velocity exactly in the relax pass. PGS: the velocity passes hold velocity only, and a
// position pass after the positions move takes back the settings.baumgarte share of each rigid
// row's and violated limit's error by moving the bodies (Box2D v2's nonlinear Gauss-Seidel), so no
// correction is left in the velocity or in the impulses that warm start the next substep. PGS's
// relax passes (after the position pass) make the velocities consistent at the pose the next
// substep starts from; the next warm start applies what the solve passes left, without what the
// relax passes added (applied again on top, a fast 40-link chain gained 3 800 J at 8 relax passes).
//
// The rows of a joint (anchor point, rotation and sliding locks, limits, spring, motor) are solved
// together as one small block, the spring and the motor each with its own law. A motor on a
// locked axis (limits of zero width) goes row by row before the block.
// Rows by type (joints.hpp has the impulse slots):
//   ball      anchor point (3 rows)
//   hinge     anchor point, 2 rotation locks across the axis, limit / motor / spring on the angle
//   slider    3 rotation locks (a block), 2 sliding locks across the axis, limit / motor / spring
//   fixed     anchor point and 3 rotation locks
//   cone      anchor point, swing limit (the cone), twist limits
//   distance  length: rigid, or min / max limits, or a spring (with optional min / max)
//   wheel     2 sliding locks across the suspension, 2 rotation locks about the (steered) axle,
//             suspension limit and spring, drive motor on the spin
// Motors clamp their impulse to maxForce x substep. Springs damp implicitly; their stiffness is
// explicit where the substep resolves the spring and implicit beyond (springRow); SI units.
#include <cstdint>
#include <limits>

#include "joints.hpp"
#include "solver/contact_constraint.hpp"
#include "solver/solver_body.hpp"

namespace anyphys::native {

/// A joint as the solver sees it this step.
struct JointConstraint {
    NativeJoint* joint = nullptr;
    std::int32_t a = kStaticBody, b = kStaticBody;  // solver bodies, or kStaticBody
    Transform fixedA, fixedB;  // pose of a side that is not a solver body (world: identity)
    int springsOnBusierBody = 1;  // the most sprung joints on either body (at least 1)
};

struct JointSolveParams {
    double h = 0.0;             // s, substep
    double invH = 0.0;
    bool soft = true;           // soft step; false: PGS
    Softness softness;          // rigid rows' position correction (soft step)
    // Soft step: the fastest an anchor's position error is closed (m/s); see anchorBiasScale.
    double anchorPushMaxVelocity = std::numeric_limits<double>::infinity();
    double baumgarte = 0.0;     // PGS: the share of a position error one position pass takes back
};

/// Applies each row's accumulated impulse (start of a substep); on PGS, the impulses as the last
/// substep's solve passes left them (NativeJoint::solvedImpulse), where its position pass kept them.
void warmStartJoint(const JointConstraint& c, const SolverBody* bodies, SolverState* states, const JointSolveParams& p);
/// One Gauss-Seidel pass over the joint's rows. `endOfSubstep`: the impulses now in the rows are
/// this substep's total and add to the step's reactions.
void solveJoint(const JointConstraint& c, const SolverBody* bodies, SolverState* states, const JointSolveParams& p,
                bool useBias, bool endOfSubstep);
/// PGS: one pass over the joint's rigid rows and violated limits on positions, moving the bodies
/// (dp, dq) by baumgarte times the error, with the substep's inverse masses. Motors and springs
/// act on velocity only; no impulse changes. Keeps the impulses as they are (the solve passes'
/// total) for the next substep's warm start.
void correctJointPosition(const JointConstraint& c, const SolverBody* bodies, SolverState* states,
                          const JointSolveParams& p);
/// After the step: the reactions (step sums / dt) and the joint's position and speed from the
/// bodies' final poses and velocities.
void reportJoint(const JointConstraint& c, const SolverBody* bodies, const SolverState* states, double dt);

}  // namespace anyphys::native
