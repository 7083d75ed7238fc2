#pragma once
// Validation of defs and settings. Shared by the World (path "BodyDef", "WorldSettings") and the
// scene loader (path "bodies[3]", "settings") so both report the same rule in the same words:
//   "bodies[3].shape.radius: must be > 0, got -1".
#include <algorithm>
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
/// s: longest time step (WorldSettings::timeStep, World::step dt). A step longer than a second is
/// a units mistake, and moves a body at maxSpeed farther than the world is wide.
inline constexpr double kMaxTimeStep = 1.0;
/// m: smallest radius or half extent. Below a micrometre a float engine rounds the size to 0 and
/// a body's mass and inertia underflow (the API fuzzer made Box2D abort on a 1e-300 m sphere).
inline constexpr double kMinLength = 1e-6;
/// kg and kg m^2: the range a dynamic body's resolved mass and each principal inertia must lie in,
/// representable in float with room to spare (a float engine flushes 1e-300 to 0 and
/// divides by it); 1e30 kg is half the Sun.
inline constexpr double kMinMass = 1e-30;
inline constexpr double kMaxMass = 1e30;
/// Largest WorldSettings::substeps, iterations and maxStepsPerUpdate: a count of 2e9 is a typo that
/// would hang the step, not a setting (the sweeps and the catalogue use at most 64 and 1000).
inline constexpr int kMaxSubsteps = 1000;
inline constexpr int kMaxIterations = 100000;
inline constexpr int kMaxStepsPerUpdate = 1000;

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
inline std::string ceilingText(double ceiling) {
    std::ostringstream os;
    os << ceiling;
    return os.str();
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
}  // namespace detail

/// Unit-norm tolerance for orientations: hand-written quaternions such as
/// [0.7071, 0, 0, 0.7071] are accepted and normalised; anything further off is a mistake.
inline constexpr double kUnitQuaternionTolerance = 1e-4;

namespace detail {
// True when the points span a volume (four of them are not coplanar), relative to their extent.
inline bool spansVolume(const std::vector<Vec3>& p) {
    if (p.size() < 4) return false;
    double extent = 0;
    for (const Vec3& q : p) extent = std::max(extent, (q - p[0]).norm());
    if (extent == 0) return false;
    const double eps = 1e-9 * extent;
    std::size_t i1 = 0;
    for (std::size_t i = 1; i < p.size() && !i1; ++i)
        if ((p[i] - p[0]).norm() > eps) i1 = i;
    if (!i1) return false;
    const Vec3 e1 = p[i1] - p[0];
    Vec3 n = Vec3::Zero();
    for (const Vec3& q : p)
        if (const Vec3 c = e1.cross(q - p[0]); c.norm() > eps * extent && c.norm() > n.norm()) n = c;
    if (n.isZero(0)) return false;
    n.normalize();
    for (const Vec3& q : p)
        if (std::abs(n.dot(q - p[0])) > eps) return true;
    return false;
}
}  // namespace detail

namespace detail {
// A compound child's surface overrides belong to that child; on any other shape the body's own
// field is the one to set, so naming it there is refused rather than silently ignored.
inline void refuseSurfaceOverrides(const ShapeDef& s, const std::string& path) {
    const auto refuse = [&](const char* field, const std::string& value) {
        throw Error::invalid(path + "." + field, value,
                             std::string("allowed only on the children of a compound shape (shape.shapes[i].") + field +
                                 "); set the body's " + field + " instead");
    };
    if (s.material) refuse("material", "\"" + *s.material + "\"");
    if (s.isTrigger) refuse("isTrigger", *s.isTrigger ? "true" : "false");
    if (s.layer) refuse("layer", std::to_string(*s.layer));
    if (s.mask) refuse("mask", std::to_string(*s.mask));
}
}  // namespace detail

