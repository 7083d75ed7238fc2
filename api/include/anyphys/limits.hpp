#pragma once
// The ceilings on absurd finite values (docs/errors.md) and the largest counts a world accepts: plain
// constants, a value type of the API like its defs. The layer checks every input against them
// (checks.hpp, validation.hpp); a backend may size its own structures by them (a plane's extent,
// an iteration option's range) without depending on the layer's checks.

namespace anyphys {

/// Largest WorldSettings::workers accepted.
inline constexpr int kMaxWorkers = 256;

// ---- ceilings on absurd finite values (see docs/errors.md) -----------------------------------
// Finite is not enough: a body 1e308 m away or a gravity of 1e19 m/s^2 overflows inside an
// engine's collision code. Like Box2D's b2_huge, the layer refuses such values up front.

/// m: largest coordinate of a position, plane offset, shape point or size. The Earth's diameter;
/// at 1e7 m a double still resolves 2e-9 m, a millionth of the default linearSlop.
inline constexpr double kMaxCoordinate = 1e7;
/// m/s^2: largest magnitude of WorldSettings::gravity, 1000 g; at the default step it adds
/// 170 m/s per step, far below the default maxSpeed.
inline constexpr double kMaxGravity = 1e4;
/// m/s and rad/s: largest WorldSettings::maxSpeed and maxAngularSpeed. At that speed for the
/// longest step a body moves a tenth of kMaxCoordinate, which every engine's broad phase takes;
/// with a ceiling of 1e20 m/s a body left the world within one substep and ODE aborted in its hash
/// grid, which counts 1/8 m cells in 32-bit integers (API fuzzer).
inline constexpr double kMaxSpeedCeiling = 1e6;
inline constexpr double kMaxAngularSpeedCeiling = 1e6;
/// s: longest time step (WorldSettings::timeStep, World::step dt). A step longer than a second is
/// a units mistake, and moves a body at maxSpeed farther than the world is wide.
inline constexpr double kMaxTimeStep = 1.0;
/// s: shortest time step. A step of 1e-300 s is a units mistake as well, and split into substeps
/// it rounds to 0 (ODE aborts on a zero step: the API fuzzer found a 5e-324 s step) or its inverse
/// overflows. A nanosecond split into kMaxSubsteps still leaves 1e-12 s, with a finite inverse.
inline constexpr double kMinTimeStep = 1e-9;
/// m: smallest radius or half extent. Below a micrometre a float engine rounds the size to 0 and
/// a body's mass and inertia underflow (the API fuzzer made Box2D abort on a 1e-300 m sphere).
inline constexpr double kMinLength = 1e-6;
/// kg and kg m^2: the range a dynamic body's resolved mass and each principal inertia must lie in,
/// representable in float with room to spare (a float engine flushes 1e-300 to 0 and
/// divides by it); 1e30 kg is half the Sun.
inline constexpr double kMinMass = 1e-30;
inline constexpr double kMaxMass = 1e30;
/// The least principal inertia of a dynamic body, as a fraction of its mass times the square of
/// its shapes' reach about that axis (the inertia it would have with the mass at the far corner).
/// Physics allows less (a point mass has none), but a solver's constraint row weighs the body's
/// turning and its translation together: past 1e12 apart, the translation falls below what a
/// double rounds away. A 1e20 kg box of 0.1 m given 2 kg m^2 (1e-17 of that inertia; the API
/// fuzzer) made ODE's LCP fail and then abort the process on a non-finite rotation.
inline constexpr double kMinInertiaRatio = 1e-12;
/// Largest WorldSettings::substeps, iterations and maxStepsPerUpdate: a count of 2e9 is a typo that
/// would hang the step, not a setting (the sweeps and the catalogue use at most 64 and 1000).
inline constexpr int kMaxSubsteps = 1000;
inline constexpr int kMaxIterations = 100000;
inline constexpr int kMaxStepsPerUpdate = 1000;

/// Unit-norm tolerance for orientations: hand-written quaternions such as
/// [0.7071, 0, 0, 0.7071] are accepted and normalised; anything further off is a mistake.
inline constexpr double kUnitQuaternionTolerance = 1e-4;

}  // namespace anyphys
