#pragma once
// Joints: constraints that hold two bodies (or a body and the static world) together. Every field
// documents its unit and default; anchors and axes are world coordinates at creation, and every
// angle and offset a joint reports is measured from the pose at creation (0 there).
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "anyphys/body.hpp"
#include "anyphys/joint_types.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

struct JointDef {
    std::string name;                  ///< optional; errors and events name it. Default ""
    JointType type = JointType::Ball;  ///< default ball
    Body bodyA;                        ///< default null: B is held to the static world
    Body bodyB;                        ///< required: a live body of the same world, not bodyA
    /// m, world: the point the bodies share (all types but distance; the wheel's centre).
    Vec3 anchor = Vec3::Zero();
    /// world, unit or normalised: hinge and slider axis, cone twist axis, wheel suspension direction.
    /// Default +Z (the only hinge axis a planar world allows).
    Vec3 axis = Vec3::UnitZ();
    // ---- distance ----
    Vec3 anchorA = Vec3::Zero();       ///< m, world: the point on A (or fixed in the world)
    Vec3 anchorB = Vec3::Zero();       ///< m, world: the point on B
    std::optional<double> length;      ///< m, > 0; default: |anchorB - anchorA| at creation
    std::optional<double> minLength;   ///< m, >= 0; with maxLength: a rope or a range instead of a rod
    std::optional<double> maxLength;   ///< m, >= minLength
    // ---- cone ----
    double swingLimit = 3.141592653589793;  ///< rad, (0, pi]: half-angle of the swing cone about axis
    std::optional<JointLimits> twistLimits; ///< rad, twist of B about axis; default free
    // ---- wheel ----
    Vec3 spinAxis = Vec3::UnitX();     ///< world: the axle, perpendicular to axis. Default +X
    bool steering = false;             ///< A may turn the wheel about axis (Joint::setSteeringAngle); 3D only
    // ---- common ----
    std::optional<JointLimits> limits;  ///< hinge angle, slider offset, wheel suspension travel; default none
    std::optional<JointMotor> motor;    ///< hinge, slider, wheel (spin); default none
    std::optional<JointSpring> spring;  ///< hinge, slider, distance, wheel (suspension); default none
    double breakForce = std::numeric_limits<double>::infinity();   ///< N: the joint breaks above this reaction force
    double breakTorque = std::numeric_limits<double>::infinity();  ///< N m: ... or above this reaction torque
    bool collideConnected = false;     ///< let A and B collide with each other. Default false
    /// The game's own value, kept for it and never read by anyphys (see BodyDef::userData).
    /// Joint::userData / setUserData. Default 0.
    std::uint64_t userData = 0;
};

}  // namespace anyphys
