#pragma once
// The names by which backends declare what they honour of joints (Capabilities::jointTypes and
// Capabilities::parameters), and which of them a JointDef uses. A parameter is named
// "joint.<type>.<field>", e.g. "joint.hinge.motor", "joint.distance.minLength".
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "anyphys/joint_def.hpp"
#include "anyphys/joint_validation.hpp"

namespace anyphys {

/// The joint type a backend receives: a ball joint in a planar world turns about Z only, so it
/// runs as a hinge about Z (Box2D's revolute joint); every other type is itself.
inline JointType peerJointType(JointType type, bool planar) {
    return planar && type == JointType::Ball ? JointType::Hinge : type;
}

/// "joint.<type>.<field>".
inline std::string jointParameter(JointType type, std::string_view field) {
    return "joint." + std::string(toString(type)) + "." + std::string(field);
}

/// The optional fields of each joint type that a backend declares separately, in this order.
/// Every type has breakForce, breakTorque and collideConnected.
inline std::vector<std::string_view> jointParameterFields(JointType type) {
    std::vector<std::string_view> fields;
    const JointFields f = jointFields(type);
    if (f.limits) fields.push_back("limits");
    if (f.motor) fields.push_back("motor");
    if (f.spring) fields.push_back("spring");
    if (f.distance) {
        fields.push_back("minLength");
        fields.push_back("maxLength");
    }
    if (f.cone) {
        fields.push_back("swingLimit");
        fields.push_back("twistLimits");
    }
    if (f.wheel) fields.push_back("steering");
    fields.push_back("breakForce");
    fields.push_back("breakTorque");
    fields.push_back("collideConnected");
    return fields;
}

/// Every joint parameter name there is (for checking a backend's declarations).
inline std::vector<std::string> allJointParameters() {
    std::vector<std::string> out;
    for (const auto& [type, name] : EnumNames<JointType>::values)
        for (std::string_view field : jointParameterFields(type)) out.push_back(jointParameter(type, field));
    return out;
}

/// The parameters `def` uses, as (field, parameter name) pairs: an optional field that is set
/// (limits, motor, spring, minLength, maxLength, twistLimits), swingLimit below pi, steering,
/// a finite breakForce or breakTorque, collideConnected true. Named after the type the backend
/// receives (peerJointType).
inline std::vector<std::pair<std::string, std::string>> usedJointParameters(const JointDef& def, bool planar) {
    const JointType type = peerJointType(def.type, planar);
    std::vector<std::pair<std::string, std::string>> used;
    const auto use = [&](bool set, std::string_view field) {
        if (set) used.emplace_back(std::string(field), jointParameter(type, field));
    };
    use(def.limits.has_value(), "limits");
    use(def.motor.has_value(), "motor");
    use(def.spring.has_value(), "spring");
    use(def.minLength.has_value(), "minLength");
    use(def.maxLength.has_value(), "maxLength");
    use(def.type == JointType::Cone && def.swingLimit < JointDef{}.swingLimit, "swingLimit");
    use(def.twistLimits.has_value(), "twistLimits");
    use(def.steering, "steering");
    use(def.breakForce < JointDef{}.breakForce, "breakForce");
    use(def.breakTorque < JointDef{}.breakTorque, "breakTorque");
    use(def.collideConnected, "collideConnected");
    return used;
}

}  // namespace anyphys
