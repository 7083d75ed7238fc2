#pragma once
// The world: the one object game code talks to. Every input is validated here; a rejected call
// throws anyphys::Error and changes nothing.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <typeinfo>
#include <vector>

#include "anyphys/body.hpp"
#include "anyphys/debug_draw.hpp"
#include "anyphys/containers/material_library.hpp"
#include "anyphys/defs.hpp"
#include "anyphys/effects.hpp"
#include "anyphys/error.hpp"
#include "anyphys/fields/field_def.hpp"
#include "anyphys/fields/particle_defs.hpp"
#include "anyphys/ids.hpp"
#include "anyphys/joint.hpp"
#include "anyphys/joint_def.hpp"
#include "anyphys/listeners/contact_listener.hpp"
#include "anyphys/world_settings.hpp"

namespace anyphys {

class World;
namespace detail {
class ForceSink;  // world_impl.hpp: one evaluation of the layer's forces
}

/// What a force callback sees: the time and body states of the current force evaluation, and
/// where to put forces. On backends that evaluate per stage (native) the callback runs at each
/// integrator stage with intermediate states, so state-dependent forces keep the integrator's
/// order; elsewhere (ForceEvaluation::PerStep) the world runs it once per step, at the step's
/// start with the step-start states, and its forces act over the whole step, every substep of it.
class ForceContext {
public:
    virtual ~ForceContext() = default;
    virtual double time() const = 0;
    virtual BodyState state(Body body) const = 0;
    virtual void addForce(Body body, const Vec3& force) = 0;
    virtual void addTorque(Body body, const Vec3& torque) = 0;
};

using ForceCallback = std::function<void(ForceContext&)>;

/// A ray-cast hit.
struct RayHit {
    Body body;
    Vec3 point = Vec3::Zero();    ///< m, world frame
    Vec3 normal = Vec3::Zero();   ///< unit surface normal at the hit, facing the ray
    double distance = 0.0;        ///< m from the ray origin
};
using WarningHandler = std::function<void(const std::string&)>;

/// One fluid or cloth as the world holds it now (World::particleSystems). The pointers stay valid
/// until the world adds or removes a fluid or cloth.
struct ParticleSystemView {
    std::string name;
    const char* kind = "fluid";                   ///< "fluid" or "cloth"
    const std::vector<Vec3>* positions = nullptr;  ///< m, world frame; a cloth's node (i, j) at j (resolution[0] + 1) + i
    const std::vector<Vec3>* velocities = nullptr; ///< m/s
    double particleRadius = 0.0;                   ///< m: how far particles keep from rigid shapes
};

/// A body a step found diverged (see WorldSettings::divergencePolicy).
struct DivergedBody {
    Body body;
    std::string name;    ///< the body's name ("" if unnamed)
    std::string reason;  ///< e.g. "linear speed 2.5e5 m/s > maxSpeed 1e5", "non-finite state"
};

class World {
public:
    /// Creates a world on settings.backend. Throws anyphys::Error for invalid settings, an
    /// unknown backend (listing the known ones) or, under the strict policy, settings the
    /// backend does not honour.
    explicit World(const WorldSettings& settings = {}, MaterialLibrary materials = {});
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    // ---- bodies -------------------------------------------------------------------------
    Body createBody(const BodyDef& def);
    /// Destroys a body: first its joints (their handles become stale, no break event), then the
    /// body (its contacts end with exit events flagged `removal`). Not while stepping.
    void destroyBody(Body body);
    bool isValid(BodyId id) const;
    /// The handle of a live body id; throws if stale.
    Body body(BodyId id);
    /// Live bodies in creation-slot order.
    std::vector<Body> bodies() const;
    std::size_t bodyCount() const;
    /// The first live body with that name; throws anyphys::Error if there is none.
    Body findBody(const std::string& name);

