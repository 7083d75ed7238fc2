#pragma once
// Defaults of the ODE backend that are not WorldSettings fields. bench/direct/ode_scenes.cpp
// repeats them to drive raw ODE exactly like the backend does: change both together.

#include <algorithm>

namespace anyphys::ode {

/// Used when WorldSettings leaves them unset. 50 quickstep iterations (ODE's own default is 20):
/// measured on box_stack_10 over five random-reorder seeds, 20 let the top box wander 1.3 to
/// 10 cm before the stack sleeps, 50 keeps it within 4.3 mm. One ODE step per anyphys step
/// (substeps step the whole world, free bodies included).
constexpr int kDefaultIterations = 50;
constexpr int kDefaultSubsteps = 1;

/// Contact points kept per geom pair (dCollide's limit). Four carry a box face on a face
/// (ODE culls box-box manifolds to the most spread-out points).
constexpr int kMaxContactsPerPair = 4;

// m/s: below this predicted slip a contact keeps ODE's own friction directions (a resting
// contact's slip is rounding noise, whose direction means nothing).
constexpr double kSlipDirectionSpeed = 1e-6;

/// Constraint force mixing (contact softness) of resting contacts. ODE's CFM is absolute, not
/// per unit mass: 1e-5 (ODE's demos, bodies of about 1 kg) lets the layer's 1000 kg boxes sink
/// centimetres; ODE's double default 1e-10 is so rigid that quickstep jitters and stacks walk.
/// 1e-6 measured best on box_stack_10 and pyramid_20. Overridden by backendOptions["cfm"].
constexpr double kDefaultCfm = 1e-6;

/// kg: the pair mass up to which contacts and joint rows take the world's CFM as it is. ODE's
/// CFM is a compliance, so one value for every pair makes a heavy pair's rows softer in
/// proportion to its mass: a ten-box stack of 100 t boxes sank 9.2 m into the ground over 10 s at
/// 1e-6, and a 1e7 kg pendulum bob stretched its hinge 4.27 m. A heavier pair's CFM is divided by
/// its mass in units of this one, which keeps its rows' frequency and damping ratio those of a
/// pair of 1 t, the mass kDefaultCfm was tuned on; lighter pairs keep the world's CFM (made
/// softer, as a rule relative at every mass would make them, fast 1 kg spheres went through thin
/// walls in three contract cases). No pair of the benchmark scenes is heavier, so
/// bench/direct/ode_scenes.cpp does not repeat the rule.
constexpr double kCfmReferenceMass = 1000.0;

/// The CFM of rows holding a pair whose heavier dynamic body weighs `pairMass` kg, for a world
/// CFM of `cfm` (kCfmReferenceMass).
inline double pairCfm(double cfm, double pairMass) {
    return pairMass > kCfmReferenceMass ? cfm * (kCfmReferenceMass / pairMass) : cfm;
}

/// The least CFM a constraint row gets, as a fraction of its weight J M^-1 J^T times the step
/// (ODE adds CFM / h to the row's diagonal): enough that dWorldStep's LCP never meets a pivot
/// that rounding made zero, far too little to soften anything. ODE's CFM is absolute and the mass
/// rule above keeps the world's below 1 t, so a 1e-15 kg box resting on the ground had rows of
/// weight 1e15 regularised by 1e-21 of it: the LCP failed and ODE aborted the process
/// (dxLDLTRemove's assertion; at 1e-20 kg, a non-finite rotation). At 60 Hz the floor passes
/// the default CFM only for bodies under about 1e-7 kg (kBounceCfm: under about 1 g), and
/// there adds 1e-12 of a row's weight, nothing measurable. No body of the benchmark scenes is
/// that light, so bench/direct/ode_scenes.cpp does not repeat it. Measured on a 0.1 m box
/// resting on the ground: 1e-14 is enough from 1e-25 to 1e-12 kg; 1e-12 leaves a factor 100.
constexpr double kCfmConditioningFloor = 1e-12;

/// `cfm`, raised where needed to the floor (kCfmConditioningFloor) for rows of weight at most
/// `rowWeight` (OdeBody::rowWeightBound of both bodies) over an ODE step of h seconds.
inline double conditionedCfm(double cfm, double h, double rowWeight) {
    return std::max(cfm, kCfmConditioningFloor * h * rowWeight);
}

/// CFM of contacts that bounce (restitution above the threshold): ODE's rigid default. A soft
/// contact acts as a damped spring and absorbs part of the rebound ODE's bounce asks for
/// (1e-6 loses 10 % of a 523 kg ball's rebound speed).
constexpr double kBounceCfm = 1e-10;

/// Successive over-relaxation of quickstep (ODE's default 1.3; 1.0 measured no better).
constexpr double kQuickStepW = 1.3;

/// Error reduction of the joints' own rows where ODE lets a joint have its own (ball, fixed,
/// double ball, and the AMotor rows that keep a hinge's axes aligned), instead of the world's
/// 0.2. A joint pulled back only a fifth of its drift per step lags behind a fast swing, and the
/// lag costs energy: a 1 m pendulum released at 2 rad, one step of 1/60 s, ran 9.6 % fast (pgs)
/// at 0.2, 2.5 % at 0.5, 1.0 % at 0.8, 0.7 % at 1 (measured). 0.8 keeps a margin below 1.
constexpr double kJointErp = 0.8;

/// Hash-space cell levels: cells from 2^-3 to 2^10 m (ODE's defaults), covering centimetre to
/// kilometre shapes.
constexpr int kHashMinLevel = -3;
constexpr int kHashMaxLevel = 10;

}  // namespace anyphys::ode

namespace anyphys::ode {

/// ODE's contact surface layer (depth allowed without correction, so resting contacts persist
/// instead of flickering) as a fraction of settings.linearSlop. A fifth of the slop: resting contacts settle
/// about this deep and persist; half the slop measured twice the stack's sinking.
constexpr double kSurfaceLayerPerSlop = 0.2;

}  // namespace anyphys::ode
