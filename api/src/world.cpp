#include "anyphys/world.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "anyphys/backends.hpp"
#include "anyphys/mass_properties.hpp"
#include "anyphys/validation.hpp"
#include "world_impl.hpp"

namespace anyphys {
namespace {

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
    return out;
}

// Marks the world as stepping for the lifetime of the guard, even if a callback throws.
class SteppingGuard {
public:
    explicit SteppingGuard(bool& flag) : flag_(flag) { flag_ = true; }
    ~SteppingGuard() { flag_ = false; }
    SteppingGuard(const SteppingGuard&) = delete;
    SteppingGuard& operator=(const SteppingGuard&) = delete;

private:
    bool& flag_;
};

bool needsGravity(const BodyDef& d) { return d.type == BodyType::Dynamic && d.gravityScale != 0.0; }
bool needsDamping(const BodyDef& d) {
    return d.type == BodyType::Dynamic && (d.linearDamping > 0.0 || d.angularDamping > 0.0);
}
bool needsGyroscopic(const BodyDef& d) { return d.type == BodyType::Dynamic && d.gyroscopic != GyroscopicMode::None; }

// The force callback's view: maps user handles to peers of this world.
class ForceContextImpl final : public ForceContext {
public:
    ForceContextImpl(World& world, ForceStage& stage, BodyPeer& (*resolve)(World&, Body))
        : world_(world), stage_(stage), resolve_(resolve) {}
    double time() const override { return stage_.time(); }
    BodyState state(Body body) const override { return stage_.state(resolve_(world_, body)); }
    void addForce(Body body, const Vec3& force) override {
        detail::requireFinite("ForceContext.addForce.force", force);
        stage_.addForce(resolve_(world_, body), force);
    }
    void addTorque(Body body, const Vec3& torque) override {
        detail::requireFinite("ForceContext.addTorque.torque", torque);
        stage_.addTorque(resolve_(world_, body), torque);
    }

private:
    World& world_;
    ForceStage& stage_;
    BodyPeer& (*resolve_)(World&, Body);
};

}  // namespace

World::World(const WorldSettings& settings, MaterialLibrary materials)
    : settings_(settings), materials_(std::move(materials)), impl_(std::make_unique<Impl>()) {
    validate(settings_, "WorldSettings");
    impl_->backend = &findBackend(settings_.backend);
    const Capabilities& caps = impl_->backend->capabilities;
    const Effects requested = settings_.effects.value_or(Effects::none());
    const auto missing = missingCapabilities(caps, settings_, requested);
    if (!missing.empty()) {
        const std::string what = "backend \"" + settings_.backend + "\" does not support: " + join(missing);
        if (settings_.capabilityPolicy == CapabilityPolicy::Strict)
            throw Error("WorldSettings: " + what + " (capabilityPolicy strict; choose lenient to run without them)");
        warn("WorldSettings: " + what + "; running without them");
    }
    impl_->peer = impl_->backend->createWorld(settings_);
    refreshEffects();
}

World::~World() = default;

void World::warn(const std::string& message) {
    if (!impl_->warned.insert(message).second) return;  // each warning once
    if (impl_->warningHandler)
        impl_->warningHandler(message);
    else
        std::cerr << "anyphys warning: " << message << '\n';
}

void World::setWarningHandler(WarningHandler handler) { impl_->warningHandler = std::move(handler); }

void World::refreshEffects() {
    Effects wanted;
    if (settings_.effects) {
        wanted = *settings_.effects;
    } else {
        if (!settings_.gravity.isZero(0) && impl_->gravityBodies > 0) wanted.add(Effect::Gravity);
        if (impl_->dampedBodies > 0) wanted.add(Effect::Damping);
        if (impl_->gyroscopicBodies > 0) wanted.add(Effect::Gyroscopic);
        if (impl_->forcesUsed || impl_->forceCallback) wanted.add(Effect::UserForces);
    }
    const Effects active = wanted & impl_->backend->capabilities.effects;
    if (active == activeEffects_ && impl_->peer) return;
    activeEffects_ = active;
    impl_->peer->setEffects(active);
}

// ---- bodies ---------------------------------------------------------------------------------