inline void validate(const ShapeDef& s, const std::string& path, bool isChild = false) {
    using namespace detail;
    if (!isChild) refuseSurfaceOverrides(s, path);
    switch (s.type) {
        case ShapeType::Sphere:
            requireSet(path + ".radius", s.radius, "a sphere needs its radius > 0 (ShapeDef::sphere(r))");
            requireLength(path + ".radius", s.radius);
            break;
        case ShapeType::Box:
            for (int i = 0; i < 3; ++i)
                requireSet(path + ".halfExtents[" + std::to_string(i) + "]", s.halfExtents[i],
                           "a box needs its halfExtents, each > 0 (ShapeDef::box(half))");
            requireLength(path + ".halfExtents[0]", s.halfExtents.x());
            requireLength(path + ".halfExtents[1]", s.halfExtents.y());
            requireLength(path + ".halfExtents[2]", s.halfExtents.z());
            break;
        case ShapeType::Capsule:
            requireSet(path + ".radius", s.radius, "a capsule needs its radius > 0 (ShapeDef::capsule(r, halfHeight))");
            requireSet(path + ".halfHeight", s.halfHeight,
                       "a capsule needs its halfHeight >= 0 (ShapeDef::capsule(r, halfHeight))");
            requireLength(path + ".radius", s.radius);
            requireLength(path + ".halfHeight", s.halfHeight, true);
            break;
        case ShapeType::Plane:
            for (int i = 0; i < 3; ++i)
                requireSet(path + ".normal[" + std::to_string(i) + "]", s.normal[i],
                           "a plane needs its normal (ShapeDef::plane(normal, offset))");
            requireFinite(path + ".normal", s.normal);
            if (s.normal.norm() < 1e-12) throw Error::invalid(path + ".normal", formatVec3(s.normal), "must be non-zero");
            requireCoordinate(path + ".offset", s.offset);
            break;
        case ShapeType::Convex:
            for (std::size_t i = 0; i < s.points.size(); ++i)
                requireCoordinate(path + ".points[" + std::to_string(i) + "]", s.points[i]);
            if (!spansVolume(s.points))
                throw Error::invalid(path + ".points", std::to_string(s.points.size()) + " points",
                                     "must hold at least 4 points that are not all in one plane");
            break;
        case ShapeType::Mesh: {
            if (s.vertices.empty()) throw Error::invalid(path + ".vertices", "[]", "must not be empty");
            for (std::size_t i = 0; i < s.vertices.size(); ++i)
                requireCoordinate(path + ".vertices[" + std::to_string(i) + "]", s.vertices[i]);
            if (s.indices.empty() || s.indices.size() % 3 != 0)
                throw Error::invalid(path + ".indices", std::to_string(s.indices.size()) + " indices",
                                     "must be a non-empty multiple of 3 (three per triangle)");
            for (std::size_t i = 0; i < s.indices.size(); ++i)
                if (s.indices[i] >= s.vertices.size())
                    throw Error::invalid(path + ".indices[" + std::to_string(i) + "]", s.indices[i],
                                         "must be < the number of vertices (" + std::to_string(s.vertices.size()) + ")");
            for (std::size_t t = 0; t < s.indices.size(); t += 3) {
                const Vec3 &a = s.vertices[s.indices[t]], &b = s.vertices[s.indices[t + 1]], &c = s.vertices[s.indices[t + 2]];
                if ((b - a).cross(c - a).norm() <= 1e-12 * std::max(1.0, (b - a).squaredNorm()))
                    throw Error::invalid(path + ".indices[" + std::to_string(t) + ".." + std::to_string(t + 2) + "]",
                                         "triangle " + std::to_string(t / 3), "must not be degenerate (zero area)");
            }
            break;
        }
        case ShapeType::Compound:
            if (isChild) throw Error::invalid(path + ".type", "compound", "compound shapes cannot be nested");
            if (s.shapes.empty()) throw Error::invalid(path + ".shapes", "[]", "must hold at least one child shape");
            for (std::size_t i = 0; i < s.shapes.size(); ++i) {
                const ShapeDef& child = s.shapes[i];
                const std::string childPath = path + ".shapes[" + std::to_string(i) + "]";
                if (child.type == ShapeType::Plane || child.type == ShapeType::Mesh || child.type == ShapeType::Compound)
                    throw Error::invalid(childPath + ".type", toString(child.type),
                                         "compound children must be sphere, box, capsule or convex");
                validate(child, childPath, true);
            }
            break;
    }
    requireCoordinate(path + ".position", s.position);
    if (!s.orientation.coeffs().allFinite() || std::abs(s.orientation.norm() - 1.0) > 1e-4)
        throw Error::invalid(path + ".orientation", formatQuat(s.orientation), "must be a unit quaternion [w, x, y, z] (norm 1 within 1e-4)");
    if (s.density) requirePositive(path + ".density", *s.density);
}

