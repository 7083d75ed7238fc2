#pragma once
// The basic checks with their wording and the way vectors appear in messages: shared by the
// field table (schema.hpp) and validation.hpp, so a rule has one wording wherever it is checked.
// The ceilings they check against are limits.hpp's.
#include <cmath>
#include <sstream>
#include <string>

#include "anyphys/error.hpp"
#include "anyphys/limits.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

inline std::string formatVec3(const Vec3& v) {
    return '[' + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + ']';
}

inline std::string formatQuat(const Quat& q) {
    return '[' + formatNumber(q.w()) + ", " + formatNumber(q.x()) + ", " + formatNumber(q.y()) + ", " + formatNumber(q.z()) + ']';
}

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