Body World::createBody(const BodyDef& input) {
    if (impl_->stepping) throw Error("World.createBody: not allowed while the world is stepping (inside a force callback)");
    validate(input, "BodyDef");
    if (!materials_.contains(input.material))
        throw Error::invalid("BodyDef.material", "\"" + input.material + "\"",
                             "must name a material of the world's library (" + join(materials_.names()) + ")");

    const Capabilities& caps = impl_->backend->capabilities;
    std::vector<std::string> missing;
    if (!caps.shapes.count(input.shape.type)) missing.push_back("shape type " + std::string(toString(input.shape.type)));
    if (!caps.bodyTypes.count(input.type)) missing.push_back("body type " + std::string(toString(input.type)));
    if (input.type == BodyType::Dynamic && !caps.gyroscopicModes.count(input.gyroscopic))
        missing.push_back("gyroscopic mode " + std::string(toString(input.gyroscopic)));
    const BodyDef defaults;
    const auto checkParameter = [&](bool used, const char* parameter) {
        if (used && !caps.parameters.count(parameter)) missing.push_back(parameter);
    };
    checkParameter(input.linearDamping != defaults.linearDamping, "body.linearDamping");
    checkParameter(input.angularDamping != defaults.angularDamping, "body.angularDamping");
    checkParameter(input.gravityScale != defaults.gravityScale, "body.gravityScale");
    if (!missing.empty()) {
        const std::string what = "backend \"" + settings_.backend + "\" does not support: " + join(missing);
        if (settings_.capabilityPolicy == CapabilityPolicy::Strict) throw Error("BodyDef: " + what);
        warn("BodyDef: " + what + "; ignored");
    }

    BodyPeerDef peerDef{input, {}};
    peerDef.def.orientation.normalize();
    if (input.type == BodyType::Dynamic) {
        const double volume = shapeVolume(input.shape);
        const double density = input.density.value_or(materials_.get(input.material).density);
        const double mass = input.mass.value_or(density * volume);
        peerDef.mass.mass = mass;
        peerDef.mass.inertia = input.inertia.value_or(unitInertia(input.shape) * mass);
    }

    const bool reuse = !impl_->freeSlots.empty();
    const std::uint32_t index = reuse ? impl_->freeSlots.back() : static_cast<std::uint32_t>(impl_->slots.size());
    std::unique_ptr<BodyPeer> peer = impl_->peer->createBody(peerDef);  // may throw: nothing changed yet
    if (reuse)
        impl_->freeSlots.pop_back();
    else
        impl_->slots.emplace_back();
    Slot& s = impl_->slots[index];
    s.peer = std::move(peer);
    s.def = peerDef.def;
    s.mass = peerDef.mass;
    ++impl_->liveBodies;
    impl_->gravityBodies += needsGravity(s.def);
    impl_->dampedBodies += needsDamping(s.def);
    impl_->gyroscopicBodies += needsGyroscopic(s.def);
    refreshEffects();
    return Body(this, BodyId{index, s.generation});
}

void World::destroyBody(Body body) {
    if (impl_->stepping) throw Error("World.destroyBody: not allowed while the world is stepping (inside a force callback)");
    if (body.world() != this) throw Error("World.destroyBody: the body belongs to another world");
    Slot& s = slot(body.id(), "World.destroyBody");
    for (const ContactEvent& event : impl_->tracker.removeBody(body.id()))
        for (ContactListener* l : impl_->listeners)
            event.trigger ? l->onTriggerExit(event) : l->onCollisionExit(event);
    impl_->peer->destroyBody(*s.peer);
    s.peer.reset();
    ++s.generation;
    impl_->freeSlots.push_back(body.id().index);
    --impl_->liveBodies;
    impl_->gravityBodies -= needsGravity(s.def);
    impl_->dampedBodies -= needsDamping(s.def);
    impl_->gyroscopicBodies -= needsGyroscopic(s.def);
    refreshEffects();
}

World::Slot& World::slot(BodyId id, const char* operation) {
    return const_cast<Slot&>(static_cast<const World*>(this)->slot(id, operation));
}

const World::Slot& World::slot(BodyId id, const char* operation) const {
    if (id.isNull()) throw Error(std::string(operation) + ": null body handle");
    if (id.index >= impl_->slots.size() || !impl_->slots[id.index].peer ||
        impl_->slots[id.index].generation != id.generation)
        throw Error(std::string(operation) + ": stale body handle (index " + std::to_string(id.index) +
                    ", generation " + std::to_string(id.generation) + "): the body was destroyed");
    return impl_->slots[id.index];
}