inline void validate(const BodyDef& b, const std::string& path) {
    using namespace detail;
    requireCoordinate(path + ".position", b.position);
    const Vec3 qv(b.orientation.x(), b.orientation.y(), b.orientation.z());
    if (!qv.allFinite() || !std::isfinite(b.orientation.w()) ||
        std::abs(b.orientation.norm() - 1.0) > kUnitQuaternionTolerance)
        throw Error::invalid(path + ".orientation", formatQuat(b.orientation),
                             "must be a unit quaternion [w, x, y, z] (norm 1 within 1e-4)");
    requireFinite(path + ".linearVelocity", b.linearVelocity);
    requireFinite(path + ".angularVelocity", b.angularVelocity);
    validate(b.shape, path + ".shape");
    if ((b.shape.type == ShapeType::Plane || b.shape.type == ShapeType::Mesh) && b.type != BodyType::Static)
        throw Error::invalid(path + ".shape.type", toString(b.shape.type),
                             "plane and mesh shapes are allowed only on static bodies (type \"static\")");
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
    if (b.dragCoefficient) requireNonNegative(path + ".dragCoefficient", *b.dragCoefficient);
    if (std::abs(b.gravityScale) > 1e3)
        throw Error::invalid(path + ".gravityScale", b.gravityScale, "must be within +-1000");
}

/// The rules of a body that depend on the world's settings: its initial velocities within the
/// speed ceilings. `settingsPath` names the settings in messages ("WorldSettings", "settings").
inline void validateLimits(const BodyDef& b, const WorldSettings& s, const std::string& path,
                           const std::string& settingsPath) {
    detail::requireSpeed(path + ".linearVelocity", b.linearVelocity, s.maxSpeed, settingsPath + ".maxSpeed", "m/s");
    detail::requireSpeed(path + ".angularVelocity", b.angularVelocity, s.maxAngularSpeed,
                         settingsPath + ".maxAngularSpeed", "rad/s");
}

namespace detail {
// Tolerance for "zero" out-of-plane components of a planar body: rounding of an in-plane value.
inline constexpr double kPlanarTolerance = 1e-9;

inline bool rotatesAboutZOnly(const Quat& q) {
    return std::abs(q.x()) <= kPlanarTolerance && std::abs(q.y()) <= kPlanarTolerance;
}

inline void validatePlanarShape(const ShapeDef& s, const std::string& path, const std::string& who) {
    if (s.type == ShapeType::Plane && std::abs(s.normal.z()) > kPlanarTolerance * s.normal.norm())
        throw Error::invalid(path + ".normal", formatVec3(s.normal), "must lie in the XY plane (z = 0) in a planar world" + who);
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        const ShapeDef& child = s.shapes[i];
        const std::string childPath = path + ".shapes[" + std::to_string(i) + "]";
        if (std::abs(child.position.z()) > kPlanarTolerance)
            throw Error::invalid(childPath + ".position", formatVec3(child.position), "must have z = 0 in a planar world" + who);
        if (!rotatesAboutZOnly(child.orientation))
            throw Error::invalid(childPath + ".orientation", formatQuat(child.orientation),
                                 "must be a rotation about Z (x = y = 0) in a planar world" + who);
    }
}
}  // namespace detail

