#pragma once
// The solver's two views of an awake body that has constraints this step, packed in arrays in
// the order the solver gathered them (Box2D v3 splits them the same way):
//  - SolverState: what the constraint stages read and write every pass (velocities, and the
//    motion since the step began, from which contact separations are updated). Small, hot.
//  - SolverBody: what stays fixed over the step (masses, inertia, forces, the step-start pose).
// Static and sleeping partners have no entry: constraints refer to them with kStaticBody and
// read a zero state.
#include <cstdint>

#include "anyphys/defs.hpp"

namespace anyphys::native {

inline constexpr std::int32_t kStaticBody = -1;

struct alignas(64) SolverState {
    // Laid out as runs of four doubles that the contact passes load whole, one per lane, and
    // transpose into the lanes' fields (state_runs.hpp): w[0..2] v[0] | v[1..2] turn | dp dq[0] |
    // dq[1..3] inBounce. A planar pass loads w[2] v[0..2] and turn dp[0..1].
    double w[3] = {0, 0, 0};               // rad/s, world frame
    double v[3] = {0, 0, 0};               // m/s, centre-of-mass velocity, world frame
    // Planar worlds: cos and sin of dq's turn about Z, kept with dq by integratePositions, so that
    // the contact passes read them rather than work them out per contact per pass.
    double turn[2] = {1, 0};
    double dp[3] = {0, 0, 0};              // m, displacement since the step began
    double dq[4] = {1, 0, 0, 0};           // rotation since the step began, (w, x, y, z): q = dq q0
    // The last run's fourth double, which the passes read and leave: 1 once the body takes part
    // in a bounce this step (the restitution stage then holds its resting contacts too).
    double inBounce = 0;
};
static_assert(sizeof(SolverState) == 16 * sizeof(double), "SolverState is four runs of four doubles");

struct SolverBody {
    // First, what integrateVelocities reads every substep (80 bytes: two cache lines at most,
    // where spread over the record it touched four of five; at 50 000 bodies the records no
    // longer fit in cache and the stage waited on them).
    std::uint32_t body = 0;                // index in NativeWorld::bodies()
    bool dynamic = false;                  // kinematic bodies keep their velocity
    bool jointed = false;                  // an enabled joint holds it this step (contact_solve.cpp's sweeps)
    bool contacted = false;                // a contact row acts on it this step (joint_solver.cpp's load)
    GyroscopicMode gyroscopic = GyroscopicMode::None;  // None unless the effect applies to this body
    Vec3 linearAcceleration = Vec3::Zero();  // gravity and user force, constant over the step
    Vec3 angularAcceleration = Vec3::Zero(); // user torque, world frame
    double linearHalfDampingFactor = 1.0;  // velocity factor per half substep, exp(-c h / 2)
    double angularHalfDampingFactor = 1.0;
    // The rest: read by the prepare stages, the gyroscopic term, restitution and the finish.
    Vec3 invMass = Vec3::Zero();           // per world axis (zero along Z in a planar world)
    Mat3 invInertia = Mat3::Zero();        // world frame, at the step start
    Vec3 inertia = Vec3::Zero();           // principal moments (gyroscopic term)
    Vec3 position0 = Vec3::Zero();         // centre of mass at the step start
    Quat orientation0 = Quat::Identity();  // at the step start
    Vec3 bounceAcceleration = Vec3::Zero();  // linearAcceleration if it fell freely last step, else 0 (restitution)
};

/// Whether an enabled joint holds solver body `index` this step (a static body: never).
inline bool heldByJoint(const SolverBody* bodies, std::int32_t index) {
    return index != kStaticBody && bodies[index].jointed;
}

}  // namespace anyphys::native
