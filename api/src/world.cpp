#include "anyphys/world.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "anyphys/backends.hpp"
#include "body_shapes.hpp"
#include "geometry/shape_bounds.hpp"
#include "anyphys/validation.hpp"
#include "world_impl.hpp"

namespace anyphys {
namespace {

/// The primitive shape types of a body's shape (a compound's children), each once.
std::set<ShapeType> primitiveTypes(const ShapeDef& shape) {
    if (shape.type != ShapeType::Compound) return {shape.type};
    std::set<ShapeType> out;
    for (const ShapeDef& child : shape.shapes) out.insert(child.type);
    return out;
}

/// The material name a piece of the body's shape uses: a compound child's own, else the body's.
const std::string& pieceMaterial(const BodyDef& def, const ShapeDef& piece) {
    return piece.material ? *piece.material : def.material;
}

/// Some piece of the body's shape is a sensor (the body's own flag, or a child's override).
bool hasTrigger(const BodyDef& def) {
    for (const ShapeDef* piece : shapePieces(def.shape))
        if (piece->isTrigger.value_or(def.isTrigger)) return true;
    return false;
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

// The body a force callback names: its slot index and peer in this world.
struct ForceTarget {
    std::uint32_t slot;
    BodyPeer& peer;
};

// The force callback's view: maps user handles to peers of this world.
class ForceContextImpl final : public ForceContext {
public:
    ForceContextImpl(World& world, detail::ForceSink& sink, ForceTarget (*resolve)(World&, Body))
        : world_(world), sink_(sink), resolve_(resolve) {}
    double time() const override { return sink_.time(); }
    BodyState state(Body body) const override;
    void addForce(Body body, const Vec3& force) override {
        detail::requireFinite("ForceContext.addForce.force", force);
        requireWithinCeiling(body, "ForceContext.addForce.force", force, false);
        Vec3 f = force;
        if (world_.settings().planar) f.z() = 0.0;  // the plane holds the body (see Body::applyForce)
        const ForceTarget target = resolve_(world_, body);
        sink_.addForce(target.slot, target.peer, f);
    }
    void addTorque(Body body, const Vec3& torque) override {
        detail::requireFinite("ForceContext.addTorque.torque", torque);
        requireWithinCeiling(body, "ForceContext.addTorque.torque", torque, true);
        Vec3 t = torque;
        if (world_.settings().planar) t.x() = t.y() = 0.0;
        const ForceTarget target = resolve_(world_, body);
        sink_.addTorque(target.slot, target.peer, t);
    }

private:
    // A force or torque that would change the body's speed or spin by more than the world's
    // ceiling within one step is absurd: refused like one given to Body::applyForce, before an
    // engine integrates it (a torque is bounded about the body's weakest principal axis).
    void requireWithinCeiling(const Body& body, const char* field, const Vec3& value, bool torque) const {
        if (value.isZero(0) || body.type() != BodyType::Dynamic) return;
        const MassProperties m = body.massProperties();
        const double dt = world_.settings().timeStep;
        const double change = value.stableNorm() / (torque ? m.inertia.minCoeff() : m.mass) * dt;
        const double ceiling = torque ? world_.settings().maxAngularSpeed : world_.settings().maxSpeed;
        detail::requirePushWithinCeiling(field, value, change, torque ? detail::PushedMotion::Spin : detail::PushedMotion::Speed,
                                         true, ceiling);
    }

    World& world_;
    detail::ForceSink& sink_;
    ForceTarget (*resolve_)(World&, Body);
};

// ForceEvaluation::PerStage: the backend's stage, with the integrator's intermediate states.
class StageForces final : public detail::ForceSink {
public:
    explicit StageForces(ForceStage& stage) : stage_(stage) {}
    double time() const override { return stage_.time(); }
    BodyState state(const BodyPeer& peer) const override { return stage_.state(peer); }
    void addForce(std::uint32_t, BodyPeer& peer, const Vec3& force) override { stage_.addForce(peer, force); }
    void addTorque(std::uint32_t, BodyPeer& peer, const Vec3& torque) override { stage_.addTorque(peer, torque); }

private:
    ForceStage& stage_;
};

// ForceEvaluation::PerStep: the step-start states; forces are summed per slot, in call order, and
// handed over only once the whole evaluation returned (World::holdStepForces).
class StepStartForces final : public detail::ForceSink {
public:
    StepStartForces(double time, std::vector<detail::HeldForce>& held, std::vector<std::uint32_t>& touched)
        : time_(time), held_(held), touched_(touched) {}
    double time() const override { return time_; }
    BodyState state(const BodyPeer& peer) const override { return peer.state(); }
    void addForce(std::uint32_t slot, BodyPeer&, const Vec3& force) override { entry(slot).force += force; }
    void addTorque(std::uint32_t slot, BodyPeer&, const Vec3& torque) override { entry(slot).torque += torque; }

private:
    detail::HeldForce& entry(std::uint32_t slot) {
        detail::HeldForce& h = held_[slot];
        if (!h.touched) {
            h.touched = true;
            touched_.push_back(slot);
        }
        return h;
    }

    double time_;
    std::vector<detail::HeldForce>& held_;
    std::vector<std::uint32_t>& touched_;
};

}  // namespace

BodyState ForceContextImpl::state(Body body) const {
    // The evaluation's state is the peer frame's: convert to the body origin like Body::state().
    BodyPeer& peer = resolve_(world_, body).peer;
    BodyState s = sink_.state(peer);
    const BodyState current = peer.state();
    const BodyState user = body.state();
    // Offset of the peer frame from the body origin is fixed in the body: reuse it.
    const Quat peerToUser = current.orientation.conjugate() * user.orientation;
    const Vec3 originOffset = current.orientation.conjugate() * (user.position - current.position);
    s.position += s.orientation * originOffset;
    s.orientation = (s.orientation * peerToUser).normalized();
    return s;
}

World::World(const WorldSettings& settings, MaterialLibrary materials)
    : link_(std::make_shared<detail::WorldLink>(detail::WorldLink{this})),
      settings_(settings),
      materials_(std::move(materials)),
      impl_(std::make_unique<Impl>()) {
    validate(settings_, "WorldSettings");
    impl_->backend = &findBackend(settings_.backend);
    const Capabilities& caps = impl_->backend->capabilities;
    if (caps.dimensions == 2 && !settings_.planar)
        throw Error::invalid("WorldSettings.planar", "false",
                             "must be true on backend \"" + settings_.backend +
                                 "\", which simulates planar worlds only (bodies in the XY plane, rotating about Z)",
                             ErrorKind::Unsupported);
    const Effects requested = settings_.effects.value_or(Effects::none());
    const auto missing = missingCapabilities(caps, settings_, requested);
    if (!missing.empty()) {
        const std::string what = "backend \"" + settings_.backend + "\" does not support: " + detail::commaList(missing);
        if (settings_.capabilityPolicy == CapabilityPolicy::Strict)
            throw Error(ErrorKind::Unsupported, "WorldSettings",
                        "WorldSettings: " + what + " (capabilityPolicy strict; choose lenient to run without them)");
        warn("WorldSettings: " + what + "; running without them");
    }
    checkBackendOptions(caps, settings_);
    // Unset solver knobs take the backend's defaults here, once: the peer reads plain values and
    // settings() shows what runs.
    settings_ = withBackendDefaults(settings_, caps);
    impl_->peer = impl_->backend->createWorld(settings_);
    TaskSystem* tasks = settings_.taskSystem;
    if (!tasks && settings_.workers > 1 && caps.parameters.contains("settings.workers")) {
        impl_->pool = std::make_unique<ThreadPool>(settings_.workers);
        tasks = impl_->pool.get();
    }
    if (tasks) impl_->peer->setTaskSystem(tasks);
    impl_->asleep = [this](BodyId id) {
        if (!isValid(id)) return false;
        const Slot& s = impl_->slots[id.index];
        return s.def.type != BodyType::Static && !s.peer->isAwake();
    };
    impl_->stillTouching = [this](BodyId a, BodyId b, std::vector<TouchingRange>& touching) {
        return stillTouching(a, b, touching);
    };
    impl_->peer->setMaterialTable(buildMaterialTable());
    refreshEffects();
}

MaterialTable World::buildMaterialTable() {
    std::vector<std::string> names{std::string(MaterialLibrary::kDefaultName)};
    for (const std::string& n : materials_.names()) names.push_back(n);
    impl_->materialIndex.clear();
    for (std::uint32_t i = 0; i < names.size(); ++i) impl_->materialIndex[names[i]] = i;
    MaterialTable table;
    table.count = names.size();
    table.values.resize(names.size() * names.size());
    impl_->anyFriction = impl_->anyRestitution = false;
    for (std::size_t a = 0; a < names.size(); ++a)
        for (std::size_t b = 0; b < names.size(); ++b) {
            const MixedMaterial m = materials_.resolve(names[a], names[b]);
            table.values[a * names.size() + b] = {m.friction, m.restitution};
            impl_->anyFriction = impl_->anyFriction || m.friction > 0;
            impl_->anyRestitution = impl_->anyRestitution || m.restitution > 0;
        }
    return table;
}

World::~World() {
    // Handles that outlive the world find it gone (StaleHandle) instead of reading freed memory.
    link_->world = nullptr;
}

void World::warn(const std::string& message) {
    if (!impl_->warned.insert(message).second) return;  // each warning once
    impl_->warningLog.push_back(message);
    if (impl_->warningHandler)
        impl_->warningHandler(message);
    else
        std::cerr << "anyphys warning: " << message << '\n';
}

void World::setWarningHandler(WarningHandler handler) { impl_->warningHandler = std::move(handler); }

const std::vector<std::string>& World::warnings() const { return impl_->warningLog; }

void* World::nativeObject(const std::type_info& pointerType) {
    // The backend peer itself, for in-tree code only (WorldPeer is not installed): the benchmark
    // that times a world's step against its bare peer (bench/effects_cost.cpp).
    if (pointerType == typeid(WorldPeer*)) return impl_->peer.get();
    return impl_->peer->nativeObject(pointerType);
}

void World::refreshEffects() {
    Effects wanted;
    if (settings_.effects) {
        wanted = *settings_.effects;
    } else {
        if (!settings_.gravity.isZero(0) && impl_->gravityBodies > 0) wanted.add(Effect::Gravity);
        if (impl_->dampedBodies > 0) wanted.add(Effect::Damping);
        if (impl_->gyroscopicBodies > 0) wanted.add(Effect::Gyroscopic);
        if (impl_->forcesUsed || impl_->forceCallback) wanted.add(Effect::UserForces);
        if (impl_->simulatedJoints > 0) wanted.add(Effect::Joints);
        wanted = wanted | impl_->fieldEffects | impl_->particleEffects;
        // Contacts need two bodies, one of which responds (or a sensor and something moving).
        const Impl& i = *impl_;
        const bool contacts = i.liveBodies >= 2 && (i.dynamicBodies > 0 || (i.triggerBodies > 0 && i.movingBodies > 0));
        if (contacts) {
            wanted.add(Effect::Contacts).add(Effect::ContinuousCollision).add(Effect::Events);
            if (i.anyFriction) wanted.add(Effect::Friction);
            if (i.anyRestitution) wanted.add(Effect::Restitution);
            if (i.sleepyBodies > 0) wanted.add(Effect::Sleeping);
        }
    }
    const Effects active = wanted & impl_->backend->capabilities.effects;
    if (active == activeEffects_ && impl_->peer) return;
    activeEffects_ = active;
    // Buoyancy, drag and wind reach the backend as forces from the force hook: its user-forces
    // stage runs while one of them does.
    Effects peerEffects = active;
    if (!(active & kFieldForceEffects).empty() && impl_->backend->capabilities.effects.has(Effect::UserForces))
        peerEffects.add(Effect::UserForces);
    impl_->peerEffects = peerEffects;
    impl_->peer->setEffects(peerEffects);
}

// ---- bodies ---------------------------------------------------------------------------------

namespace {
// A dynamic body's resolved mass and principal inertia must lie in [kMinMass, kMaxMass]: a 1e-300 kg
// body's inertia underflows to 0 and its principal axes to NaN (Box2D aborted on it), a 1e308 kg
// one's overflows. Names the def field that made it: mass, inertia, else density.
void requireUsableMass(const BodyDef& def, const ResolvedShapes& resolved, double density) {
    const MassProperties& m = resolved.mass;
    const auto usable = [](double v) { return v >= kMinMass && v <= kMaxMass; };
    if (usable(m.mass) && usable(m.inertia.x()) && usable(m.inertia.y()) && usable(m.inertia.z()) &&
        resolved.peerFrame.position.allFinite() && resolved.peerFrame.orientation.coeffs().allFinite())
        return;
    const char* field = def.mass ? "BodyDef.mass" : def.inertia ? "BodyDef.inertia" : "BodyDef.density";
    std::ostringstream os;
    os.precision(6);
    os << "gives a mass of " << m.mass << " kg and principal inertia [" << m.inertia.x() << ", " << m.inertia.y() << ", "
       << m.inertia.z() << "] kg m^2 for this shape; each must be in [" << kMinMass << ", " << kMaxMass
       << "] (anyphys::kMinMass, kMaxMass)";
    const double value = def.mass ? *def.mass : def.inertia ? def.inertia->minCoeff() : density;
    throw Error::invalid(field, value, os.str());
}

// Each principal inertia must be at least kMinInertiaRatio x mass x the squared reach of the
// shapes about that axis (bounded by their boxes in the principal frame).
void requireResolvableInertia(const BodyDef& def, const ResolvedShapes& resolved) {
    Vec3 reach = Vec3::Zero();  // along each principal axis, the farthest any shape extends
    for (const PeerShape& shape : resolved.shapes)
        if (const auto box = shapeBounds(shape.def, shape.local))
            reach = reach.cwiseMax(box->min.cwiseAbs()).cwiseMax(box->max.cwiseAbs());
    const Vec3 r2 = reach.cwiseAbs2();
    const MassProperties& m = resolved.mass;
    const Vec3 least = kMinInertiaRatio * m.mass * Vec3(r2.y() + r2.z(), r2.x() + r2.z(), r2.x() + r2.y());
    if ((m.inertia.array() >= least.array()).all()) return;
    const auto list = [](const Vec3& v) {
        std::ostringstream os;
        os.precision(6);
        os << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
        return os.str();
    };
    std::ostringstream rule;
    rule.precision(6);
    rule << "each principal inertia must be at least anyphys::kMinInertiaRatio (" << kMinInertiaRatio
         << ") x mass x its squared reach about that axis, " << list(least) << " kg m^2 for " << m.mass
         << " kg reaching " << list(reach) << " m from its centre of mass (lighter in rotation, a solver in "
         << "double precision loses the body's translation)";
    // Given inertia is the user's; otherwise the shapes' densities made it (a compound's).
    throw Error::invalid(def.inertia ? "BodyDef.inertia" : "BodyDef.shape", list(m.inertia), rule.str());
}

// What the backend lacks to hold a dynamic body of `mass` kg up (Capabilities::lightestBody,
// heaviestBody), or "" when it holds it.
std::string massOutsideRange(const Capabilities& caps, double mass) {
    const bool light = caps.lightestBody > 0.0 && mass < caps.lightestBody;
    const bool heavy = caps.heaviestBody > 0.0 && mass > caps.heaviestBody;
    if (!light && !heavy) return "";
    std::ostringstream os;
    os.precision(6);
    os << "a body of " << mass << " kg (it holds " << (light ? "no body under " : "no body over ")
       << (light ? caps.lightestBody : caps.heaviestBody) << " kg up on its contacts: capabilities "
       << (light ? "lightestBody" : "heaviestBody") << ")";
    return os.str();
}
}  // namespace

Body World::createBody(const BodyDef& input) {
    impl_->refuseWhileStepping("World.createBody");
    impl_->refuseWhileDrawing("World.createBody");
    validate(input, "BodyDef");
    validateLimits(input, settings_, "BodyDef", "WorldSettings");
    if (settings_.planar) validatePlanar(input, "BodyDef");
    requireKnownMaterials(input);

    const Capabilities& caps = impl_->backend->capabilities;
    std::vector<std::string> missing;
    // Each names the field and what the backend has instead, so the message says what to change.
    const auto offered = [](const auto& set) {
        std::vector<std::string> names;
        for (const auto& item : set) names.emplace_back(toString(item));
        return detail::commaList(names);
    };
    if (!caps.shapes.count(input.shape.type))
        missing.push_back("shape type " + std::string(toString(input.shape.type)) + " (BodyDef.shape.type; it has " +
                          offered(caps.shapes) + ")");
    if (!caps.bodyTypes.count(input.type))
        missing.push_back("body type " + std::string(toString(input.type)) + " (BodyDef.type; it has " + offered(caps.bodyTypes) + ")");
    if (input.type == BodyType::Dynamic && !caps.gyroscopicModes.count(input.gyroscopic))
        missing.push_back("gyroscopic mode " + std::string(toString(input.gyroscopic)) + " (BodyDef.gyroscopic; it has " +
                          offered(caps.gyroscopicModes) + ")");
    const BodyDef defaults;
    const auto checkParameter = [&](bool used, const char* parameter) {
        if (used && !caps.parameters.count(parameter)) missing.push_back(parameter);
    };
    checkParameter(input.linearDamping != defaults.linearDamping, "body.linearDamping");
    checkParameter(input.angularDamping != defaults.angularDamping, "body.angularDamping");
    checkParameter(input.gravityScale != defaults.gravityScale, "body.gravityScale");
    for (const ShapeDef& child : input.shape.shapes) {
        checkParameter(child.material.has_value(), "body.shape.shapes.material");
        checkParameter(child.isTrigger.has_value(), "body.shape.shapes.isTrigger");
        checkParameter(child.layer.has_value(), "body.shape.shapes.layer");
        checkParameter(child.mask.has_value(), "body.shape.shapes.mask");
    }
    for (ShapeType mine : primitiveTypes(input.shape))
        for (const auto& [present, count] : impl_->shapeBodies)
            if (count > 0 && caps.missingShapePairs.contains(std::minmax(mine, present)))
                missing.push_back("collision between " + std::string(toString(std::min(mine, present))) + " and " +
                                  std::string(toString(std::max(mine, present))) + " shapes");
    if (!missing.empty()) {
        const std::string what = "backend \"" + settings_.backend + "\" does not support: " + detail::commaList(missing);
        if (settings_.capabilityPolicy == CapabilityPolicy::Strict) throw Error(ErrorKind::Unsupported, "BodyDef", "BodyDef: " + what);
        warn("BodyDef: " + what + "; ignored");
    }

    BodyDef def = input;
    def.orientation.normalize();
    const double density = def.density.value_or(materials_.get(def.material).density);
    ResolvedShapes resolved = resolveShapes(def, pieceDensities(def));
    if (def.type == BodyType::Dynamic) {
        requireUsableMass(def, resolved, density);
        requireResolvableInertia(def, resolved);
        const std::string outside = massOutsideRange(caps, resolved.mass.mass);
        if (!outside.empty()) {
            const std::string field = def.mass ? "BodyDef.mass" : "BodyDef.density";
            const std::string what = field + ": backend \"" + settings_.backend + "\" does not support " + outside;
            if (settings_.capabilityPolicy == CapabilityPolicy::Strict) throw Error(ErrorKind::Unsupported, field, what);
            warn(what + "; simulated anyway");
        }
    }
    resolveSurfaces(def, resolved.shapes);
    BodyPeerDef peerDef;
    peerDef.def = def;
    const Transform peerPose{def.position + def.orientation * resolved.peerFrame.position,
                             def.orientation * resolved.peerFrame.orientation};
    peerDef.def.position = peerPose.position;
    peerDef.def.orientation = peerPose.orientation;
    peerDef.mass = resolved.mass;
    peerDef.mass.centerOfMass = Vec3::Zero();
    peerDef.mass.principalAxes = Quat::Identity();
    peerDef.shapes = std::move(resolved.shapes);
    peerDef.material = impl_->materialIndex.at(def.material);

    const bool reuse = !impl_->freeSlots.empty();
    const std::uint32_t index = reuse ? impl_->freeSlots.back() : static_cast<std::uint32_t>(impl_->slots.size());
    const std::uint32_t generation = reuse ? impl_->slots[index].generation : 1;
    peerDef.userData = packId(BodyId{index, generation});
    std::unique_ptr<BodyPeer> peer = impl_->peer->createBody(peerDef);  // may throw: nothing changed yet
    if (reuse)
        impl_->freeSlots.pop_back();
    else
        impl_->slots.emplace_back();
    Slot& s = impl_->slots[index];
    s.peer = std::move(peer);
    s.def = def;
    s.mass = resolved.mass;
    s.peerFrame = resolved.peerFrame;
    s.checkedPose = peerPose;
    s.frozen = false;
    countBody(s.def, +1);
    refreshEffects();
    return Body(this, BodyId{index, s.generation});
}

void World::requireKnownMaterials(const BodyDef& def) const {
    const auto require = [&](const std::string& name, const std::string& field) {
        if (!materials_.contains(name))
            throw Error::invalid(field, "\"" + name + "\"",
                                 "must name a material of the world's library (" + detail::commaList(materials_.names()) + ")");
    };
    require(def.material, "BodyDef.material");
    for (std::size_t i = 0; i < def.shape.shapes.size(); ++i)
        if (def.shape.shapes[i].material)
            require(*def.shape.shapes[i].material, "BodyDef.shape.shapes[" + std::to_string(i) + "].material");
}

std::vector<double> World::pieceDensities(const BodyDef& def) const {
    // A piece's own density, else the body's, else its material's: a child that names its own
    // material (an ice bumper) weighs as that material unless a density is given.
    std::vector<double> densities;
    for (const ShapeDef* piece : shapePieces(def.shape))
        densities.push_back(piece->density.value_or(def.density.value_or(materials_.get(pieceMaterial(def, *piece)).density)));
    return densities;
}

void World::resolveSurfaces(const BodyDef& def, std::vector<PeerShape>& shapes) const {
    const std::vector<const ShapeDef*> pieces = shapePieces(def.shape);
    for (std::size_t i = 0; i < shapes.size(); ++i) {  // flattenShape keeps the pieces' order
        const ShapeDef& piece = *pieces[i];
        shapes[i].material = impl_->materialIndex.at(pieceMaterial(def, piece));
        shapes[i].layer = piece.layer.value_or(def.layer);
        shapes[i].mask = piece.mask.value_or(def.mask);
        shapes[i].isTrigger = piece.isTrigger.value_or(def.isTrigger);
    }
}

void World::destroyBody(Body body) {
    impl_->refuseWhileStepping("World.destroyBody");
    impl_->refuseWhileDrawing("World.destroyBody");
    if (!body.world() && !body.id().isNull())
        throw Error(ErrorKind::StaleHandle, "", "World.destroyBody: stale body handle: the body's world was destroyed");
    if (body.world() && body.world() != this)
        throw Error(ErrorKind::InvalidState, "", "World.destroyBody: the body belongs to another world");
    Slot& s = slot(body.id(), "World.destroyBody");
    // Its joints first: a joint never outlives one of its bodies.
    while (!s.joints.empty()) releaseJoint(s.joints.back());
    for (const ContactEvent& event : impl_->tracker.removeBody(body.id()))
        for (ContactListener* l : impl_->listeners)
            event.trigger ? l->onTriggerExit(event) : l->onCollisionExit(event);
    impl_->peer->destroyBody(*s.peer);
    s.peer.reset();
    s.fieldBody.reset();
    s.frozen = false;
    ++s.generation;
    impl_->freeSlots.push_back(body.id().index);
    countBody(s.def, -1);
    refreshEffects();
}

void World::countBody(const BodyDef& d, int delta) {
    Impl& i = *impl_;
    const auto count = [delta](std::size_t& counter, bool applies) {
        if (applies) counter += delta;
    };
    count(i.liveBodies, true);
    count(i.gravityBodies, needsGravity(d));
    count(i.dampedBodies, needsDamping(d));
    count(i.gyroscopicBodies, needsGyroscopic(d));
    count(i.dynamicBodies, d.type == BodyType::Dynamic);
    count(i.movingBodies, d.type != BodyType::Static);
    count(i.triggerBodies, hasTrigger(d));
    count(i.sleepyBodies, d.type == BodyType::Dynamic && d.allowSleep);
    for (ShapeType type : primitiveTypes(d.shape)) i.shapeBodies[type] += delta;
}

World::Slot& World::slot(BodyId id, const char* operation) {
    return const_cast<Slot&>(static_cast<const World*>(this)->slot(id, operation));
}

const World::Slot& World::slot(BodyId id, const char* operation) const {
    if (id.isNull()) throw Error(ErrorKind::StaleHandle, "", std::string(operation) + ": null body handle");
    if (id.index >= impl_->slots.size() || !impl_->slots[id.index].peer ||
        impl_->slots[id.index].generation != id.generation)
        throw Error(ErrorKind::StaleHandle, "", std::string(operation) + ": stale body handle (index " + std::to_string(id.index) +
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
    impl_->refuseWhileStepping("World.step");
    impl_->refuseWhileDrawing("World.step");
    detail::requireTimeStep("World.step.dt", dt);
    if (impl_->divergedUnresolved) refuseStillDiverged();
    {
        SteppingGuard guard(impl_->stepping);
        if (activeEffects_.has(Effect::Explosion)) fireExplosions(dt);
        if (impl_->layerForces && impl_->peerEffects.has(Effect::UserForces)) holdStepForces();
        impl_->peer->setImpulsesRead(impl_->eventsRead || !impl_->listeners.empty());
        impl_->peer->step(time_, dt);
        if (activeEffects_.has(Effect::Fluid) || activeEffects_.has(Effect::Cloth)) stepParticles(dt);
    }
    // Compensated summation keeps time == n * dt to the last bit over long runs.
    const double y = dt - timeCompensation_;
    const double t = time_ + y;
    timeCompensation_ = (t - time_) - y;
    time_ = t;
    ++stepCount_;
    if (!impl_->frozenSlots.empty()) holdFrozen();
    checkDivergence(dt);  // may throw Diverged: before events, so no listener sees a diverged state
    if (!impl_->breakableJoints.empty() || !impl_->lastJointEvents.empty()) breakJoints();
    if (activeEffects_.has(Effect::Events)) dispatchEvents();
    if (!impl_->lastJointEvents.empty()) {
        // A copy: a listener may step the world, which rewrites the list.
        const std::vector<JointEvent> broken = impl_->lastJointEvents;
        deliverJointBreaks(broken);
    }
}

const std::vector<DivergedBody>& World::lastDiverged() const { return impl_->lastDiverged; }

namespace {

// Why a body state has diverged, or nullptr when `limits` admit it.
const char* divergence(const BodyState& s, const MotionLimits& limits) {
    if (limits.admit(s)) return nullptr;
    if (!(s.linearVelocity.allFinite() && s.angularVelocity.allFinite() && s.position.allFinite() &&
          s.orientation.coeffs().allFinite()))
        return "non-finite state";
    if (!(s.linearVelocity.squaredNorm() <= limits.maxSpeed2)) return "linearVelocity";
    if (!(s.angularVelocity.squaredNorm() <= limits.maxAngularSpeed2)) return "angularVelocity";
    return "position";
}

std::string number(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

}  // namespace

MotionLimits World::motionLimits() const {
    return {settings_.maxSpeed * settings_.maxSpeed, settings_.maxAngularSpeed * settings_.maxAngularSpeed, kMaxCoordinate};
}

void World::checkDivergence(double dt) {
    (void)dt;
    Impl& i = *impl_;
    i.lastDiverged.clear();
    // Every dynamic and kinematic body asleep: no state changed since the last check.
    if (!i.peer->hasAwakeBodies()) return;
    const MotionLimits limits = motionLimits();
    std::string firstField;
    const auto noteDiverged = [&](std::uint32_t k, const BodyState& state, const char* what) {
        Slot& s = i.slots[k];
        std::string reason;
        const std::string who = s.def.name.empty() ? "body #" + std::to_string(k) : "body \"" + s.def.name + "\"";
        std::string field = who + ".";
        if (what == std::string_view("non-finite state")) {
            reason = "non-finite state (position " + formatVec3(state.position) + ", linearVelocity " +
                     formatVec3(state.linearVelocity) + ", angularVelocity " + formatVec3(state.angularVelocity) + ")";
            field += !state.position.allFinite() ? "position" : !state.linearVelocity.allFinite() ? "linearVelocity"
                     : !state.angularVelocity.allFinite() ? "angularVelocity" : "orientation";
        } else if (what == std::string_view("linearVelocity")) {
            reason = "speed " + number(state.linearVelocity.stableNorm()) + " m/s > WorldSettings.maxSpeed " + number(settings_.maxSpeed);
            field += what;
        } else if (what == std::string_view("angularVelocity")) {
            reason = "angular speed " + number(state.angularVelocity.stableNorm()) + " rad/s > WorldSettings.maxAngularSpeed " +
                     number(settings_.maxAngularSpeed);
            field += what;
        } else {
            reason = "position " + formatVec3(state.position) + " beyond +-" + number(kMaxCoordinate) + " m (anyphys::kMaxCoordinate)";
            field += what;
        }
        if (firstField.empty()) firstField = field;
        i.lastDiverged.push_back({Body(this, BodyId{k, s.generation}), s.def.name, reason});
    };
    if (settings_.divergencePolicy == DivergencePolicy::Freeze) {
        // A body that diverges is held at its last sound pose: every pose is read and kept.
        for (std::uint32_t k = 0; k < i.slots.size(); ++k) {
            Slot& s = i.slots[k];
            if (!s.peer || s.def.type == BodyType::Static || s.frozen) continue;
            const BodyState state = s.peer->state();
            if (const char* what = divergence(state, limits))
                noteDiverged(k, state, what);
            else
                s.checkedPose = {state.position, state.orientation};
        }
    } else {
        // Throw keeps no pose: the peer scans its own arrays, and only what it finds is read here,
        // in slot order (the keys lead with the slot index).
        i.unsound.clear();
        i.peer->findUnsound(limits, i.unsound);
        std::sort(i.unsound.begin(), i.unsound.end());
        for (const std::uint64_t key : i.unsound) {
            const std::uint32_t k = unpackId(key).index;
            const BodyState state = i.slots[k].peer->state();
            if (const char* what = divergence(state, limits)) noteDiverged(k, state, what);
        }
    }
    if (i.lastDiverged.empty()) return;
    const std::string when = " at step " + std::to_string(stepCount_) + " (t = " + number(time_) + " s)";
    if (settings_.divergencePolicy == DivergencePolicy::Throw) {
        std::string message = "World.step: diverged" + when + ":";
        constexpr std::size_t kNamed = 8;  // one line, even for a pile that exploded
        for (std::size_t n = 0; n < i.lastDiverged.size() && n < kNamed; ++n) {
            const DivergedBody& d = i.lastDiverged[n];
            message += (n ? "; " : " ") + (d.name.empty() ? "body #" + std::to_string(d.body.id().index) : "body \"" + d.name + "\"") +
                       " " + d.reason;
        }
        if (i.lastDiverged.size() > kNamed) message += "; and " + std::to_string(i.lastDiverged.size() - kNamed) + " more";
        message += " (WorldSettings.divergencePolicy throw; freeze holds such bodies still and keeps stepping)";
        i.divergedUnresolved = true;
        throw Error(ErrorKind::Diverged, firstField, message);
    }
    for (const DivergedBody& d : i.lastDiverged) {
        Slot& s = i.slots[d.body.id().index];
        s.frozen = true;
        i.frozenSlots.push_back(d.body.id().index);
        warn("World.step: " + (d.name.empty() ? "body #" + std::to_string(d.body.id().index) : "body \"" + d.name + "\"") +
             " diverged" + when + ": " + d.reason + "; frozen at its last checked pose (WorldSettings.divergencePolicy freeze)");
    }
    holdFrozen();
}

// After a Diverged throw the engine still holds the diverged states, for the caller to inspect
// (docs/errors.md). Stepping on would hand an engine non-finite or out-of-world states again, the
// kind it aborts on (ODE's hash grid, its normalisations). So the next step goes ahead only once
// each of those bodies is destroyed or set right; until then it throws and the world stays as it is.
void World::refuseStillDiverged() {
    Impl& i = *impl_;
    const MotionLimits limits = motionLimits();
    for (const DivergedBody& d : i.lastDiverged) {
        const BodyId id = d.body.id();
        if (id.index >= i.slots.size()) continue;
        const Slot& s = i.slots[id.index];
        if (!s.peer || s.generation != id.generation) continue;  // destroyed since
        const char* what = divergence(s.peer->state(), limits);
        if (!what) continue;
        const std::string who = d.name.empty() ? "body #" + std::to_string(id.index) : "body \"" + d.name + "\"";
        const std::string quantity = what == std::string_view("non-finite state") ? "state" : what;
        throw Error(ErrorKind::Diverged, who + "." + quantity,
                    "World.step: " + who + " is still diverged (" + d.reason +
                        "); destroy it, or set it right (setTransform, setLinearVelocity, setAngularVelocity), before stepping on");
    }
    i.divergedUnresolved = false;
}

void World::holdFrozen() {
    Impl& i = *impl_;
    std::erase_if(i.frozenSlots, [&](std::uint32_t k) { return !i.slots[k].peer || !i.slots[k].frozen; });
    for (std::uint32_t k : i.frozenSlots) {
        Slot& s = i.slots[k];
        s.peer->setTransform(s.checkedPose.position, s.checkedPose.orientation);
        s.peer->setLinearVelocity(Vec3::Zero());
        s.peer->setAngularVelocity(Vec3::Zero());
    }
}

void World::dispatchEvents() {
    Impl& i = *impl_;
    // A listener of the last step's events stepped the world: its loop still reads them.
    if (i.dispatching > 0) i.retiredEvents.push_back(std::move(i.lastEvents));
    i.eventsUnwritten = false;  // a diff not read by now never will be
    if (!i.peer->hasAwakeBodies()) {  // every contact has a sleeping body: none begins, stays or ends
        i.tracker.recycle(i.lastEvents);
        return;
    }
    i.contacts.clear();
    i.peer->reportContacts(i.contacts);
    // The layer decides what touching means, identically for every backend: a collision pair
    // touches when some point is closer than linearSlop, or (where the backend reports impulses)
    // pushed the bodies apart: an engine may turn a fast body around on a speculative contact
    // before the surfaces meet, and a contact that changes a velocity is a contact. A trigger
    // pair touches when it overlaps. A collision pair that touched ends only once its shapes are
    // farther apart than kExitSlops linearSlops (stillTouching): a gap that wanders about the
    // linearSlop boundary (Box2D's resting piles sit there) does not blink in and out.
    const bool impulses = i.backend->capabilities.contactImpulses;
    // What the events carry: none when settings.contactImpulses is false, or when the peer
    // skipped measuring them because nobody read events before this step (ODE).
    i.eventImpulses = impulses && settings_.contactImpulses && i.peer->measuredImpulses();
    const double slop = settings_.linearSlop, exitReach = kExitSlops * slop;
    i.touching.clear();
    i.nearListed.clear();
    for (std::uint32_t n = 0; n < i.contacts.pairs.size(); ++n) {
        const ContactReport::Pair& c = i.contacts.pairs[n];
        // A pair whose points the peer deferred carried an impulse: it touches (and is not read).
        bool touches = c.trigger || c.pointsDeferred, near = false;
        for (std::uint32_t k = c.firstPoint; k < c.firstPoint + c.pointCount && !touches; ++k) {
            const ContactPoint& p = i.contacts.points[k];
            touches = p.depth > -slop || (impulses && p.normalImpulse > 0.0);
            near = near || p.depth > -exitReach;
        }
        if (!touches) {
            if (near) i.nearListed.push_back({std::min(c.bodyA, c.bodyB), std::max(c.bodyA, c.bodyB), n});
            continue;
        }
        const BodyId a = unpackId(c.bodyA), b = unpackId(c.bodyB);
        const bool asleep = i.contacts.sleepKnown ? c.asleep : i.asleep(a) || i.asleep(b);
        i.touching.push_back({a, b, c.trigger, i.eventImpulses, asleep, c.normal, c.firstPoint, c.pointCount});
    }
    // Events without impulses (settings.contactImpulses false) carry none, whatever the engine
    // measured; the impulses above still decided what touches, so the events are the same.
    i.impulsesCleared = !settings_.contactImpulses;
    if (i.impulsesCleared)  // deferred points too, once written (Impl::writeDeferredPoints)
        for (ContactPoint& p : i.contacts.points) p.normalImpulse = 0.0;
    std::sort(i.nearListed.begin(), i.nearListed.end());  // for stillTouching's search; first listing first
    i.tracker.diff(i.touching, i.asleep, i.stillTouching);
    i.eventsUnwritten = true;
    if (!i.listeners.empty())
        deliverEvents();
    else if (i.eventsRead)
        i.writtenEvents();
}

bool World::stillTouching(BodyId a, BodyId b, std::vector<TouchingRange>& touching) {
    Impl& i = *impl_;
    if (!isValid(a) || !isValid(b)) return false;
    const double reach = kExitSlops * settings_.linearSlop;
    // Listed by the engine a little apart, within the exit band (dispatchEvents).
    const std::uint64_t low = std::min(packId(a), packId(b)), high = std::max(packId(a), packId(b));
    const auto listed = std::lower_bound(i.nearListed.begin(), i.nearListed.end(), Impl::NearListed{low, high, 0});
    if (listed != i.nearListed.end() && listed->low == low && listed->high == high) {
        const ContactReport::Pair& c = i.contacts.pairs[listed->pair];
        touching.push_back({unpackId(c.bodyA), unpackId(c.bodyB), false, i.eventImpulses, false, c.normal, c.firstPoint,
                            c.pointCount});
        return true;
    }
    // Not listed: the peer may find it (ODE reports only overlapping shapes).
    const std::size_t pair = i.contacts.pairs.size();
    if (!i.peer->reportNearPair(*i.slots[a.index].peer, *i.slots[b.index].peer, reach, i.contacts)) return false;
    const ContactReport::Pair& c = i.contacts.pairs[pair];
    bool touches = false;
    for (std::uint32_t k = c.firstPoint; k < c.firstPoint + c.pointCount && !touches; ++k)
        touches = i.contacts.points[k].depth > -reach;
    if (touches)
        touching.push_back({a, b, false, i.eventImpulses, false, c.normal, c.firstPoint, c.pointCount});
    i.contacts.pairs.resize(pair);  // the listing stays the peer's own (its points are kept)
    return touches;
}

void World::deliverEvents() {
    Impl& i = *impl_;
    // Listeners may create and destroy bodies, add and remove listeners, even step: the events
    // are read from their own storage (a step inside a callback retires it rather than reuse it),
    // and go to the listeners registered when delivery began.
    const std::vector<ContactEvent>& written = i.writtenEvents();
    const ContactEvent* const events = written.data();
    const std::size_t count = written.size();
    std::vector<ContactListener*> nestedListeners;
    std::vector<ContactListener*>& listeners = i.dispatching == 0 ? i.listenersNow : nestedListeners;
    listeners.assign(i.listeners.begin(), i.listeners.end());
    struct Delivering {
        Impl& impl;
        explicit Delivering(Impl& in) : impl(in) { ++impl.dispatching; }
        ~Delivering() {
            if (--impl.dispatching > 0) return;
            for (std::vector<ContactEvent>& retired : impl.retiredEvents) impl.tracker.recycle(retired);
            impl.retiredEvents.clear();
        }
        Delivering(const Delivering&) = delete;
        Delivering& operator=(const Delivering&) = delete;
    } delivering(i);
    for (std::size_t k = 0; k < count; ++k) {
        const ContactEvent& e = events[k];
        // A body destroyed by an earlier callback already had its exits delivered.
        if (e.phase != ContactPhase::Exit && (!isValid(e.bodyA) || !isValid(e.bodyB))) continue;
        for (ContactListener* l : listeners) {
            if (e.trigger)
                e.phase == ContactPhase::Enter ? l->onTriggerEnter(e) : l->onTriggerExit(e);
            else if (e.phase == ContactPhase::Enter)
                l->onCollisionEnter(e);
            else if (e.phase == ContactPhase::Stay)
                l->onCollisionStay(e);
            else
                l->onCollisionExit(e);
        }
    }
}

const std::vector<ContactEvent>& World::lastEvents() const {
    impl_->eventsRead = true;
    return impl_->writtenEvents();
}

// ---- queries --------------------------------------------------------------------------------

namespace {
// m: longest ray handed to a peer. Everything a world holds lies within kMaxCoordinate of the
// origin (3.5e7 m corner to corner), so a longer ray finds nothing more, while 1e308 overflows
// inside an engine's ray code.
constexpr double kMaxRayLength = 1e8;

struct Ray {
    Vec3 direction;      // unit
    double maxDistance;  // clamped to kMaxRayLength
};

// Checks a ray and returns its unit direction. The direction is scaled by its largest component
// before normalising: the norm of (1e308, 1e308, 0) overflows to inf, and dividing by it gave a
// zero direction that ODE aborted on (found by tests/fuzz).
Ray validateRay(const Vec3& origin, const Vec3& direction, double maxDistance, const char* what) {
    const std::string w(what);
    detail::requireCoordinate(w + ".origin", origin);
    detail::requireFinite(w + ".direction", direction);
    const double scale = direction.cwiseAbs().maxCoeff();
    if (!(scale >= 1e-12)) throw Error::invalid(w + ".direction", formatVec3(direction), "must be non-zero (a component >= 1e-12)");
    detail::requireNonNegative(w + ".maxDistance", maxDistance);
    return {(direction / scale).normalized(), std::min(maxDistance, kMaxRayLength)};
}

// A planar world's queries stay in its plane, on every backend: a ray leaving it would see the
// bodies' depth on a 3D engine and nothing on a planar one.
void requireRayInPlane(const Vec3& origin, const Vec3& direction, const char* what) {
    const std::string w(what);
    const char* rule = "must lie in the XY plane (z = 0) in a planar world";
    if (std::abs(origin.z()) > detail::kPlanarTolerance) throw Error::invalid(w + ".origin", formatVec3(origin), rule);
    if (std::abs(direction.z()) > detail::kPlanarTolerance) throw Error::invalid(w + ".direction", formatVec3(direction), rule);
}

// Where a ray starts exactly on a surface the engines disagree: ODE and Box2D met it both ways,
// Bullet neither, native heading in only. Each ray therefore starts this far behind its origin,
// measured back along it: a surface through the origin is then met heading in (at distance 0
// once the distances are measured from the origin again) and, heading out, holds the ray's start
// inside its solid, which no backend hits. A millionth of the origin's largest coordinate (at
// least 1 micrometre), on every backend, so that "on a surface" means the same everywhere: ten
// times what Box2D's float rays need to start behind the surface (1e-7 relative did in the
// contract case, 3e-8 did not), 100 times what Bullet's convex cast needs to meet a surface it
// starts next to (1e-8 met it, 1e-9 did not).
double rayStartBehind(const Vec3& origin) { return 1e-6 * std::max(1.0, origin.cwiseAbs().maxCoeff()); }

}  // namespace

std::vector<PeerRayHit> detail::castFromOrigin(WorldPeer& peer, const Vec3& origin, const Vec3& direction, double maxDistance,
                                               bool closestOnly, std::uint32_t mask) {
    const double behind = rayStartBehind(origin);
    std::vector<PeerRayHit> hits = peer.raycast(origin - behind * direction, direction, maxDistance + behind, closestOnly, mask);
    for (PeerRayHit& h : hits) h.distance = std::max(0.0, h.distance - behind);
    return hits;
}

std::optional<RayHit> World::raycast(const Vec3& origin, const Vec3& direction, double maxDistance, std::uint32_t mask) {
    const Ray ray = validateRay(origin, direction, maxDistance, "World.raycast");
    if (settings_.planar) requireRayInPlane(origin, direction, "World.raycast");
    const auto hits = detail::castFromOrigin(*impl_->peer, origin, ray.direction, ray.maxDistance, true, mask);
    if (hits.empty()) return std::nullopt;
    const PeerRayHit& hit = hits.front();
    return RayHit{Body(this, unpackId(hit.body)), hit.point, hit.normal, hit.distance};
}

std::vector<RayHit> World::raycastAll(const Vec3& origin, const Vec3& direction, double maxDistance, std::uint32_t mask) {
    const Ray ray = validateRay(origin, direction, maxDistance, "World.raycastAll");
    if (settings_.planar) requireRayInPlane(origin, direction, "World.raycastAll");
    std::vector<RayHit> out;
    for (const PeerRayHit& h : detail::castFromOrigin(*impl_->peer, origin, ray.direction, ray.maxDistance, false, mask))
        out.push_back({Body(this, unpackId(h.body)), h.point, h.normal, h.distance});
    return out;
}

std::vector<Body> World::overlap(const ShapeDef& shape, const Transform& pose, std::uint32_t mask) {
    validate(shape, "World.overlap.shape");
    if (shape.type == ShapeType::Plane || shape.type == ShapeType::Mesh)
        throw Error::invalid("World.overlap.shape.type", toString(shape.type), "must be sphere, box, capsule, convex or compound");
    detail::requireCoordinate("World.overlap.pose.position", pose.position);
    // As setTransform: a zero or far from unit quaternion is a mistake (normalising a zero one
    // handed NaN to the engines).
    if (!pose.orientation.coeffs().allFinite() || std::abs(pose.orientation.norm() - 1.0) > kUnitQuaternionTolerance)
        throw Error::invalid("World.overlap.pose.orientation", formatQuat(pose.orientation),
                             "must be a unit quaternion [w, x, y, z] (norm 1 within 1e-4)");
    const Transform unit{pose.position, pose.orientation.normalized()};
    if (settings_.planar) {
        validatePlanar(shape, "World.overlap.shape");
        if (std::abs(pose.position.z()) > detail::kPlanarTolerance)
            throw Error::invalid("World.overlap.pose.position", formatVec3(pose.position), "must have z = 0 in a planar world");
        if (!detail::rotatesAboutZOnly(unit.orientation))
            throw Error::invalid("World.overlap.pose.orientation", formatQuat(pose.orientation),
                                 "must be a rotation about Z (x = y = 0) in a planar world");
    }
    std::vector<Body> out;
    for (std::uint64_t key : impl_->peer->overlap(flattenShape(shape), unit, mask)) out.emplace_back(this, unpackId(key));
    return out;
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
    impl_->refuseWhileStepping("World.setForceCallback", "");
    if (callback && settings_.effects && !settings_.effects->has(Effect::UserForces))
        throw Error(ErrorKind::Unsupported, "WorldSettings.effects",
                    "World.setForceCallback: the world's declared effects exclude \"userForces\"; add it to WorldSettings.effects");
    impl_->forceCallback = std::move(callback);
    installForceHook();
    refreshEffects();
}

void World::installForceHook() {
    const bool fieldForces = !(impl_->fieldEffects & kFieldForceEffects).empty();
    const bool evaluate = impl_->forceCallback || fieldForces;
    if (impl_->backend->capabilities.forceEvaluation == ForceEvaluation::PerStep) {
        impl_->layerForces = evaluate;  // World::step runs them (holdStepForces)
        return;
    }
    if (!evaluate) {
        impl_->peer->setForceHook({});
        return;
    }
    impl_->peer->setForceHook([this](ForceStage& stage) {
        StageForces sink(stage);
        evaluateForces(sink);
    });
}

void World::evaluateForces(detail::ForceSink& sink) {
    // The fields first (they read only states), then the game's callback.
    if (!(activeEffects_ & kFieldForceEffects).empty()) applyFieldForces(sink);
    if (!impl_->forceCallback) return;
    ForceContextImpl context(*this, sink, [](World& w, Body b) -> ForceTarget {
        if (b.world() != &w)
            throw Error(b.world() ? ErrorKind::InvalidState : ErrorKind::StaleHandle, "",
                        b.world() ? "ForceContext: the body belongs to another world"
                                  : "ForceContext: stale body handle (null, or its world was destroyed)");
        return {b.id().index, *w.slot(b.id(), "ForceContext").peer};
    });
    impl_->forceCallback(context);
}

void World::holdStepForces() {
    Impl& i = *impl_;
    if (i.heldForces.size() < i.slots.size()) i.heldForces.resize(i.slots.size());
    // Every entry is zero again when this returns, also when the callback throws: a refused
    // evaluation hands nothing to the peers, and nothing of it leaks into the next step.
    struct Reset {
        Impl& impl;
        ~Reset() {
            for (std::uint32_t s : impl.heldSlots) impl.heldForces[s] = {};
            impl.heldSlots.clear();
        }
    } reset{i};
    StepStartForces sink(time_, i.heldForces, i.heldSlots);
    evaluateForces(sink);
    for (std::uint32_t s : i.heldSlots) {
        const Slot& slot = i.slots[s];
        if (slot.def.type != BodyType::Dynamic) continue;  // nothing else responds to a force
        slot.peer->holdForStep(i.heldForces[s].force, i.heldForces[s].torque);
    }
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
        throw Error(ErrorKind::Unsupported, "WorldSettings.effects",
                    "Body.applyForce: the world's declared effects exclude \"userForces\"; add it to WorldSettings.effects");
    if (!impl_->forcesUsed) {
        impl_->forcesUsed = true;
        refreshEffects();
    }
}

}  // namespace anyphys
