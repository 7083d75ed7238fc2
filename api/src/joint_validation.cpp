// Joint def validation (joint_validation.hpp): the rules between fields and types, in the words
// World::createJoint and the scene loader share.
#include "anyphys/joint_validation.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

namespace anyphys {

JointFields jointFields(JointType type) {
    JointFields f;
    switch (type) {
        case JointType::Fixed: f.anchor = true; break;
        case JointType::Ball: f.anchor = f.axis = true; break;
        case JointType::Hinge: f.anchor = f.axis = f.limits = f.motor = f.spring = f.angular = true; break;
        case JointType::Slider: f.anchor = f.axis = f.limits = f.motor = f.spring = true; break;
        case JointType::Distance: f.distance = f.spring = true; break;
        case JointType::Cone: f.anchor = f.axis = f.cone = f.angular = true; break;
        case JointType::Wheel: f.anchor = f.axis = f.wheel = f.limits = f.motor = f.spring = true; break;
    }
    return f;
}

namespace detail {

std::string jointWho(const std::string& name) { return name.empty() ? "" : " (joint \"" + name + "\")"; }

std::string typesUsing(bool JointFields::*field) {
    std::string out;
    int count = 0;
    for (const auto& [type, name] : EnumNames<JointType>::values)
        if (jointFields(type).*field) ++count;
    int seen = 0;
    for (const auto& [type, name] : EnumNames<JointType>::values) {
        if (!(jointFields(type).*field)) continue;
        ++seen;
        out += (seen == 1 ? "" : seen == count ? " and " : ", ") + std::string(name);
    }
    return out;
}

// Helpers of the rules below.
namespace {

/// Axes are accepted within this cosine of perpendicular (wheel axle vs suspension) or of the
/// plane (planar worlds), so hand-written axes such as [0.7071, 0.7071, 0] pass.
constexpr double kJointAxisTolerance = 1e-4;
/// Anchors of a distance joint closer than this have no direction.
constexpr double kMinAnchorDistance = 1e-9;

std::string formatLimits(const JointLimits& l) {
    return "[" + formatNumber(l.lower) + ", " + formatNumber(l.upper) + "]";
}

void requireUnused(bool used, bool JointFields::*field, JointType type, const std::string& path,
                          const std::string& value) {
    if (used)
        throw Error::invalid(path, value,
                             "must be absent for a " + std::string(toString(type)) + " joint (only " + typesUsing(field) +
                                 " joints use it)");
}

void requireNonZeroAxis(const std::string& field, const Vec3& v) {
    requireFinite(field, v);
    if (!(v.norm() > 1e-12)) throw Error::invalid(field, formatVec3(v), "must be non-zero (a direction)");
}

/// lower <= upper, both finite, 0 inside (where the joint starts), and within [-bound, bound].
void validateRange(const JointLimits& l, const std::string& field, double bound, const std::string& boundName) {
    schema::checkFields(schema::jointLimitsFields(), l, field, [](const auto&) { return true; });
    if (!(l.lower <= l.upper))
        throw Error(ErrorKind::InvalidArgument, field, field + ": lower must be <= upper, got " + formatNumber(l.lower) + " > " + formatNumber(l.upper));
    if (l.lower < -bound) throw Error::invalid(field + ".lower", l.lower, "must be >= -" + boundName);
    if (l.upper > bound) throw Error::invalid(field + ".upper", l.upper, "must be <= " + boundName);
}

void requireContainsZero(const JointLimits& l, const std::string& field) {
    if (l.lower > 0 || l.upper < 0)
        throw Error::invalid(field, formatLimits(l),
                             "must contain 0 (every position is measured from the pose at creation, where it is 0)");
}

using schema::checkRow;

}  // namespace
}  // namespace detail

void validateJointLimits(const JointLimits& l, JointType type, const std::string& field, bool atCreation) {
    const bool angular = jointFields(type).angular;
    detail::validateRange(l, field, angular ? std::numbers::pi : std::numeric_limits<double>::infinity(), "pi");
    if (atCreation) detail::requireContainsZero(l, field);
}

void validateJointMotor(const JointMotor& m, const std::string& field) {
    schema::checkFields(schema::jointMotorFields(), m, field, [](const auto&) { return true; });
}

void validateJointMotorSpeed(const JointMotor& m, JointType type, double maxSpeed, double maxAngularSpeed,
                             const std::string& field) {
    const bool angular = jointFields(type).angular || type == JointType::Wheel;  // a wheel's motor spins it
    const double ceiling = angular ? maxAngularSpeed : maxSpeed;
    if (std::abs(m.speed) <= ceiling) return;
    throw Error::invalid(field + ".speed", m.speed,
                         std::string("must lie within the world's ") + (angular ? "maxAngularSpeed" : "maxSpeed") + ", +-" +
                             formatNumber(ceiling) + (angular ? " rad/s" : " m/s") +
                             " (the motor drives body B at this speed; faster, the body has diverged)");
}

void validateJointSpring(const JointSpring& s, const std::string& field) {
    schema::checkFields(schema::jointSpringFields(), s, field, [](const auto&) { return true; });
    const auto both = [](double a, double b) { return formatNumber(a) + " and " + formatNumber(b); };
    if (s.hertz > 0 && (s.stiffness > 0 || s.damping > 0))
        throw Error::invalid(field, "stiffness and damping " + both(s.stiffness, s.damping) + " with hertz " +
                                        formatNumber(s.hertz),
                             "give either stiffness and damping, or hertz and dampingRatio, not both");
    if (s.hertz == 0 && s.dampingRatio > 0)
        throw Error::invalid(field + ".dampingRatio", s.dampingRatio,
                             "must be 0 without hertz (give hertz > 0 with it, or damping in N s/m)");
    if (s.hertz == 0 && s.stiffness == 0 && s.damping == 0)
        throw Error::invalid(field, "all zero", "must have stiffness or damping > 0, or hertz > 0 (no spring: leave it unset)");
}

void validate(const JointDef& j, const std::string& path) {
    using namespace detail;
    const JointFields f = jointFields(j.type);
    // Anchors have the bodies' ceiling: one 1e308 m away made Box2D's state NaN in the first step.
    const auto& rows = schema::jointDefFields();
    for (std::string_view key : {"anchor", "axis", "anchorA", "anchorB", "spinAxis"}) checkRow(rows, key, j, path);
    if (f.axis) requireNonZeroAxis(path + ".axis", j.axis);

    // Optional fields belong to some types only: setting one elsewhere is a mistake, not a no-op.
    requireUnused(!f.limits && j.limits.has_value(), &JointFields::limits, j.type, path + ".limits",
                  j.limits ? formatLimits(*j.limits) : "");
    requireUnused(!f.motor && j.motor.has_value(), &JointFields::motor, j.type, path + ".motor", "a motor");
    requireUnused(!f.spring && j.spring.has_value(), &JointFields::spring, j.type, path + ".spring", "a spring");
    requireUnused(!f.distance && j.length.has_value(), &JointFields::distance, j.type, path + ".length",
                  j.length ? formatNumber(*j.length) : "");
    requireUnused(!f.distance && j.minLength.has_value(), &JointFields::distance, j.type, path + ".minLength",
                  j.minLength ? formatNumber(*j.minLength) : "");
    requireUnused(!f.distance && j.maxLength.has_value(), &JointFields::distance, j.type, path + ".maxLength",
                  j.maxLength ? formatNumber(*j.maxLength) : "");
    requireUnused(!f.cone && j.twistLimits.has_value(), &JointFields::cone, j.type, path + ".twistLimits",
                  j.twistLimits ? formatLimits(*j.twistLimits) : "");
    requireUnused(!f.cone && j.swingLimit != JointDef{}.swingLimit, &JointFields::cone, j.type, path + ".swingLimit",
                  formatNumber(j.swingLimit));
    requireUnused(!f.wheel && j.steering, &JointFields::wheel, j.type, path + ".steering", "true");

    if (j.limits) validateJointLimits(*j.limits, j.type, path + ".limits", true);
    if (j.motor) validateJointMotor(*j.motor, path + ".motor");
    if (j.spring) validateJointSpring(*j.spring, path + ".spring");

    if (f.cone) {
        if (!(j.swingLimit > 0 && j.swingLimit <= std::numbers::pi))
            throw Error::invalid(path + ".swingLimit", j.swingLimit, "must be in (0, pi] (half-angle of the swing cone, rad)");
        if (j.twistLimits) {
            validateRange(*j.twistLimits, path + ".twistLimits", std::numbers::pi, "pi");
            requireContainsZero(*j.twistLimits, path + ".twistLimits");
        }
    }
    if (f.wheel) {
        requireNonZeroAxis(path + ".spinAxis", j.spinAxis);
        const double cosine = j.axis.normalized().dot(j.spinAxis.normalized());
        if (std::abs(cosine) > kJointAxisTolerance)
            throw Error::invalid(path + ".spinAxis", formatVec3(j.spinAxis),
                                 "must be perpendicular to axis " + formatVec3(j.axis) + " (cosine within 1e-4 of 0), cosine " +
                                     formatNumber(cosine));
    }
    if (f.distance) {
        const double d = (j.anchorB - j.anchorA).norm();
        if (!(d > kMinAnchorDistance))
            throw Error::invalid(path + ".anchorB", formatVec3(j.anchorB),
                                 "must differ from anchorA (the line between them is the joint's direction)");
        for (std::string_view key : {"length", "minLength", "maxLength"}) checkRow(rows, key, j, path);
        if (j.minLength && j.maxLength && !(*j.minLength <= *j.maxLength))
            throw Error(ErrorKind::InvalidArgument, path + ".maxLength", path + ".maxLength: must be >= minLength, got " + formatNumber(*j.maxLength) + " < " +
                        formatNumber(*j.minLength));
        // The anchors' distance at creation lies in the range, as every position starts in its limits.
        if (j.minLength && *j.minLength > d)
            throw Error::invalid(path + ".minLength", *j.minLength,
                                 "must be <= the anchors' distance at creation (" + formatNumber(d) + " m)");
        if (j.maxLength && *j.maxLength < d)
            throw Error::invalid(path + ".maxLength", *j.maxLength,
                                 "must be >= the anchors' distance at creation (" + formatNumber(d) + " m)");
    }
    checkRow(rows, "breakForce", j, path);
    checkRow(rows, "breakTorque", j, path);
}

void validatePlanar(const JointDef& j, const std::string& path) {
    using namespace detail;
    const std::string who = jointWho(j.name);
    const JointFields f = jointFields(j.type);
    const auto inPlane = [&](const std::string& field, const Vec3& v) {
        if (std::abs(v.z()) > kPlanarTolerance)
            throw Error::invalid(path + field, formatVec3(v), "must have z = 0 in a planar world" + who);
    };
    const auto alongZ = [&](const std::string& field, const Vec3& v, const std::string& what) {
        if (std::hypot(v.x(), v.y()) > kJointAxisTolerance * v.norm())
            throw Error::invalid(path + field, formatVec3(v), "must be along Z in a planar world (" + what + ")" + who);
    };
    const auto directionInPlane = [&](const std::string& field, const Vec3& v, const std::string& what) {
        if (std::abs(v.z()) > kJointAxisTolerance * v.norm())
            throw Error::invalid(path + field, formatVec3(v), "must lie in the XY plane (z = 0) in a planar world (" + what + ")" + who);
    };
    if (j.type == JointType::Cone)
        throw Error::invalid(path + ".type", "cone",
                             "must not be cone in a planar world (its swing cone leaves the plane; use a hinge with limits)" + who);
    if (f.anchor) inPlane(".anchor", j.anchor);
    if (f.distance) {
        inPlane(".anchorA", j.anchorA);
        inPlane(".anchorB", j.anchorB);
    }
    if (j.type == JointType::Hinge) alongZ(".axis", j.axis, "the only axis bodies turn about");
    if (j.type == JointType::Slider || j.type == JointType::Wheel)
        directionInPlane(".axis", j.axis, "bodies move in the plane");
    if (j.type == JointType::Wheel) {
        alongZ(".spinAxis", j.spinAxis, "a wheel in the plane spins about Z");
        if (j.steering) throw Error::invalid(path + ".steering", "true", "must be false in a planar world (steering turns the axle out of Z)" + who);
    }
}

void validateJointBodies(const std::optional<JointBodyView>& a, const JointBodyView& b, bool sameBody,
                                const std::string& path) {
    const auto describe = [](const JointBodyView& v) {
        return std::string(toString(v.type)) + (v.name.empty() ? " body" : " body \"" + v.name + "\"");
    };
    if (sameBody)
        throw Error::invalid(path + ".bodyB", describe(b), "must differ from bodyA (a joint holds two bodies, or a body to the world)");
    const bool dynamic = b.type == BodyType::Dynamic || (a && a->type == BodyType::Dynamic);
    if (!dynamic)
        throw Error::invalid(path + ".bodyB", describe(b) + " with " + (a ? describe(*a) : std::string("the static world")),
                             "at least one of bodyA and bodyB must be dynamic");
}

}  // namespace anyphys