    // ---- joints -------------------------------------------------------------------------
    /// Joins def.bodyB to def.bodyA, or to the static world when bodyA is null. The def is
    /// validated (joint_validation.hpp: the same rules and words as scene files), the bodies must
    /// be live bodies of this world, at least one dynamic, and the backend must honour the type
    /// and every parameter used (strict policy: throws naming them; lenient: warns once and runs
    /// without them, or without the joint if its type is missing). Anchors and axes are world
    /// coordinates now; every position is measured from this pose. Not while stepping.
    Joint createJoint(const JointDef& def);
    /// Destroys a joint, broken or not; its handles become stale. Not while stepping.
    void destroyJoint(Joint joint);
    bool isValid(JointId id) const;
    /// The handle of a live joint id; throws if stale.
    Joint joint(JointId id);
    /// Live joints (broken ones included) in creation-slot order.
    std::vector<Joint> joints() const;
    std::size_t jointCount() const;
    /// The first live joint with that name; throws anyphys::Error if there is none.
    Joint findJoint(const std::string& name);

    // ---- stepping -----------------------------------------------------------------------
    /// One step of settings().timeStep.
    void step();
    /// One step of dt seconds (in [kMinTimeStep, kMaxTimeStep]). After the engine stepped, the layer checks
    /// every dynamic and kinematic body: a non-finite state, a speed above settings().maxSpeed or
    /// maxAngularSpeed, or a position beyond kMaxCoordinate has diverged. Under the throw policy
    /// (default) the step throws anyphys::Error of kind Diverged naming those bodies (the states
    /// stay as the engine made them, events are not dispatched); under freeze they are held still
    /// at their last checked pose, a warning is given once per body, and the step completes.
    void step(double dt);
    /// The bodies the last step found diverged (empty when none), in slot order.
    const std::vector<DivergedBody>& lastDiverged() const;
    /// Fixed-step accumulator for frame loops: adds `elapsed` seconds and takes as many fixed
    /// steps as fit (at most settings().maxStepsPerUpdate; the rest is dropped so a slow frame
    /// cannot snowball). Returns the number of steps taken.
    int update(double elapsed);
    /// Fraction of a fixed step left in the accumulator, in [0, 1): for rendering interpolation.
    double interpolationAlpha() const;
    double time() const { return time_; }
    std::uint64_t stepCount() const { return stepCount_; }

    // ---- forces -------------------------------------------------------------------------
    /// Runs inside every step (see ForceContext). Replaces any previous callback; empty clears.
    void setForceCallback(ForceCallback callback);

    // ---- force fields (docs/fields.md) ----------------------------------------------------
    /// Adds a field (buoyancy, drag, wind or explosion), validated like scene files
    /// ("FieldDef.radius: must be > 0, got -1"); its effect is derived from then on (under declared
    /// effects that exclude it, throws). In a planar world its vectors must lie in the plane. The
    /// field acts from the next step; fields act in the order added. Not while stepping.
    void addField(const FieldDef& field);
    /// The fields added, in order.
    const std::vector<FieldDef>& fields() const;
    /// Removes every field; their effects are no longer derived. Not while stepping.
    void clearFields();

    // ---- fluids and cloths (docs/fields.md) -----------------------------------------------
    /// Adds a block of position-based fluid filling def's box, validated like scene files
    /// ("FluidDef.spacing: must be > 0, got 0"); the `fluid` effect is derived from then on (under
    /// declared effects that exclude it, throws). Its particles collide both ways with every
    /// non-trigger body. In a planar world it is a slab in the XY plane as deep as its box along
    /// Z. Runs after each rigid step. Not while stepping.
    void addFluid(const FluidDef& fluid);
    /// The fluids added, in order.
    const std::vector<FluidDef>& fluids() const;
    /// Adds a cloth sheet (`cloth` effect), validated like scene files. In a planar world it must
    /// lie in the XY plane (corner z = 0, axes without Z). Not while stepping.
    void addCloth(const ClothDef& cloth);
    /// The cloths added, in order.
    const std::vector<ClothDef>& cloths() const;
    /// Removes every fluid and cloth; their effects are no longer derived. Not while stepping.
    void clearParticles();
    /// Every fluid (in order added), then every cloth, with their particles as they are now.
    std::vector<ParticleSystemView> particleSystems() const;
    /// The mean force (N, world frame, at the centre of mass) fluids and cloths exerted on the body
    /// over the last step: on a dynamic body it was applied as an impulse after the rigid step;
    /// static and kinematic bodies report it without moving. Zero when no particles touched it.
    Vec3 particleForce(Body body) const;