bool World::isValid(BodyId id) const {
    return !id.isNull() && id.index < impl_->slots.size() && impl_->slots[id.index].peer &&
           impl_->slots[id.index].generation == id.generation;
}

Body World::body(BodyId id) {
    slot(id, "World.body");
    return Body(this, id);
}

std::vector<Body> World::bodies() const {
    std::vector<Body> out;
    out.reserve(impl_->liveBodies);
    for (std::uint32_t i = 0; i < impl_->slots.size(); ++i)
        if (impl_->slots[i].peer) out.emplace_back(const_cast<World*>(this), BodyId{i, impl_->slots[i].generation});
    return out;
}

std::size_t World::bodyCount() const { return impl_->liveBodies; }

Body World::findBody(const std::string& name) {
    for (std::uint32_t i = 0; i < impl_->slots.size(); ++i)
        if (impl_->slots[i].peer && impl_->slots[i].def.name == name) return Body(this, BodyId{i, impl_->slots[i].generation});
    throw Error::invalid("World.findBody.name", "\"" + name + "\"", "must name a live body");
}

// ---- stepping -------------------------------------------------------------------------------

void World::step() { step(settings_.timeStep); }

void World::step(double dt) {
    if (impl_->stepping) throw Error("World.step: not allowed while the world is stepping (inside a force callback)");
    detail::requirePositive("World.step.dt", dt);
    {
        SteppingGuard guard(impl_->stepping);
        impl_->peer->step(time_, dt);
    }
    // Compensated summation keeps time == n * dt to the last bit over long runs.
    const double y = dt - timeCompensation_;
    const double t = time_ + y;
    timeCompensation_ = (t - time_) - y;
    time_ = t;
    ++stepCount_;
}

int World::update(double elapsed) {
    if (!(std::isfinite(elapsed) && elapsed >= 0.0)) throw Error::invalid("World.update.elapsed", elapsed, "must be >= 0 and finite");
    accumulator_ += elapsed;
    const double dt = settings_.timeStep;
    int steps = 0;
    while (accumulator_ >= dt && steps < settings_.maxStepsPerUpdate) {
        step(dt);
        accumulator_ -= dt;
        ++steps;
    }
    if (accumulator_ >= dt) accumulator_ = std::fmod(accumulator_, dt);  // drop what a slow frame cannot catch up
    return steps;
}

double World::interpolationAlpha() const { return accumulator_ / settings_.timeStep; }

// ---- forces and events ----------------------------------------------------------------------

void World::setForceCallback(ForceCallback callback) {
    if (impl_->stepping) throw Error("World.setForceCallback: not allowed while the world is stepping");
    if (callback && settings_.effects && !settings_.effects->has(Effect::UserForces))
        throw Error("World.setForceCallback: the world's declared effects exclude \"userForces\"; add it to WorldSettings.effects");
    impl_->forceCallback = std::move(callback);
    if (impl_->forceCallback) {
        impl_->peer->setForceHook([this](ForceStage& stage) {
            ForceContextImpl context(*this, stage, [](World& w, Body b) -> BodyPeer& {
                if (b.world() != &w) throw Error("ForceContext: the body belongs to another world");
                return *w.slot(b.id(), "ForceContext").peer;
            });
            impl_->forceCallback(context);
        });
    } else {
        impl_->peer->setForceHook({});
    }
    refreshEffects();
}

void World::addListener(ContactListener* listener) {
    if (!listener) throw Error::invalid("World.addListener.listener", "null", "must not be null");
    if (std::find(impl_->listeners.begin(), impl_->listeners.end(), listener) == impl_->listeners.end())
        impl_->listeners.push_back(listener);
}

void World::removeListener(ContactListener* listener) {
    impl_->listeners.erase(std::remove(impl_->listeners.begin(), impl_->listeners.end(), listener), impl_->listeners.end());
}

void World::noteForcesUsed() {
    if (settings_.effects && !settings_.effects->has(Effect::UserForces))
        throw Error("Body.applyForce: the world's declared effects exclude \"userForces\"; add it to WorldSettings.effects");
    if (!impl_->forcesUsed) {
        impl_->forcesUsed = true;
        refreshEffects();
    }
}

}  // namespace anyphys
