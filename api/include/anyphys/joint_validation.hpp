#pragma once
// Validation of joint defs. Shared by World::createJoint (path "JointDef") and the scene loader
// (path "joints[2]") so both report the same rule in the same words:
//   "joints[0].limits: lower must be <= upper, got 1.2 > 0.4".
// Each field's own rule comes from its row (schema/joint_fields.hpp); the rules between fields
// and types are code here.
// The rules on the bodies themselves (which body, which world) are checked where the bodies are
// known; validateJointBodies holds the ones both places share.
#include <optional>
#include <string>

#include "anyphys/error.hpp"
#include "anyphys/joint_def.hpp"
#include "anyphys/schema/joint_fields.hpp"
#include "anyphys/validation.hpp"

namespace anyphys {

/// Which JointDef fields a joint type uses (the others must stay at their defaults).
struct JointFields {
    bool anchor = false;       ///< anchor (every type but distance)
    bool axis = false;         ///< axis (hinge, slider, cone, wheel; ball: the direction whose swing is reported)
    bool distance = false;     ///< anchorA, anchorB, length, minLength, maxLength
    bool cone = false;         ///< swingLimit, twistLimits
    bool wheel = false;        ///< spinAxis, steering
    bool limits = false;
    bool motor = false;
    bool spring = false;
    bool angular = false;      ///< limits, motor and spring act on an angle (rad, N m) rather than an offset (m, N)
};

JointFields jointFields(JointType type);

namespace detail {
/// " (joint \"name\")" for messages, or nothing for an unnamed joint.
std::string jointWho(const std::string& name);
/// "hinge, slider and wheel": the types that use a field.
std::string typesUsing(bool JointFields::*field);
}  // namespace detail

/// Limits of a joint of `type` (JointDef::limits, or Joint::setLimits). Angular limits (hinge)
/// lie in [-pi, pi], the range every engine's hinge limits share. `atCreation`: must contain 0.
void validateJointLimits(const JointLimits& l, JointType type, const std::string& field, bool atCreation);

void validateJointMotor(const JointMotor& m, const std::string& field);

/// A motor of a joint of `type` no faster than the world's ceilings: a slider's speed within
/// `maxSpeed` (m/s), a hinge's or wheel's within `maxAngularSpeed` (rad/s), the
/// WorldSettings fields. The motor drives body B at its speed, and a body past the ceiling has
/// diverged: ODE aborted inside its step on a slider motor of 1e20 m/s, whose body left the
/// collision grid within one substep.
void validateJointMotorSpeed(const JointMotor& m, JointType type, double maxSpeed, double maxAngularSpeed,
                             const std::string& field);

/// Either stiffness and damping, or hertz and dampingRatio; not all zero.
void validateJointSpring(const JointSpring& s, const std::string& field);

/// Every rule on a JointDef's own values (the bodies are checked by whoever resolves them).
/// The World then normalises `axis` and makes `spinAxis` exactly perpendicular to it.
void validate(const JointDef& j, const std::string& path);

/// The extra rules of a planar world (XY plane, rotation about Z): anchors at z = 0, hinge axes
/// along Z, slider and wheel axes in the plane, wheel axles along Z and no steering; cone joints
/// are 3D only. A ball joint is allowed: in the plane it turns about Z only, so the World runs it
/// as a hinge about Z. Messages name the joint.
void validatePlanar(const JointDef& j, const std::string& path);

/// What the joint rules need to know of a body: its name and type.
struct JointBodyView {
    std::string name;
    BodyType type = BodyType::Dynamic;
};

/// The rules on the pair of bodies: two different bodies (or a body and the world, `a` empty),
/// at least one of them dynamic (a joint between things that cannot move does nothing).
void validateJointBodies(const std::optional<JointBodyView>& a, const JointBodyView& b, bool sameBody,
                         const std::string& path);

}  // namespace anyphys
