#include "joint_resolution.hpp"

#include <cmath>
#include <numbers>

#include "anyphys/joint_capabilities.hpp"

namespace anyphys {
namespace {

/// The pose `world` (in the world) seen from `frame` (a peer frame in the world, or the world).
Transform relativeTo(const std::optional<JointBodyFrame>& body, const Transform& world) {
    if (!body) return world;
    const Quat inverse = body->pose.orientation.conjugate();
    return {inverse * (world.position - body->pose.position), (inverse * world.orientation).normalized()};
}

Vec3 pointIn(const std::optional<JointBodyFrame>& body, const Vec3& world) {
    return body ? Vec3(body->pose.orientation.conjugate() * (world - body->pose.position)) : world;
}

/// 1 / m (0 for the world and unmovable bodies).
double inverseMass(const std::optional<JointBodyFrame>& body) {
    return body && body->mass > 0 ? 1.0 / body->mass : 0.0;
}

/// 1 / I about `axis` through `point` (0 for the world and unmovable bodies).
double inverseInertia(const std::optional<JointBodyFrame>& body, const Vec3& point, const Vec3& axis) {
    if (!body || !(body->mass > 0)) return 0.0;
    const Vec3 local = body->pose.orientation.conjugate() * axis;
    const double aboutCentre = local.dot(body->inertia.cwiseProduct(local));
    const double offset = (body->pose.position - point).cross(axis).squaredNorm();
    const double inertia = aboutCentre + body->mass * offset;
    return inertia > 0 ? 1.0 / inertia : 0.0;
}

/// A right-handed frame with X = x (unit) and Y = y (unit, perpendicular to x).
Quat frameOf(const Vec3& x, const Vec3& y) {
    Mat3 r;
    r.col(0) = x;
    r.col(1) = y;
    r.col(2) = x.cross(y);
    return Quat(r).normalized();
}

/// The unit vector perpendicular to x nearest world +Y, or nearest world +Z when x is close to Y.
Vec3 perpendicular(const Vec3& x) {
    const Vec3 reference = std::abs(x.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitZ();
    return (reference - reference.dot(x) * x).normalized();
}

}  // namespace

JointDef normalizedJointDef(const JointDef& def) {
    JointDef out = def;
    if (out.axis.norm() > 0) out.axis.normalize();
    if (out.type == JointType::Wheel) out.spinAxis = (out.spinAxis - out.spinAxis.dot(out.axis) * out.axis).normalized();
    return out;
}

Transform jointFrame(const JointDef& def, bool planar) {
    if (def.type == JointType::Distance) {
        const Vec3 x = (def.anchorB - def.anchorA).normalized();
        return {def.anchorA, frameOf(x, perpendicular(x))};
    }
    const Vec3 x = peerJointType(def.type, planar) != def.type ? Vec3::UnitZ() : Vec3(def.axis.normalized());
    const Vec3 y = def.type == JointType::Wheel ? Vec3(def.spinAxis) : perpendicular(x);
    return {def.anchor, frameOf(x, y)};
}

double effectiveMass(const std::optional<JointBodyFrame>& a, const JointBodyFrame& b) {
    const double sum = inverseMass(a) + inverseMass(b);
    return sum > 0 ? 1.0 / sum : 0.0;
}

double effectiveInertia(const std::optional<JointBodyFrame>& a, const JointBodyFrame& b, const Vec3& point,
                        const Vec3& axis) {
    const double sum = inverseInertia(a, point, axis) + inverseInertia(b, point, axis);
    return sum > 0 ? 1.0 / sum : 0.0;
}

JointSpringSI resolveSpring(const JointSpring& spring, double effective) {
    if (!(spring.hertz > 0)) return {spring.stiffness, spring.damping};
    const double omega = 2.0 * std::numbers::pi * spring.hertz;
    return {effective * omega * omega, 2.0 * spring.dampingRatio * effective * omega};
}

double springEffective(const JointDef& def, const std::optional<JointBodyFrame>& a, const JointBodyFrame& b,
                       const Transform& frame) {
    if (jointFields(def.type).angular) return effectiveInertia(a, b, frame.position, frame.orientation * Vec3::UnitX());
    return effectiveMass(a, b);
}

JointPeerDef resolveJoint(const JointDef& input, const std::optional<JointBodyFrame>& a, const JointBodyFrame& b,
                          bool planar) {
    const JointDef def = normalizedJointDef(input);
    JointPeerDef out;
    out.type = peerJointType(def.type, planar);
    const Transform frame = jointFrame(def, planar);
    out.frameA = relativeTo(a, frame);
    if (def.type == JointType::Distance) {
        out.frameB = relativeTo(b, Transform{def.anchorB, frame.orientation});
        out.anchorA = pointIn(a, def.anchorA);
        out.anchorB = pointIn(b, def.anchorB);
        out.length = def.length.value_or((def.anchorB - def.anchorA).norm());
        out.minLength = def.minLength;
        out.maxLength = def.maxLength;
    } else {
        out.frameB = relativeTo(b, frame);
    }
    out.swingLimit = def.swingLimit;
    out.twistLimits = def.twistLimits;
    out.steering = def.steering;
    out.limits = def.limits;
    out.motor = def.motor;
    if (def.spring) out.spring = resolveSpring(*def.spring, springEffective(def, a, b, frame));
    out.collideConnected = def.collideConnected;
    return out;
}

}  // namespace anyphys
