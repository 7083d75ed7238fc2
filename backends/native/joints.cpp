#include "joints.hpp"

#include "native_world.hpp"

namespace anyphys::native {

NativeJoint& NativeJointPeer::joint() const { return world_.joints()[index_]; }

double NativeJointPeer::position() const { return joint().position; }
double NativeJointPeer::speed() const { return joint().speed; }
Vec3 NativeJointPeer::reactionForce() const { return joint().reactionForce; }
Vec3 NativeJointPeer::reactionTorque() const { return joint().reactionTorque; }

// Every change wakes the joint's bodies: a sleeping pair must react to a new motor speed.
void NativeJointPeer::setMotor(const std::optional<JointMotor>& motor) {
    joint().def.motor = motor;
    if (!motor) joint().releaseRow(kMotor);
    world_.wakeJoint(index_);
}

void NativeJointPeer::setLimits(const std::optional<JointLimits>& limits) {
    joint().def.limits = limits;
    joint().releaseRow(kLower);
    joint().releaseRow(kUpper);
    world_.wakeJoint(index_);
}

void NativeJointPeer::setSpring(const std::optional<JointSpringSI>& spring) {
    joint().def.spring = spring;
    joint().releaseRow(kSpring);
    world_.wakeJoint(index_);
}

void NativeJointPeer::setSteeringAngle(double angle) {
    joint().steeringAngle = angle;
    world_.wakeJoint(index_);
}

}  // namespace anyphys::native
