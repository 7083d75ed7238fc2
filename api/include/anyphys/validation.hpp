#pragma once
// Validation of defs and settings. Shared by the World (path "BodyDef", "WorldSettings") and the
// scene loader (path "bodies[3]", "settings") so both report the same rule in the same words:
//   "bodies[3].shape.radius: must be > 0, got -1".
#include <cmath>
#include <sstream>
#include <string>

#include "anyphys/defs.hpp"
#include "anyphys/error.hpp"
#include "anyphys/world_settings.hpp"

namespace anyphys {

inline std::string formatVec3(const Vec3& v) {
    std::ostringstream os;
    os.precision(17);
    os << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
    return os.str();
}

inline std::string formatQuat(const Quat& q) {
    std::ostringstream os;
    os.precision(17);
    os << '[' << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << ']';
    return os.str();
}

namespace detail {
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
}  // namespace detail

/// Unit-norm tolerance for orientations: hand-written quaternions such as
/// [0.7071, 0, 0, 0.7071] are accepted and normalised; anything further off is a mistake.
inline constexpr double kUnitQuaternionTolerance = 1e-4;

inline void validate(const ShapeDef& s, const std::string& path) {
    using namespace detail;
    switch (s.type) {
        case ShapeType::Sphere: requirePositive(path + ".radius", s.radius); break;
        case ShapeType::Box:
            requirePositive(path + ".halfExtents[0]", s.halfExtents.x());
            requirePositive(path + ".halfExtents[1]", s.halfExtents.y());
            requirePositive(path + ".halfExtents[2]", s.halfExtents.z());
            break;
        case ShapeType::Capsule:
            requirePositive(path + ".radius", s.radius);
            requireNonNegative(path + ".halfHeight", s.halfHeight);
            break;
        case ShapeType::Plane:
            requireFinite(path + ".normal", s.normal);
            if (s.normal.norm() < 1e-12) throw Error::invalid(path + ".normal", formatVec3(s.normal), "must be non-zero");
            requireFinite(path + ".offset", s.offset);
            break;
    }
}

inline void validate(const BodyDef& b, const std::string& path) {
    using namespace detail;
    requireFinite(path + ".position", b.position);
    const Vec3 qv(b.orientation.x(), b.orientation.y(), b.orientation.z());
    if (!qv.allFinite() || !std::isfinite(b.orientation.w()) ||
        std::abs(b.orientation.norm() - 1.0) > kUnitQuaternionTolerance)
        throw Error::invalid(path + ".orientation", formatQuat(b.orientation),
                             "must be a unit quaternion [w, x, y, z] (norm 1 within 1e-4)");
    requireFinite(path + ".linearVelocity", b.linearVelocity);
    requireFinite(path + ".angularVelocity", b.angularVelocity);
    validate(b.shape, path + ".shape");
    if (b.shape.type == ShapeType::Plane && b.type != BodyType::Static)
        throw Error::invalid(path + ".shape.type", "plane", "plane shapes are allowed only on static bodies (type \"static\")");
    if (b.type == BodyType::Static && (!b.linearVelocity.isZero(0) || !b.angularVelocity.isZero(0)))
        throw Error::invalid(path + (b.linearVelocity.isZero(0) ? ".angularVelocity" : ".linearVelocity"),
                             formatVec3(b.linearVelocity.isZero(0) ? b.angularVelocity : b.linearVelocity),
                             "must be zero for a static body");
    if (b.mass) requirePositive(path + ".mass", *b.mass);
    if (b.density) requirePositive(path + ".density", *b.density);
    if (b.inertia) {
        requirePositive(path + ".inertia[0]", b.inertia->x());
        requirePositive(path + ".inertia[1]", b.inertia->y());
        requirePositive(path + ".inertia[2]", b.inertia->z());
    }
    requireNonNegative(path + ".linearDamping", b.linearDamping);
    requireNonNegative(path + ".angularDamping", b.angularDamping);
    requireFinite(path + ".gravityScale", b.gravityScale);
}

inline void validate(const WorldSettings& s, const std::string& path) {
    using namespace detail;
    if (s.backend.empty()) throw Error::invalid(path + ".backend", "\"\"", "must name a backend");
    requireFinite(path + ".gravity", s.gravity);
    requirePositive(path + ".timeStep", s.timeStep);
    if (s.iterations < 1) throw Error::invalid(path + ".iterations", s.iterations, "must be >= 1");
    if (s.substeps < 1) throw Error::invalid(path + ".substeps", s.substeps, "must be >= 1");
    if (s.maxStepsPerUpdate < 1) throw Error::invalid(path + ".maxStepsPerUpdate", s.maxStepsPerUpdate, "must be >= 1");
    for (const auto& [name, value] : s.backendOptions) requireFinite(path + ".backendOptions." + name, value);
}

}  // namespace anyphys