/// The extra rules of a planar world (WorldSettings::planar): the body lies in the XY plane,
/// turns about Z only and moves in the plane. Messages name the body.
inline void validatePlanar(const BodyDef& b, const std::string& path) {
    using namespace detail;
    const std::string who = b.name.empty() ? "" : " (body \"" + b.name + "\")";
    if (std::abs(b.position.z()) > kPlanarTolerance)
        throw Error::invalid(path + ".position", formatVec3(b.position), "must have z = 0 in a planar world" + who);
    if (!rotatesAboutZOnly(b.orientation))
        throw Error::invalid(path + ".orientation", formatQuat(b.orientation),
                             "must be a rotation about Z (x = y = 0) in a planar world" + who);
    if (std::abs(b.linearVelocity.z()) > kPlanarTolerance)
        throw Error::invalid(path + ".linearVelocity", formatVec3(b.linearVelocity),
                             "must have z = 0 in a planar world" + who);
    if (std::abs(b.angularVelocity.x()) > kPlanarTolerance || std::abs(b.angularVelocity.y()) > kPlanarTolerance)
        throw Error::invalid(path + ".angularVelocity", formatVec3(b.angularVelocity),
                             "must be about Z only (x = y = 0) in a planar world" + who);
    validatePlanarShape(b.shape, path + ".shape", who);
}

inline void validate(const WorldSettings& s, const std::string& path) {
    using namespace detail;
    if (s.backend.empty()) throw Error::invalid(path + ".backend", "\"\"", "must name a backend");
    requireFinite(path + ".gravity", s.gravity);
    if (s.gravity.norm() > kMaxGravity)
        throw Error::invalid(path + ".gravity", formatVec3(s.gravity),
                             "magnitude must be <= " + ceilingText(kMaxGravity) + " m/s^2 (anyphys::kMaxGravity)");
    if (s.planar && std::abs(s.gravity.z()) > kPlanarTolerance)
        throw Error::invalid(path + ".gravity", formatVec3(s.gravity), "must have z = 0 in a planar world");
    requirePositive(path + ".timeStep", s.timeStep);
    if (s.timeStep > kMaxTimeStep)
        throw Error::invalid(path + ".timeStep", s.timeStep, "must be <= " + ceilingText(kMaxTimeStep) + " s (anyphys::kMaxTimeStep)");
    requirePositive(path + ".maxSpeed", s.maxSpeed);
    requirePositive(path + ".maxAngularSpeed", s.maxAngularSpeed);
    if (s.iterations && (*s.iterations < 1 || *s.iterations > kMaxIterations))
        throw Error::invalid(path + ".iterations", *s.iterations, "must be in [1, " + std::to_string(kMaxIterations) + "] (anyphys::kMaxIterations)");
    if (s.substeps && (*s.substeps < 1 || *s.substeps > kMaxSubsteps))
        throw Error::invalid(path + ".substeps", *s.substeps, "must be in [1, " + std::to_string(kMaxSubsteps) + "] (anyphys::kMaxSubsteps)");
    if (s.maxStepsPerUpdate < 1 || s.maxStepsPerUpdate > kMaxStepsPerUpdate)
        throw Error::invalid(path + ".maxStepsPerUpdate", s.maxStepsPerUpdate,
                             "must be in [1, " + std::to_string(kMaxStepsPerUpdate) + "] (anyphys::kMaxStepsPerUpdate)");
    if (s.workers < 1 || s.workers > kMaxWorkers)
        throw Error::invalid(path + ".workers", s.workers, "must be in [1, " + std::to_string(kMaxWorkers) + "]");
    for (const auto& [name, value] : s.backendOptions) requireFinite(path + ".backendOptions." + name, value);
    requirePositive(path + ".contactHertz", s.contactHertz);
    requireNonNegative(path + ".contactDampingRatio", s.contactDampingRatio);
    requirePositive(path + ".contactPushMaxVelocity", s.contactPushMaxVelocity);
    requireNonNegative(path + ".baumgarte", s.baumgarte);
    if (s.baumgarte > 1) throw Error::invalid(path + ".baumgarte", s.baumgarte, "must be in [0, 1]");
    requireNonNegative(path + ".restitutionThreshold", s.restitutionThreshold);
    requirePositive(path + ".linearSlop", s.linearSlop);
    requireNonNegative(path + ".speculativeDistance", s.speculativeDistance);
    requireNonNegative(path + ".sleepLinearVelocity", s.sleepLinearVelocity);
    requireNonNegative(path + ".sleepAngularVelocity", s.sleepAngularVelocity);
    requireNonNegative(path + ".timeToSleep", s.timeToSleep);
}

}  // namespace anyphys
