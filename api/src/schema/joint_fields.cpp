// The rows of JointDef and its sub-objects (see schema/joint_fields.hpp). Which types use a field
// comes from jointFields(type) (joint_validation.hpp), the same table validation and the backends'
// parameter names use.
#include <cstdint>
#include <limits>
#include <vector>

#include "anyphys/joint_validation.hpp"
#include "anyphys/schema/joint_fields.hpp"
#include "anyphys/schema/rows.hpp"

namespace anyphys::schema {

namespace {
// The types whose JointFields flag `field` is set.
std::uint32_t typesUsing(bool JointFields::*field) {
    std::uint32_t out = 0;
    for (const auto& [type, name] : EnumNames<JointType>::values)
        if (jointFields(type).*field) out |= bit(type);
    return out;
}
}  // namespace

const std::vector<Field<JointDef>>& jointDefFields() {
    using J = JointDef;
    using F = Field<J>;
    const std::uint32_t anchor = typesUsing(&JointFields::anchor), axis = typesUsing(&JointFields::axis),
                        distance = typesUsing(&JointFields::distance), cone = typesUsing(&JointFields::cone),
                        wheel = typesUsing(&JointFields::wheel), limits = typesUsing(&JointFields::limits),
                        motor = typesUsing(&JointFields::motor), spring = typesUsing(&JointFields::spring);
    static const std::vector<F> rows = {
        with<J>({.key = "name", .path = "joint.name", .type = Type::String, .value = std::string(""),
                 .note = "unique when given; errors and events name it", .honour = Honour::Parent,
                 .save = Save::WhenNotDefault},
                member(&J::name)),
        {.key = "type", .path = "joint.type", .type = Type::Enum, .required = true,
         .note = "backends list the types they run (`anyphys backends`: joint types)", .honour = Honour::Parent,
         .ownCode = true, .allowed = allowedNames<JointType>},
        {.key = "bodyA", .path = "joint.bodyA", .type = Type::String, .unit = "body name",
         .defaultText = "omitted: the world", .note = "a body of the scene, or `\"world\"` (refused when a body is named `\"world\"`: it would mean both)", .honour = Honour::Parent,
         .ownCode = true},
        {.key = "bodyB", .path = "joint.bodyB", .type = Type::String, .unit = "body name", .required = true,
         .note = "a body of the scene, not bodyA; one of the two dynamic", .honour = Honour::Parent, .ownCode = true},
        with<J>({.key = "anchor", .path = "joint.anchor", .type = Type::Vec3, .unit = "m, world", .value = Vec3(0, 0, 0),
                 .check = Check::Coordinate, .note = "the point the bodies share (wheel: the wheel centre)",
                 .honour = Honour::Parent, .types = anchor},
                member(&J::anchor)),
        with<J>({.key = "axis", .path = "joint.axis", .type = Type::Vec3, .unit = "world direction",
                 .value = Vec3(0, 0, 1), .check = Check::Finite,
                 .note = "and non-zero; normalised. Hinge and slider axis, cone twist axis, wheel suspension direction "
                         "(ball: the axis its swing is measured from). Planar worlds: hinge along Z, slider and wheel "
                         "in the XY plane",
                 .honour = Honour::Parent, .types = axis},
                member(&J::axis)),
        with<J>({.key = "anchorA", .path = "joint.anchorA", .type = Type::Vec3, .unit = "m, world",
                 .value = Vec3(0, 0, 0), .check = Check::Coordinate, .note = "the point on A (or fixed in the world)",
                 .honour = Honour::Parent, .types = distance},
                member(&J::anchorA)),
        with<J>({.key = "anchorB", .path = "joint.anchorB", .type = Type::Vec3, .unit = "m, world",
                 .value = Vec3(0, 0, 0), .check = Check::Coordinate, .note = "the point on B; differs from anchorA",
                 .honour = Honour::Parent, .types = distance},
                member(&J::anchorB)),
        with<J>({.key = "length", .path = "joint.length", .unit = "m", .defaultText = "the anchors' distance at creation",
                 .check = Check::Positive, .honour = Honour::Parent, .save = Save::WhenSet, .types = distance},
                member(&J::length)),
        with<J>({.key = "minLength", .path = "joint.*.minLength", .unit = "m", .defaultText = "none (a rigid rod)",
                 .check = Check::NonNegative,
                 .note = "<= `maxLength` and <= the anchors' distance at creation: a range, or a rope with only "
                         "`maxLength`",
                 .save = Save::WhenSet, .types = distance},
                member(&J::minLength)),
        with<J>({.key = "maxLength", .path = "joint.*.maxLength", .unit = "m", .defaultText = "none (a rigid rod)",
                 .check = Check::Positive, .note = ">= `minLength` and >= the anchors' distance at creation",
                 .save = Save::WhenSet, .types = distance},
                member(&J::maxLength)),
        with<J>({.key = "swingLimit", .path = "joint.*.swingLimit", .unit = "rad", .value = JointDef{}.swingLimit,
                 .defaultText = "pi (free)", .note = "in (0, pi]: half-angle of the swing cone about `axis`",
                 .types = cone},
                member(&J::swingLimit)),
        {.key = "twistLimits", .path = "joint.*.twistLimits", .type = Type::Object, .unit = "rad, `{lower, upper}`",
         .defaultText = "free", .note = "twist of B about `axis`; lower <= 0 <= upper, within +-pi",
         .save = Save::WhenSet, .types = cone, .ownCode = true},
        with<J>({.key = "spinAxis", .path = "joint.spinAxis", .type = Type::Vec3, .unit = "world direction",
                 .value = Vec3(1, 0, 0), .check = Check::Finite,
                 .note = "the axle: non-zero, perpendicular to `axis` (cosine within 1e-4 of 0)",
                 .honour = Honour::Parent, .types = wheel},
                member(&J::spinAxis)),
        with<J>({.key = "steering", .path = "joint.*.steering", .type = Type::Bool, .value = false,
                 .note = "the wheel may be turned about `axis` (`Joint::setSteeringAngle`); 3D only", .types = wheel},
                member(&J::steering)),
        {.key = "limits", .path = "joint.*.limits", .type = Type::Object, .unit = "rad (hinge) or m, `{lower, upper}`",
         .defaultText = "none",
         .note = "hinge angle (within +-pi), slider offset, wheel suspension travel; lower <= 0 <= upper",
         .save = Save::WhenSet, .types = limits, .ownCode = true},
        {.key = "motor", .path = "joint.*.motor", .type = Type::Object, .unit = "object, see below",
         .defaultText = "none", .note = "drives the joint toward `speed` with at most `maxForce` (wheel: the spin)", .save = Save::WhenSet,
         .types = motor, .ownCode = true},
        {.key = "spring", .path = "joint.*.spring", .type = Type::Object, .unit = "object, see below",
         .defaultText = "none", .note = "toward the rest position (distance: the rest length; wheel: the suspension)", .save = Save::WhenSet,
         .types = spring, .ownCode = true},
        with<J>({.key = "breakForce", .path = "joint.*.breakForce", .unit = "N", .value = JointDef{}.breakForce,
                 .defaultText = "infinity: never (not written)", .check = Check::Threshold,
                 .words = " (infinity, the default: never breaks)",
                 .note = "the joint breaks when its reaction force exceeds it (reported to listeners, `Joint::isBroken`)",
                 .save = Save::WhenNotDefault},
                member(&J::breakForce)),
        with<J>({.key = "breakTorque", .path = "joint.*.breakTorque", .unit = "N m", .value = JointDef{}.breakTorque,
                 .defaultText = "infinity: never (not written)", .check = Check::Threshold,
                 .words = " (infinity, the default: never breaks)", .note = "... or its reaction torque",
                 .save = Save::WhenNotDefault},
                member(&J::breakTorque)),
        with<J>({.key = "collideConnected", .path = "joint.*.collideConnected", .type = Type::Bool, .value = false,
                 .note = "let the two bodies collide with each other"},
                member(&J::collideConnected)),
        {.key = "userData", .path = "joint.userData", .type = Type::Object, .unit = "any JSON value",
         .defaultText = "none",
         .note = "the game's: kept as JSON text (`SceneJoint::userData`) and saved back; an unsigned integer is also "
                 "`JointDef::userData` (`Joint::userData()`)",
         .honour = Honour::Parent, .save = Save::WhenSet, .ownCode = true},
    };
    return rows;
}

const std::vector<Field<JointLimits>>& jointLimitsFields() {
    using L = JointLimits;
    static const std::vector<Field<L>> rows = {
        with<L>({.key = "lower", .path = "joint.limits.lower", .unit = "rad or m", .value = 0.0, .required = true,
                 .check = Check::Finite, .note = "<= 0 (where the joint starts) and <= `upper`", .honour = Honour::Parent},
                member(&L::lower)),
        with<L>({.key = "upper", .path = "joint.limits.upper", .unit = "rad or m", .value = 0.0, .required = true,
                 .check = Check::Finite, .note = ">= 0", .honour = Honour::Parent},
                member(&L::upper)),
    };
    return rows;
}

const std::vector<Field<JointMotor>>& jointMotorFields() {
    using M = JointMotor;
    static const std::vector<Field<M>> rows = {
        with<M>({.key = "speed", .path = "joint.motor.speed", .unit = "rad/s or m/s", .value = 0.0,
                 .check = Check::Finite, .note = "target relative speed of B", .honour = Honour::Parent},
                member(&M::speed)),
        with<M>({.key = "maxForce", .path = "joint.motor.maxForce", .unit = "N m or N", .value = 0.0,
                 .check = Check::NonNegative, .note = "the most the motor may apply", .honour = Honour::Parent},
                member(&M::maxForce)),
    };
    return rows;
}

const std::vector<Field<JointSpring>>& jointSpringFields() {
    using S = JointSpring;
    // Written as a pair: stiffness and damping, or hertz and dampingRatio (see scene_json.cpp).
    static const std::vector<Field<S>> rows = {
        with<S>({.key = "stiffness", .path = "joint.spring.stiffness", .unit = "N/m or N m/rad", .value = 0.0,
                 .check = Check::NonNegative, .honour = Honour::Parent},
                member(&S::stiffness)),
        with<S>({.key = "damping", .path = "joint.spring.damping", .unit = "N s/m or N m s/rad", .value = 0.0,
                 .check = Check::NonNegative, .honour = Honour::Parent},
                member(&S::damping)),
        with<S>({.key = "hertz", .path = "joint.spring.hertz", .unit = "Hz", .value = 0.0, .check = Check::NonNegative,
                 .note = "used when > 0, then stiffness and damping must be 0: the layer turns hertz and dampingRatio "
                         "into them with the joint's effective mass or inertia",
                 .honour = Honour::Parent},
                member(&S::hertz)),
        with<S>({.key = "dampingRatio", .path = "joint.spring.dampingRatio", .unit = "1", .value = 0.0,
                 .check = Check::NonNegative, .note = "0 without hertz; not all four 0", .honour = Honour::Parent},
                member(&S::dampingRatio)),
    };
    return rows;
}

}  // namespace anyphys::schema
