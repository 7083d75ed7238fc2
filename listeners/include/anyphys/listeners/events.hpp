#pragma once
// Collision and trigger events: the same meaning on every backend.
#include <cstdint>
#include <string>
#include <vector>

#include "anyphys/ids.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

enum class ContactPhase { Enter, Stay, Exit };

struct ContactPoint {
    Vec3 position = Vec3::Zero();  ///< m, world frame
    double depth = 0.0;            ///< m, penetration (> 0 when overlapping)
    double normalImpulse = 0.0;    ///< N s; meaningful only where the backend reports impulses
};

/// One pair's event. Pair order is fixed: bodyA < bodyB (lower id first); `normal` points from
/// A to B.
struct ContactEvent {
    BodyId bodyA;
    BodyId bodyB;
    ContactPhase phase = ContactPhase::Enter;
    bool trigger = false;       ///< a sensor overlap rather than a collision
    bool removal = false;       ///< exit caused by destroying one of the bodies
    bool hasImpulses = false;   ///< normalImpulse values are real (backend capability, settings.contactImpulses; ODE: from the step after events were first read)
    Vec3 normal = Vec3::Zero();
    std::vector<ContactPoint> points;  ///< empty for exits and triggers
};

/// What a backend reports for one touching pair after a step (ids already mapped by the layer).
struct TouchingPair {
    BodyId bodyA;
    BodyId bodyB;
    bool trigger = false;
    bool hasImpulses = false;
    Vec3 normal = Vec3::Zero();
    std::vector<ContactPoint> points;
};

/// A touching pair whose points are a range of one array shared by the step's pairs, so that a
/// step of thousands of pairs needs no allocation per pair (ContactTracker's allocation-free update).
struct TouchingRange {
    BodyId bodyA;
    BodyId bodyB;
    bool trigger = false;
    bool hasImpulses = false;
    bool asleep = false;          ///< a body of the pair is asleep: the contact persists silently (no Stay)
    Vec3 normal = Vec3::Zero();   ///< from A to B
    std::uint32_t firstPoint = 0; ///< points [firstPoint, firstPoint + pointCount) of the shared array
    std::uint32_t pointCount = 0;
};

/// A joint broke: after a step, its reaction force or torque exceeded JointDef::breakForce or
/// breakTorque. The joint's handle stays valid (Joint::isBroken); its constraint is gone.
struct JointEvent {
    JointId joint;
    std::string name;             ///< the joint's name (JointDef::name), "" when it has none
    Vec3 force = Vec3::Zero();    ///< N, world frame: the reaction on bodyB over the step it broke in
    Vec3 torque = Vec3::Zero();   ///< N m, world frame, about B's anchor
};

}  // namespace anyphys