    // ---- queries ------------------------------------------------------------------------
    /// In a planar world a query stays in the XY plane on every backend: a ray's origin and
    /// direction have z = 0, an overlap's pose has z = 0 and turns about Z only (else an
    /// anyphys::Error naming the field).
    /// Closest hit of the ray origin + t direction, 0 <= t <= maxDistance (direction need not
    /// be unit), on bodies whose layer is in `mask`. Triggers are not hit, nor is a shape whose
    /// solid holds the origin (below a plane included): a ray cast from inside a body finds what
    /// lies beyond it. A ray whose origin lies on a surface (within a millionth of the origin's
    /// largest coordinate, at least 1 um) meets it at distance 0 heading in, and not heading out;
    /// a mesh, a sheet without a solid, is met from either side.
    std::optional<RayHit> raycast(const Vec3& origin, const Vec3& direction, double maxDistance,
                                  std::uint32_t mask = 0xFFFFFFFFu);
    /// Every hit along the ray, nearest first (at most one per shape).
    std::vector<RayHit> raycastAll(const Vec3& origin, const Vec3& direction, double maxDistance,
                                   std::uint32_t mask = 0xFFFFFFFFu);
    /// Bodies overlapping `shape` placed at `pose`, whose layer is in `mask`. Triggers are skipped.
    std::vector<Body> overlap(const ShapeDef& shape, const Transform& pose, std::uint32_t mask = 0xFFFFFFFFu);

    // ---- events -------------------------------------------------------------------------
    /// Listeners receive events after each step's physics, on the caller's thread, in pair
    /// order (exits, enters, stays). A listener may create and destroy bodies in a callback.
    void addListener(ContactListener* listener);
    void removeListener(ContactListener* listener);
    /// The events of the last step (also what listeners received). Until the first call (and
    /// while no listener is added) steps do not write them, only track which pairs touch; the
    /// call writes the last step's, and from then on every step does, so the reference follows
    /// every step. An engine that measures impulses only for the events (ODE) does so from the
    /// step after the first call or listener: the step read first may carry none (hasImpulses
    /// false). Call it once before stepping to have them from the first step.
    const std::vector<ContactEvent>& lastEvents() const;
    /// The joints that broke in the last step (also what listeners received through
    /// onJointBreak). Breaking is the layer's, the same on every backend: after each step, a
    /// joint whose reaction force exceeds breakForce, or whose reaction torque exceeds
    /// breakTorque, loses its constraint and stays as a broken handle.
    const std::vector<JointEvent>& lastJointEvents() const;

    // ---- debug drawing ------------------------------------------------------------------
    /// Hands the world to `drawer` (see debug_draw.hpp): each primitive shape at its pose in its
    /// body's colour, the last step's contact points (lastEvents(): pairs asleep have no events,
    /// so a sleeping pile shows none), the frames and limits of simulated joints, and the world
    /// bounds of shapes, as `options` select. The same calls on every backend. Throws
    /// anyphys::Error for bad options (nothing drawn), or while the world is stepping.
    void debugDraw(DebugDraw& drawer, const DebugDrawOptions& options = {}) const;

    // ---- configuration ------------------------------------------------------------------
    const WorldSettings& settings() const { return settings_; }
    const std::string& backendName() const { return settings_.backend; }
    /// The effects being simulated now (declared, or derived from content).
    Effects activeEffects() const { return activeEffects_; }
    const MaterialLibrary& materials() const { return materials_; }
    /// Receives lenient-policy and freeze-policy warnings; default: one line on stderr.
    void setWarningHandler(WarningHandler handler);
    /// Every warning this world has given, in order, each once.
    const std::vector<std::string>& warnings() const;

