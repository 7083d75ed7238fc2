#pragma once
// World-wide settings. Every field documents its unit and default.
#include <map>
#include <optional>
#include <string>

#include "anyphys/effects.hpp"
#include "anyphys/enums.hpp"
#include "anyphys/math.hpp"
#include "anyphys/task_system.hpp"

namespace anyphys {

/// What happens when a scene asks for something its backend does not honour.
enum class CapabilityPolicy {
    Strict,   ///< throw anyphys::Error listing what is missing (default)
    Lenient,  ///< proceed, and report each missing feature once through the warning handler
};

/// What World::step does when, after the engine stepped, a body's state is non-finite or beyond
/// the ceilings (WorldSettings::maxSpeed, maxAngularSpeed, anyphys::kMaxCoordinate).
enum class DivergencePolicy {
    Throw,   ///< throw anyphys::Error of kind Diverged naming the bodies (default); the world keeps the states the engine made
    Freeze,  ///< hold each such body still at its last checked pose (zero velocity), warn once per body, keep stepping
};

// Their scene-file names.
template <>
struct EnumNames<CapabilityPolicy> {
    static constexpr std::string_view what = "capability policy";
    static constexpr std::array<std::pair<CapabilityPolicy, std::string_view>, 2> values{{
        {CapabilityPolicy::Strict, "strict"}, {CapabilityPolicy::Lenient, "lenient"}}};
};
template <>
struct EnumNames<DivergencePolicy> {
    static constexpr std::string_view what = "divergence policy";
    static constexpr std::array<std::pair<DivergencePolicy, std::string_view>, 2> values{{
        {DivergencePolicy::Throw, "throw"}, {DivergencePolicy::Freeze, "freeze"}}};
};

/// Default ceiling of WorldSettings::maxSpeed, m/s: 100 km/s, beyond any rigid body a game or a
/// test simulates (a rifle bullet ~1e3, low orbit ~8e3 m/s), yet caught long before it overflows.
inline constexpr double kDefaultMaxSpeed = 1e5;
/// Default ceiling of WorldSettings::maxAngularSpeed, rad/s: above the fastest real machinery
/// (a dental turbine spins ~4e4 rad/s).
inline constexpr double kDefaultMaxAngularSpeed = 1e5;

struct WorldSettings {
    std::string backend = "native";                 ///< registered backend name; default "native"
    Vec3 gravity = Vec3(0, -9.81, 0);               ///< m/s^2, world frame; default (0, -9.81, 0)
    double timeStep = 1.0 / 60.0;                   ///< s, the fixed step of step() and update(); default 1/60
    Integrator integrator = Integrator::SemiImplicitEuler;  ///< default semi-implicit Euler
    /// A planar world: bodies lie in the XY plane (z = 0), rotate about Z only and move in the
    /// plane; forces, torques and impulses out of the plane are dropped. Needed by 2D backends
    /// (box2d), honoured by every backend whose capabilities say `planar`. Default false.
    bool planar = false;
    /// Constraint solver. Unset (default): the backend's default (capabilities.defaultSolver: soft_step on native,
    /// pgs elsewhere), filled in with iterations and substeps by World (withBackendDefaults): settings() shows it.
    std::optional<Solver> solver;
    /// Solver iterations per substep, >= 1. Unset (default): the backend's default
    /// (capabilities.defaultIterations), raised when `substeps` is set below the backend's
    /// default so that a step still does the default work (defaultIterations x defaultSubsteps
    /// sweeps): native at 1 substep runs 8 iterations, at 4 substeps 2.
    std::optional<int> iterations;
    /// Constraint-solver substeps per step, >= 1: bodies in contact are solved and moved in
    /// `substeps` slices of the step; free bodies are integrated once per step by `integrator`.
    /// Unset (default): the backend's default (capabilities.defaultSubsteps). The count, not the
    /// rate, is fixed: native caps its contacts' stiffness at a fifth of the substep rate, so a
    /// longer step with the same count gives softer stacks (at 1/30 s the catalogue's 40-box column
    /// sags four times as far as at 1/60 s and topples after 25 s; 16 substeps hold it as 8 do
    /// at 60 Hz).
    std::optional<int> substeps;
    /// Effects to simulate. Unset (default): derived from the world's content, e.g. damping only
    /// when some body has non-zero damping. Set: exactly these effects, nothing else.
    std::optional<Effects> effects;
    // ---- contacts (used when the contacts effect is on) ----
    double contactHertz = 60.0;                     ///< Hz, soft-contact stiffness (soft step), > 0; default 60 (native caps it at a fifth of the substep rate)
    double contactDampingRatio = 10.0;              ///< soft-contact damping ratio, >= 0; default 10 (heavily damped: no bounce from overlap)
    double contactPushMaxVelocity = 3.0;            ///< m/s, fastest speed at which overlap is pushed apart, > 0; default 3
    double baumgarte = 0.2;                         ///< PGS: fraction of overlap corrected per step (native: and of a joint's error per position pass), in [0, 1]; default 0.2
    double restitutionThreshold = 1.0;              ///< m/s, slower impacts do not bounce, >= 0; default 1
    double linearSlop = 0.005;                      ///< m, allowed overlap and touching tolerance, > 0; default 0.005
    double speculativeDistance = 0.02;              ///< m, contacts are created this far before touching, >= 0; default 4 x linearSlop
    /// Contact events carry each point's normal impulse (ContactPoint::normalImpulse, the events'
    /// hasImpulses) on backends whose capabilities say contactImpulses; default true. false: the
    /// same events with no impulses (hasImpulses false, every normalImpulse 0), for a game that
    /// reads which pairs touch but not how hard; an engine that measures impulses only for the
    /// events then skips that work (ODE: the contact joints' feedback). ODE skips it too until
    /// events are first read or listened to (World::lastEvents).
    bool contactImpulses = true;
    // ---- sleeping (used when the sleeping effect is on) ----
    double sleepLinearVelocity = 0.05;              ///< m/s, slower bodies may sleep, >= 0; default 0.05
    double sleepAngularVelocity = 0.05;             ///< rad/s, slower-spinning bodies may sleep, >= 0; default 0.05
    double timeToSleep = 0.5;                       ///< s, an island at rest this long falls asleep, >= 0; default 0.5
    int maxStepsPerUpdate = 8;                      ///< cap on fixed steps one update() may take, >= 1; default 8
    // ---- divergence (checked by the layer after every step, on every backend) ----
    /// m/s, > 0: a body faster than this has diverged; initial and set velocities, impulses and
    /// one step's worth of force beyond it are refused. Default kDefaultMaxSpeed (1e5).
    double maxSpeed = kDefaultMaxSpeed;
    /// rad/s, > 0: the same for spin. Default kDefaultMaxAngularSpeed (1e5).
    double maxAngularSpeed = kDefaultMaxAngularSpeed;
    /// What a step does with a body whose state is non-finite, faster than maxSpeed or
    /// maxAngularSpeed, or farther than kMaxCoordinate from the origin. Default throw.
    DivergencePolicy divergencePolicy = DivergencePolicy::Throw;
    /// Threads that step the world, the calling thread included, in [1, 256]; default 1. With more
    /// than one the world runs a ThreadPool of its own (unless `taskSystem` is set). Results do
    /// not depend on the count. Backends whose engine steps on one thread ignore it (they do not
    /// list the parameter "settings.workers").
    int workers = 1;
    /// The game's own scheduler, not owned: it must outlive the world. Default null. When set, the
    /// world runs its parallel work on it and `workers` is ignored. Not saved in scene files.
    TaskSystem* taskSystem = nullptr;
    CapabilityPolicy capabilityPolicy = CapabilityPolicy::Strict;  ///< default strict
    /// Backend-specific numeric options by name (e.g. "erp", "cfm" on ODE); each backend lists
    /// the ones it honours in its capabilities. Default: none.
    std::map<std::string, double> backendOptions;
};

}  // namespace anyphys
