// Joint handle methods: validate, then forward to the joint's peer. A broken joint keeps its
// handle and def but has no peer: it reports zeros, and changes to it are kept in its def only.
#include "anyphys/joint.hpp"

#include "anyphys/joint_validation.hpp"
#include "handle_link.hpp"
#include "world_impl.hpp"

namespace anyphys {
namespace {

World& worldOf(const std::shared_ptr<detail::WorldLink>& link, JointId id, const char* operation) {
    return detail::linkedWorld(link, id, "joint", operation);
}

/// Refuses a setter on a type that has no such field, naming the joint and the types that have one.
void requireField(const JointDef& def, bool JointFields::*field, const char* operation, const char* what) {
    if (jointFields(def.type).*field) return;
    throw Error::invalid(std::string(operation) + detail::jointWho(def.name), std::string(toString(def.type)) + " joint",
                         std::string("only ") + detail::typesUsing(field) + " joints have " + what);
}

}  // namespace

#define ANYPHYS_JOINT(op) worldOf(link_, id_, op).jointSlot(id_, op)

Joint::Joint(World* world, JointId id) : link_(world ? world->link_ : nullptr), id_(id) {}

bool Joint::isValid() const { return world() && world()->isValid(id_); }

const std::string& Joint::name() const { return ANYPHYS_JOINT("Joint.name").def.name; }
JointType Joint::type() const { return ANYPHYS_JOINT("Joint.type").def.type; }
Body Joint::bodyA() const { return ANYPHYS_JOINT("Joint.bodyA").def.bodyA; }
Body Joint::bodyB() const { return ANYPHYS_JOINT("Joint.bodyB").def.bodyB; }
JointDef Joint::def() const { return ANYPHYS_JOINT("Joint.def").def; }
bool Joint::isBroken() const { return ANYPHYS_JOINT("Joint.isBroken").broken; }
std::uint64_t Joint::userData() const { return ANYPHYS_JOINT("Joint.userData").def.userData; }
void Joint::setUserData(std::uint64_t value) { ANYPHYS_JOINT("Joint.setUserData").def.userData = value; }

double Joint::position() const {
    const auto& j = ANYPHYS_JOINT("Joint.position");
    return j.peer ? j.peer->position() : 0.0;
}
double Joint::speed() const {
    const auto& j = ANYPHYS_JOINT("Joint.speed");
    return j.peer ? j.peer->speed() : 0.0;
}
Vec3 Joint::reactionForce() const {
    const auto& j = ANYPHYS_JOINT("Joint.reactionForce");
    return j.peer ? j.peer->reactionForce() : Vec3::Zero();
}
Vec3 Joint::reactionTorque() const {
    const auto& j = ANYPHYS_JOINT("Joint.reactionTorque");
    return j.peer ? j.peer->reactionTorque() : Vec3::Zero();
}

void Joint::setMotor(const std::optional<JointMotor>& motor) {
    constexpr const char* op = "Joint.setMotor";
    auto& j = ANYPHYS_JOINT(op);
    requireField(j.def, &JointFields::motor, op, "a motor");
    if (motor) {
        validateJointMotor(*motor, op);
        const WorldSettings& w = world()->settings();
        validateJointMotorSpeed(*motor, j.def.type, w.maxSpeed, w.maxAngularSpeed, op);
    }
    j.def.motor = motor;
    if (j.peer && world()->honoursJointField(j, "motor", op)) j.peer->setMotor(motor);
}

void Joint::setLimits(const std::optional<JointLimits>& limits) {
    constexpr const char* op = "Joint.setLimits";
    auto& j = ANYPHYS_JOINT(op);
    requireField(j.def, &JointFields::limits, op, "limits");
    if (limits) validateJointLimits(*limits, j.def.type, op, false);
    j.def.limits = limits;
    if (j.peer && world()->honoursJointField(j, "limits", op)) j.peer->setLimits(limits);
}

void Joint::setSpring(const std::optional<JointSpring>& spring) {
    constexpr const char* op = "Joint.setSpring";
    auto& j = ANYPHYS_JOINT(op);
    requireField(j.def, &JointFields::spring, op, "a spring");
    if (spring) validateJointSpring(*spring, op);
    j.def.spring = spring;
    if (j.peer && world()->honoursJointField(j, "spring", op))
        j.peer->setSpring(spring ? std::optional<JointSpringSI>(world()->jointSpringSI(j, *spring)) : std::nullopt);
}

void Joint::setSteeringAngle(double angle) {
    constexpr const char* op = "Joint.setSteeringAngle";
    auto& j = ANYPHYS_JOINT(op);
    detail::requireFinite(std::string(op) + ".angle", angle);
    if (!j.def.steering)
        throw Error::invalid(std::string(op) + detail::jointWho(j.def.name), std::string(toString(j.def.type)) + " joint",
                             "only wheel joints created with steering = true can steer");
    if (j.peer) j.peer->setSteeringAngle(angle);
}

void* Joint::nativeObject(const std::type_info& pointerType) const {
    const auto& j = ANYPHYS_JOINT("Joint.native");
    return j.peer ? j.peer->nativeObject(pointerType) : nullptr;
}

}  // namespace anyphys