    // ---- escape hatch -------------------------------------------------------------------
    /// The engine's own world object when this world runs on the engine that has a T, else
    /// nullptr: dxWorld (ODE's dWorldID) on ode, btDiscreteDynamicsWorld on bullet, b2World on
    /// box2d. For engine features the layer lacks; changes made through it bypass validation and
    /// events. (In-tree code may also ask for the private WorldPeer: the backend peer itself.)
    template <class T>
    T* native() { return static_cast<T*>(nativeObject(typeid(T*))); }
    void* nativeObject(const std::type_info& pointerType);

private:
    friend class Body;
    friend class Joint;
    struct Impl;
    struct Slot;
    struct JointSlot;

    Slot& slot(BodyId id, const char* operation);
    const Slot& slot(BodyId id, const char* operation) const;
    JointSlot& jointSlot(JointId id, const char* operation);
    const JointSlot& jointSlot(JointId id, const char* operation) const;
    void releaseJoint(std::uint32_t index);  // destroys a live joint slot (peer first)
    void breakJoints();                       // after a step: breaks overloaded joints
    void deliverJointBreaks(const std::vector<JointEvent>& events);
    // Joint setters: whether the backend honours `field` of the joint's type (strict: throws
    // naming it; lenient: warns and returns false), and a spring in SI for the bodies as they are.
    bool honoursJointField(const JointSlot& joint, const char* field, const char* operation);
    JointSpringSI jointSpringSI(const JointSlot& joint, const JointSpring& spring) const;
    void refreshEffects();
    void countBody(const BodyDef& def, int delta);  // effect-derivation counters
    void dispatchEvents();
    /// The tracker's near query: whether the peer finds a pair it no longer lists within
    /// linearSlop (appending its contact to `touching`).
    bool stillTouching(BodyId a, BodyId b, std::vector<struct TouchingRange>& touching);
    void deliverEvents();  // the last step's events to the listeners
    struct MaterialTable buildMaterialTable();
    // Per-piece surfaces of a compound (a child's own material, density, filter, sensor flag).
    void requireKnownMaterials(const BodyDef& def) const;  // the body's and every child's, named
    std::vector<double> pieceDensities(const BodyDef& def) const;
    void resolveSurfaces(const BodyDef& def, std::vector<struct PeerShape>& shapes) const;
    void noteForcesUsed();  // first force or torque: derive the userForces effect
    void installForceHook();  // who evaluates the fields and the force callback: the peer per stage, or the layer per step
    void evaluateForces(detail::ForceSink& sink);  // the fields, then the force callback
    void holdStepForces();    // PerStep backends: one evaluation at the step's start, handed to the peers
    void applyFieldForces(detail::ForceSink& sink);  // world_fields.cpp: buoyancy, drag, wind
    void fireExplosions(double dt);             // world_fields.cpp: explosions due in this step
    void stepParticles(double dt);              // world_particles.cpp: fluids and cloths after the rigid step
    void warn(const std::string& message);
    struct MotionLimits motionLimits() const;  // the settings' ceilings on a body's state
    void checkDivergence(double dt);  // after a step: non-finite or over-ceiling states (settings_.divergencePolicy)
    void refuseStillDiverged();       // before a step that follows a Diverged throw
    void holdFrozen();                // after a step: frozen bodies back to their held pose

    std::shared_ptr<detail::WorldLink> link_;  // shared with every handle; cleared by ~World
    WorldSettings settings_;
    MaterialLibrary materials_;
    Effects activeEffects_;
    double time_ = 0.0;
    double timeCompensation_ = 0.0;  // Kahan summation term of time_
    double accumulator_ = 0.0;
    std::uint64_t stepCount_ = 0;
    std::unique_ptr<Impl> impl_;
};

}  // namespace anyphys
