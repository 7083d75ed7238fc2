// World's joints: creation (validation, capabilities, resolution), destruction, lookup, and the
// layer's breaking pass after each step.
#include <algorithm>
#include <cmath>
#include <string>

#include "anyphys/backends.hpp"
#include "anyphys/joint_capabilities.hpp"
#include "anyphys/joint_validation.hpp"
#include "joint_resolution.hpp"
#include "../world_impl.hpp"

namespace anyphys {
namespace {

/// What joint resolution needs of a body slot: its peer frame now and, if the joint can move
/// it, its mass.
template <class Slot>
JointBodyFrame frameOf(const Slot& s) {
    const BodyState state = s.peer->state();
    const bool movable = s.def.type == BodyType::Dynamic;
    return JointBodyFrame{{state.position, state.orientation}, movable ? s.mass.mass : 0.0, s.mass.inertia};
}

std::string quotedName(const JointDef& def) { return def.name.empty() ? "" : " \"" + def.name + "\""; }

/// The longest lever a joint may have on a dynamic body, in the body's smallest radius of
/// gyration (sqrt(I / m)). A row's turning part grows with the lever squared over that radius
/// squared: found by the API fuzzer, a ball joint anchored 1.7e7 m from a 5 cm ball (5e8 radii)
/// left ODE's direct solver a matrix past double precision, its rotation NaN, and ODE aborted the
/// process. 1e6 radii is 6 km for a 1 cm ball and leaves the rows 4 digits of precision.
constexpr double kMaxJointLeverInGyrationRadii = 1e6;

/// Refuses an anchor too far from a dynamic body's centre of mass (kMaxJointLeverInGyrationRadii).
template <class Slot>
void requireLeverWithinReach(const Slot& s, const Vec3& anchor, const std::string& field, const char* side) {
    if (s.def.type != BodyType::Dynamic || !(s.mass.mass > 0.0)) return;
    const double radius = std::sqrt(s.mass.inertia.minCoeff() / s.mass.mass);
    const double lever = (anchor - s.peer->state().position).norm();
    if (!(lever <= kMaxJointLeverInGyrationRadii * radius))
        throw Error::invalid(field, formatVec3(anchor),
                             "must lie within " + formatNumber(kMaxJointLeverInGyrationRadii) + " radii of gyration of " + side + "'s centre of mass (" +
                                 formatNumber(kMaxJointLeverInGyrationRadii * radius) + " m; the lever is " +
                                 formatNumber(lever) + " m): a longer lever leaves the solvers no precision");
}

/// Clears a parameter the backend lacks (lenient policy): the peer never sees it.
void dropParameter(JointDef& def, const std::string& field) {
    const JointDef defaults;
    if (field == "limits") def.limits.reset();
    if (field == "motor") def.motor.reset();
    if (field == "spring") def.spring.reset();
    if (field == "minLength") def.minLength.reset();
    if (field == "maxLength") def.maxLength.reset();
    if (field == "swingLimit") def.swingLimit = defaults.swingLimit;
    if (field == "twistLimits") def.twistLimits.reset();
    if (field == "steering") def.steering = false;
    if (field == "breakForce") def.breakForce = defaults.breakForce;
    if (field == "breakTorque") def.breakTorque = defaults.breakTorque;
    if (field == "collideConnected") def.collideConnected = false;
}

}  // namespace

Joint World::createJoint(const JointDef& input) {
    impl_->refuseWhileStepping("World.createJoint");
    impl_->refuseWhileDrawing("World.createJoint");
    validate(input, "JointDef");
    // The bodies: B required, A null for the world; both live bodies of this world.
    const auto bodySlot = [this](const Body& body, const char* field) -> Slot* {
        if (!body.world())
            throw Error(ErrorKind::StaleHandle, field,
                        std::string(field) + ": stale body handle: the body's world was destroyed");
        if (body.world() != this)
            throw Error::invalid(field, "a body of another world", "must be a body of this world", ErrorKind::InvalidState);
        std::string operation = field;
        return &slot(body.id(), operation.c_str());
    };
    if (input.bodyB.id().isNull())
        throw Error::invalid("JointDef.bodyB", "null", "is required: the body the joint holds (bodyA null holds it to the world)");
    Slot* a = input.bodyA.id().isNull() ? nullptr : bodySlot(input.bodyA, "JointDef.bodyA");
    Slot* b = bodySlot(input.bodyB, "JointDef.bodyB");
    const auto view = [](const Slot& s) { return JointBodyView{s.def.name, s.def.type}; };
    validateJointBodies(a ? std::optional<JointBodyView>(view(*a)) : std::nullopt, view(*b), a == b, "JointDef");
    const bool distance = input.type == JointType::Distance;
    if (a) requireLeverWithinReach(*a, distance ? input.anchorA : input.anchor, distance ? "JointDef.anchorA" : "JointDef.anchor", "bodyA");
    requireLeverWithinReach(*b, distance ? input.anchorB : input.anchor, distance ? "JointDef.anchorB" : "JointDef.anchor", "bodyB");
    // ODE welds a fixed joint's bodies by their centres, wherever the anchor is: the lever is the
    // other body's centre (found by the API fuzzer: a 5 cm ball fixed to a kinematic body 1.4e7 m
    // away, 4e8 of its radii of gyration, aborted ODE's direct solver).
    if (input.type == JointType::Fixed && a) {
        requireLeverWithinReach(*b, a->peer->state().position, "JointDef.bodyA", "bodyB");
        requireLeverWithinReach(*a, b->peer->state().position, "JointDef.bodyB", "bodyA");
    }
    if (settings_.planar) validatePlanar(input, "JointDef");
    if (input.motor)
        validateJointMotorSpeed(*input.motor, input.type, settings_.maxSpeed, settings_.maxAngularSpeed, "JointDef.motor");
    if (settings_.effects && !settings_.effects->has(Effect::Joints))
        throw Error(ErrorKind::Unsupported, "WorldSettings.effects",
                    "World.createJoint: the world's declared effects exclude \"joints\"; add it to WorldSettings.effects");

    // Capabilities: strict refuses; lenient runs without what is missing (the joint itself if its
    // type is), saying so once.
    const Capabilities& caps = impl_->backend->capabilities;
    const bool planar = settings_.planar;
    const JointDef def = normalizedJointDef(input);
    JointDef applied = def;  // what the peer receives
    bool simulated = true;
    if (const auto missing = missingJointCapabilities(caps, input, planar); !missing.empty()) {
        const std::string what = "JointDef" + quotedName(input) + ": backend \"" + settings_.backend +
                                 "\" does not support: " + detail::commaList(missing);
        if (settings_.capabilityPolicy == CapabilityPolicy::Strict)
            throw Error(ErrorKind::Unsupported, "JointDef", what + " (capabilityPolicy strict; choose lenient to run without them)");
        simulated = caps.effects.has(Effect::Joints) &&
                    caps.jointTypes.contains(std::string(toString(peerJointType(input.type, planar))));
        for (const auto& [field, parameter] : usedJointParameters(input, planar))
            if (!caps.parameters.contains(parameter)) dropParameter(applied, field);
        warn(what + (simulated ? "; ignored" : "; the joint is not simulated"));
    }

    JointPeerDef peerDef = resolveJoint(applied, a ? std::optional<JointBodyFrame>(frameOf(*a)) : std::nullopt,
                                        frameOf(*b), planar);
    peerDef.bodyA = a ? a->peer.get() : nullptr;
    peerDef.bodyB = b->peer.get();

    const bool reuse = !impl_->freeJoints.empty();
    const std::uint32_t index = reuse ? impl_->freeJoints.back() : static_cast<std::uint32_t>(impl_->joints.size());
    const std::uint32_t generation = reuse ? impl_->joints[index].generation : 1;
    peerDef.userData = packId(JointId{index, generation});
    std::unique_ptr<JointPeer> peer;
    if (simulated) {
        peer = impl_->peer->createJoint(peerDef);  // may throw: nothing changed yet
        if (!peer)
            throw Error(ErrorKind::Internal, "", "World.createJoint: backend \"" + settings_.backend + "\" returned no joint");
    }

    if (reuse)
        impl_->freeJoints.pop_back();
    else
        impl_->joints.emplace_back();
    JointSlot& j = impl_->joints[index];
    j.peer = std::move(peer);
    j.live = true;
    j.broken = false;
    j.def = def;
    j.peerType = peerDef.type;
    j.frameA = peerDef.frameA;
    j.frameB = peerDef.frameB;
    j.breakForce = j.peer ? applied.breakForce : JointDef{}.breakForce;
    j.breakTorque = j.peer ? applied.breakTorque : JointDef{}.breakTorque;
    if (a) a->joints.push_back(index);
    b->joints.push_back(index);
    ++impl_->liveJoints;
    if (j.peer) ++impl_->simulatedJoints;
    if (j.peer && j.breakable()) {
        auto& watched = impl_->breakableJoints;
        watched.insert(std::lower_bound(watched.begin(), watched.end(), index), index);  // slot order: events in a fixed order
    }
    for (Slot* s : {a, b})
        if (s && s->def.type == BodyType::Dynamic) s->peer->setAwake(true);
    refreshEffects();
    return Joint(this, JointId{index, j.generation});
}

void World::destroyJoint(Joint joint) {
    impl_->refuseWhileStepping("World.destroyJoint");
    impl_->refuseWhileDrawing("World.destroyJoint");
    if (!joint.world())
        throw Error(ErrorKind::StaleHandle, "", "World.destroyJoint: stale joint handle: the joint's world was destroyed");
    if (joint.world() != this) throw Error(ErrorKind::InvalidState, "", "World.destroyJoint: the joint belongs to another world");
    jointSlot(joint.id(), "World.destroyJoint");
    releaseJoint(joint.id().index);
    refreshEffects();
}

void World::releaseJoint(std::uint32_t index) {
    JointSlot& j = impl_->joints[index];
    if (j.peer) {
        impl_->peer->destroyJoint(*j.peer);
        j.peer.reset();
        --impl_->simulatedJoints;
    }
    for (const Body& body : {j.def.bodyA, j.def.bodyB}) {
        if (body.id().isNull()) continue;
        auto& list = impl_->slots[body.id().index].joints;
        list.erase(std::find(list.begin(), list.end(), index));
    }
    std::erase(impl_->breakableJoints, index);
    j.live = false;
    j.broken = false;
    j.def = JointDef{};
    ++j.generation;
    impl_->freeJoints.push_back(index);
    --impl_->liveJoints;
}

World::JointSlot& World::jointSlot(JointId id, const char* operation) {
    return const_cast<JointSlot&>(static_cast<const World*>(this)->jointSlot(id, operation));
}

const World::JointSlot& World::jointSlot(JointId id, const char* operation) const {
    if (id.isNull()) throw Error(ErrorKind::StaleHandle, "", std::string(operation) + ": null joint handle");
    if (!isValid(id))
        throw Error(ErrorKind::StaleHandle, "", std::string(operation) + ": stale joint handle (index " + std::to_string(id.index) + ", generation " +
                    std::to_string(id.generation) + "): the joint was destroyed, or one of its bodies was");
    return impl_->joints[id.index];
}

bool World::isValid(JointId id) const {
    return !id.isNull() && id.index < impl_->joints.size() && impl_->joints[id.index].live &&
           impl_->joints[id.index].generation == id.generation;
}

Joint World::joint(JointId id) {
    jointSlot(id, "World.joint");
    return Joint(this, id);
}

std::vector<Joint> World::joints() const {
    std::vector<Joint> out;
    out.reserve(impl_->liveJoints);
    for (std::uint32_t i = 0; i < impl_->joints.size(); ++i)
        if (impl_->joints[i].live) out.emplace_back(const_cast<World*>(this), JointId{i, impl_->joints[i].generation});
    return out;
}

std::size_t World::jointCount() const { return impl_->liveJoints; }

Joint World::findJoint(const std::string& name) {
    for (std::uint32_t i = 0; i < impl_->joints.size(); ++i)
        if (impl_->joints[i].live && impl_->joints[i].def.name == name) return Joint(this, JointId{i, impl_->joints[i].generation});
    throw Error::invalid("World.findJoint.name", "\"" + name + "\"", "must name a live joint");
}

bool World::honoursJointField(const JointSlot& j, const char* field, const char* operation) {
    const std::string parameter = jointParameter(j.peerType, field);
    if (impl_->backend->capabilities.parameters.contains(parameter)) return true;
    const std::string what = std::string(operation) + quotedName(j.def) + ": backend \"" + settings_.backend +
                             "\" does not support " + parameter;
    if (settings_.capabilityPolicy == CapabilityPolicy::Strict)
        throw Error(ErrorKind::Unsupported, "", what + " (capabilityPolicy strict; choose lenient to run without it)");
    warn(what + "; ignored");
    return false;
}

JointSpringSI World::jointSpringSI(const JointSlot& j, const JointSpring& spring) const {
    const Body a = j.def.bodyA, b = j.def.bodyB;
    const std::optional<JointBodyFrame> frameA =
        a.id().isNull() ? std::nullopt : std::optional<JointBodyFrame>(frameOf(impl_->slots[a.id().index]));
    const JointBodyFrame frameB = frameOf(impl_->slots[b.id().index]);
    // The masses as they are now, about the joint's axis and anchor as created (exact while the
    // bodies stay near that pose; hertz is a tuning aid, not a measurement).
    return resolveSpring(spring, springEffective(j.def, frameA, frameB, jointFrame(j.def, settings_.planar)));
}

const std::vector<JointEvent>& World::lastJointEvents() const { return impl_->lastJointEvents; }

void World::breakJoints() {
    Impl& i = *impl_;
    i.lastJointEvents.clear();
    for (std::uint32_t index : i.breakableJoints) {
        JointSlot& j = i.joints[index];
        const Vec3 force = j.peer->reactionForce(), torque = j.peer->reactionTorque();
        // Strictly above: a joint holds exactly its stated load.
        if (!(force.norm() > j.breakForce || torque.norm() > j.breakTorque)) continue;
        i.lastJointEvents.push_back({JointId{index, j.generation}, j.def.name, force, torque});
        i.peer->destroyJoint(*j.peer);
        j.peer.reset();
        j.broken = true;
        --i.simulatedJoints;
    }
    if (i.lastJointEvents.empty()) return;
    std::erase_if(i.breakableJoints, [&i](std::uint32_t index) { return i.joints[index].broken; });
    refreshEffects();
}

void World::deliverJointBreaks(const std::vector<JointEvent>& events) {
    // Listeners registered now; a callback may destroy joints or bodies, or even step.
    const std::vector<ContactListener*> listeners = impl_->listeners;
    for (const JointEvent& event : events)
        for (ContactListener* l : listeners) l->onJointBreak(event);
}

}  // namespace anyphys
