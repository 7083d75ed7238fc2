#pragma once
// The ceilings on absurd finite values, the basic checks with their wording and the way vectors
// appear in messages: shared by the field table (schema.hpp) and validation.hpp, so a rule has
// one wording wherever it is checked.
#include <cmath>
#include <sstream>
#include <string>

#include "anyphys/error.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

inline std::string formatVec3(const Vec3& v) {
    return '[' + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + ']';
}

inline std::string formatQuat(const Quat& q) {
    return '[' + formatNumber(q.w()) + ", " + formatNumber(q.x()) + ", " + formatNumber(q.y()) + ", " + formatNumber(q.z()) + ']';
}

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

namespace detail {
inline std::string ceilingText(double ceiling) {
    std::ostringstream os;
    os << ceiling;
    return os.str();
}
inline void requireFinite(const std::string& field, double v) {
    if (!std::isfinite(v)) throw Error::invalid(field, v, "must be finite");
}
inline void requireFinite(const std::string& field, const Vec3& v) {
    if (!v.allFinite()) throw Error::invalid(field, formatVec3(v), "must be finite");
}
inline void requirePositive(const std::string& field, double v) {
    if (!(std::isfinite(v) && v > 0)) throw Error::invalid(field, v, "must be > 0");
}
inline void requireNonNegative(const std::string& field, double v) {
    if (!(std::isfinite(v) && v >= 0)) throw Error::invalid(field, v, "must be >= 0");
}
/// A position or offset: finite and every coordinate within +-kMaxCoordinate.
inline void requireCoordinate(const std::string& field, const Vec3& v) {
    requireFinite(field, v);
    if (v.cwiseAbs().maxCoeff() > kMaxCoordinate)
        throw Error::invalid(field, formatVec3(v),
                             "every coordinate must be within +-" + ceilingText(kMaxCoordinate) + " m (anyphys::kMaxCoordinate)");
}
inline void requireCoordinate(const std::string& field, double v) {
    requireFinite(field, v);
    if (std::abs(v) > kMaxCoordinate)
        throw Error::invalid(field, v, "must be within +-" + ceilingText(kMaxCoordinate) + " m (anyphys::kMaxCoordinate)");
}
/// A time step: in [kMinTimeStep, kMaxTimeStep].
inline void requireTimeStep(const std::string& field, double dt) {
    requirePositive(field, dt);
    if (dt < kMinTimeStep)
        throw Error::invalid(field, dt, "must be >= " + ceilingText(kMinTimeStep) + " s (anyphys::kMinTimeStep)");
    if (dt > kMaxTimeStep)
        throw Error::invalid(field, dt, "must be <= " + ceilingText(kMaxTimeStep) + " s (anyphys::kMaxTimeStep)");
}
/// A field a shape type needs and that has no default (kUnset): "not set" names it and says why.
/// `rule` says what the type needs, e.g. "a sphere needs its radius > 0 (ShapeDef::sphere(r))".
inline void requireSet(const std::string& field, double v, const std::string& rule) {
    if (std::isnan(v))
        throw Error(ErrorKind::InvalidArgument, field, field + ": not set (or NaN); " + rule + ", there is no default");
}
/// A size: > 0 and at most kMaxCoordinate.
inline void requireLength(const std::string& field, double v, bool allowZero = false) {
    allowZero ? requireNonNegative(field, v) : requirePositive(field, v);
    if (!allowZero && v < kMinLength)
        throw Error::invalid(field, v, "must be >= " + ceilingText(kMinLength) + " m (anyphys::kMinLength)");
    if (v > kMaxCoordinate)
        throw Error::invalid(field, v, "must be <= " + ceilingText(kMaxCoordinate) + " m (anyphys::kMaxCoordinate)");
}
/// A speed against its ceiling: `setting` names it ("WorldSettings.maxSpeed").
inline void requireSpeed(const std::string& field, const Vec3& v, double ceiling, const std::string& setting,
                         const char* unit) {
    requireFinite(field, v);
    if (v.norm() > ceiling)
        throw Error::invalid(field, formatVec3(v),
                             "magnitude must be <= " + setting + " (" + ceilingText(ceiling) + " " + unit + ")");
}
/// What a push changes, each with its ceiling: a body's speed (WorldSettings::maxSpeed, m/s) or its
/// spin (WorldSettings::maxAngularSpeed, rad/s).
enum class PushedMotion { Speed, Spin };
/// A push that changes a body's speed or spin by `change` beyond the world's `ceiling` is absurd
/// (an engine handed it integrates an infinite velocity): refused naming `field` and its `value`.
/// `overOneStep`: a force or torque, acting for WorldSettings::timeStep; otherwise an impulse.
inline void requirePushWithinCeiling(const std::string& field, const Vec3& value, double change, PushedMotion motion,
                                     bool overOneStep, double ceiling) {
    if (change <= ceiling) return;  // false for NaN: refused
    const bool speed = motion == PushedMotion::Speed;
    const char* unit = speed ? " m/s" : " rad/s";
    throw Error::invalid(field, formatVec3(value),
                         std::string("would change the body's ") + (speed ? "speed" : "spin") + " by " + ceilingText(change) +
                             unit + (overOneStep ? " in one step (WorldSettings.timeStep)" : "") + ", more than WorldSettings." +
                             (speed ? "maxSpeed (" : "maxAngularSpeed (") + ceilingText(ceiling) + unit + ")");
}
}  // namespace detail

}  // namespace anyphys
