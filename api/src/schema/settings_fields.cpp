// The rows of WorldSettings, in the order scene files write them (see schema.hpp).
// WorldSettings::taskSystem has no row: a pointer to the game's scheduler has no scene-file form.
#include <string>
#include <vector>

#include "anyphys/world_settings.hpp"
#include "anyphys/schema/settings_fields.hpp"
#include "anyphys/schema/rows.hpp"

namespace anyphys::schema {

const std::vector<Field<WorldSettings>>& settingsFields() {
    using S = WorldSettings;
    using F = Field<S>;
    static const std::vector<F> rows = {
        with<S>({.key = "backend", .path = "settings.backend", .type = Type::String, .unit = "name",
                 .value = std::string("native"), .check = Check::NonEmpty, .words = "must name a backend",
                 .note = "must be a built backend when the world is created (`anyphys backends`)",
                 .honour = Honour::Layer},
                member(&S::backend)),
        with<S>({.key = "gravity", .path = "settings.gravity", .type = Type::Vec3, .unit = "m/s^2, world frame",
                 .value = Vec3(0, -9.81, 0), .check = Check::Magnitude, .bound = kMaxGravity,
                 .words = " m/s^2 (anyphys::kMaxGravity)", .note = "z = 0 in a planar world"},
                member(&S::gravity)),
        with<S>({.key = "timeStep", .path = "settings.timeStep", .unit = "s", .value = 1.0 / 60.0, .defaultText = "`1/60`",
                 .check = Check::TimeStep,
                 .note = "the fixed step of `step()` and `update()`"},
                member(&S::timeStep)),
        with<S>({.key = "integrator", .path = "settings.integrator", .type = Type::Enum,
                 .value = std::string("semi_implicit_euler"), .note = "integrates free bodies"},
                member(&S::integrator), allowedNames<Integrator>),
        with<S>({.key = "planar", .path = "settings.planar", .type = Type::Bool, .value = false,
                 .note = "`true`: a planar world (see below). Required by `box2d`; 3D backends run it with a plane constraint",
                 .honour = Honour::LayerIfPlanar, .save = Save::WhenNotDefault},
                member(&S::planar)),
        with<S>({.key = "solver", .path = "settings.solver", .type = Type::Enum,
                 .defaultText = "absent: the backend's default (`anyphys backends` shows it)",
                 .note = "`soft_step` (substepped soft contacts, Box2D v3 style), `pgs` (sequential impulses), `direct` "
                         "(an engine's global solver)",
                 .save = Save::WhenSet},
                member(&S::solver), allowedNames<Solver>),
        with<S>({.key = "substeps", .path = "settings.substeps", .type = Type::Count, .unit = "count",
                 .defaultText = "absent: the backend's default", .check = Check::CountIn, .bound = kMaxSubsteps,
                 .words = " (anyphys::kMaxSubsteps)",
                 .note = "constraint-solver substeps per step. Native: bodies in contact are solved and moved in that "
                         "many slices, free bodies are integrated once per step by `integrator`. ODE and Bullet step the "
                         "whole world that many times with `timeStep / substeps`",
                 .save = Save::WhenSet},
                member(&S::substeps)),
        with<S>({.key = "iterations", .path = "settings.iterations", .type = Type::Count, .unit = "count",
                 .defaultText = "absent: the backend's default, raised when `substeps` is below the backend's default so "
                                "that a step keeps the default work",
                 .check = Check::CountIn, .bound = kMaxIterations, .words = " (anyphys::kMaxIterations)",
                 .note = "solver iterations per substep", .save = Save::WhenSet},
                member(&S::iterations)),
        {.key = "effects", .path = "settings.effects", .type = Type::Object, .unit = "array of names",
         .defaultText = "absent: derived from content",
         .note = "effect names (`anyphys backends` lists them); `[]` means simulate nothing", .save = Save::WhenSet,
         .ownCode = true},
        with<S>({.key = "contactHertz", .path = "settings.contactHertz", .unit = "Hz", .value = 60.0,
                 .check = Check::Positive, .note = "soft-contact stiffness (soft step); native caps it at a fifth of the substep rate, and up to that cap stiffens a contact between moving bodies that carries more than their weight (a column's lower contacts), so ten-box stacks of 2 to 32 cm cubes stand within 3 mm at the defaults (2 cm cubes in a planar world need shorter steps). Native's joints keep their own stiffness"},
                member(&S::contactHertz)),
        with<S>({.key = "contactDampingRatio", .path = "settings.contactDampingRatio", .unit = "1", .value = 10.0,
                 .check = Check::NonNegative, .note = "soft-contact damping ratio (10: heavily damped, no bounce from overlap)"},
                member(&S::contactDampingRatio)),
        with<S>({.key = "contactPushMaxVelocity", .path = "settings.contactPushMaxVelocity", .unit = "m/s", .value = 3.0,
                 .check = Check::Positive, .note = "fastest speed at which overlap is pushed apart"},
                member(&S::contactPushMaxVelocity)),
        with<S>({.key = "baumgarte", .path = "settings.baumgarte", .unit = "1", .value = 0.2, .check = Check::UnitInterval,
                 .note = "PGS: fraction of overlap corrected per step (native: and of a joint's error per position pass)"},
                member(&S::baumgarte)),
        with<S>({.key = "restitutionThreshold", .path = "settings.restitutionThreshold", .unit = "m/s", .value = 1.0,
                 .check = Check::NonNegative, .note = "impacts slower than this do not bounce"},
                member(&S::restitutionThreshold)),
        with<S>({.key = "linearSlop", .path = "settings.linearSlop", .unit = "m", .value = 0.005, .check = Check::Positive,
                 .note = "allowed overlap and touching tolerance"},
                member(&S::linearSlop)),
        with<S>({.key = "speculativeDistance", .path = "settings.speculativeDistance", .unit = "m", .value = 0.02,
                 .check = Check::NonNegative, .note = "contacts are created this far before touching"},
                member(&S::speculativeDistance)),
        with<S>({.key = "contactImpulses", .path = "settings.contactImpulses", .type = Type::Bool, .value = true,
                 .note = "contact events carry each point's normal impulse; `false`: the same events without "
                         "impulses, and an engine that measures them only for the events (ODE) skips that work",
                 .honour = Honour::Layer, .save = Save::WhenNotDefault},
                member(&S::contactImpulses)),
        with<S>({.key = "sleepLinearVelocity", .path = "settings.sleepLinearVelocity", .unit = "m/s", .value = 0.05,
                 .check = Check::NonNegative, .note = "slower bodies may sleep"},
                member(&S::sleepLinearVelocity)),
        with<S>({.key = "sleepAngularVelocity", .path = "settings.sleepAngularVelocity", .unit = "rad/s", .value = 0.05,
                 .check = Check::NonNegative, .note = "slower-spinning bodies may sleep"},
                member(&S::sleepAngularVelocity)),
        with<S>({.key = "timeToSleep", .path = "settings.timeToSleep", .unit = "s", .value = 0.5,
                 .check = Check::NonNegative, .note = "an island at rest this long falls asleep"},
                member(&S::timeToSleep)),
        with<S>({.key = "maxSpeed", .path = "settings.maxSpeed", .unit = "m/s", .value = kDefaultMaxSpeed,
                 .check = Check::PositiveAtMost, .bound = kMaxSpeedCeiling, .words = " m/s (anyphys::kMaxSpeedCeiling)",
                 .note = "a body faster than this after a step has diverged; initial velocities, set velocities, "
                         "impulses and one step of a force beyond it are refused",
                 .honour = Honour::Layer},
                member(&S::maxSpeed)),
        with<S>({.key = "maxAngularSpeed", .path = "settings.maxAngularSpeed", .unit = "rad/s",
                 .value = kDefaultMaxAngularSpeed, .check = Check::PositiveAtMost, .bound = kMaxAngularSpeedCeiling,
                 .words = " rad/s (anyphys::kMaxAngularSpeedCeiling)", .note = "the same for spin",
                 .honour = Honour::Layer},
                member(&S::maxAngularSpeed)),
        with<S>({.key = "maxStepsPerUpdate", .path = "settings.maxStepsPerUpdate", .type = Type::Count, .unit = "count",
                 .value = 8, .check = Check::CountIn, .bound = kMaxStepsPerUpdate,
                 .words = " (anyphys::kMaxStepsPerUpdate)", .note = "cap on the fixed steps one `update()` takes",
                 .honour = Honour::Layer},
                member(&S::maxStepsPerUpdate)),
        with<S>({.key = "workers", .path = "settings.workers", .type = Type::Count, .unit = "count", .value = 1,
                 .check = Check::CountIn, .bound = kMaxWorkers,
                 .note = "threads that step the world, the caller's included; results do not depend on it (backends "
                         "that step on one thread do not list it)",
                 .save = Save::WhenNotDefault},
                member(&S::workers)),
        with<S>({.key = "capabilityPolicy", .path = "settings.capabilityPolicy", .type = Type::Enum,
                 .value = std::string("strict"),
                 .note = "`strict`: a feature the backend lacks is an error; `lenient`: a warning",
                 .honour = Honour::Layer},
                member(&S::capabilityPolicy), allowedNames<CapabilityPolicy>),
        with<S>({.key = "divergencePolicy", .path = "settings.divergencePolicy", .type = Type::Enum,
                 .value = std::string("throw"),
                 .note = "what a step does with a body whose state is non-finite, beyond `maxSpeed` / `maxAngularSpeed`, "
                         "or beyond +-1e7 m: `throw` (an error of kind `diverged` naming the bodies) or `freeze` (each "
                         "such body is held still at its last checked pose, with a warning, and the world keeps stepping)",
                 .honour = Honour::Layer},
                member(&S::divergencePolicy), allowedNames<DivergencePolicy>),
        {.key = "backendOptions", .path = "settings.backendOptions", .type = Type::Object, .unit = "object: name -> number",
         .defaultText = "`{}`", .check = Check::Finite,
         .note = "each backend lists the names it honours and the values each takes (`anyphys backends`); the layer refuses other names, and values out of range",
         .honour = Honour::Layer, .ownCode = true},
    };
    return rows;
}

}  // namespace anyphys::schema
