// Registration record of the native backend: its name, capabilities and world factory.
#include <memory>

#include "anyphys/limits.hpp"
#include "anyphys/peers/backend.hpp"
#include "native_world.hpp"

namespace anyphys {

Backend makeNativeBackend() {
    Backend backend;
    backend.name = "native";
    backend.description = "anyphys in-house rigid-body engine: soft-step and PGS contact solvers, five integrators";
    Capabilities& caps = backend.capabilities;
    caps.dimensions = 3;
    caps.planar = true;  // a plane constraint: linear Z and rotation about X and Y locked
    caps.shapes = {ShapeType::Sphere, ShapeType::Box,  ShapeType::Capsule, ShapeType::Plane,
                   ShapeType::Convex, ShapeType::Mesh, ShapeType::Compound};
    caps.bodyTypes = {BodyType::Static, BodyType::Kinematic, BodyType::Dynamic};
    caps.effects = Effects::all();
    caps.jointTypes = {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"};
    caps.solvers = {Solver::SoftStep, Solver::ProjectedGaussSeidel};
    caps.defaultSolver = native::NativeWorld::kDefaultSolver;
    caps.defaultSubsteps = native::NativeWorld::kDefaultSubsteps;
    caps.defaultIterations = native::NativeWorld::kDefaultIterations;
    caps.contactImpulses = true;
    caps.queries = {"raycast", "overlap"};
    caps.integrators = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::Verlet,
                        Integrator::Midpoint, Integrator::RK4};
    caps.gyroscopicModes = {GyroscopicMode::None, GyroscopicMode::Explicit, GyroscopicMode::Implicit};
    caps.forceEvaluation = ForceEvaluation::PerStage;
    caps.options = {
        {.name = "relaxIterations",
         .meaning = "relax passes per substep: joints and contacts solved again without position bias after the "
                    "positions move, which takes back the velocity the push out of overlap added and lets a heavy "
                    "body's impact settle; default settings.iterations on soft_step, 0 on pgs (Baumgarte's push "
                    "stays in the velocity). On pgs the joints' next warm start is what the solve passes left, not "
                    "the relax passes' additions",
         .min = 0, .max = kMaxIterations, .integer = true},
    };
    caps.parameters = {"settings.gravity", "settings.timeStep", "settings.integrator", "settings.substeps",
                       "settings.effects", "body.type", "body.position", "body.orientation", "body.linearVelocity",
                       "body.angularVelocity", "body.shape", "body.mass", "body.density", "body.inertia",
                       "body.linearDamping", "body.angularDamping", "body.gravityScale", "body.gyroscopic",
                       "body.material", "body.isTrigger", "body.layer", "body.mask", "body.allowSleep", "body.isAwake", "body.shape.shapes.material", "body.shape.shapes.isTrigger",
                       "body.shape.shapes.layer", "body.shape.shapes.mask",
                       "settings.solver", "settings.iterations", "settings.contactHertz", "settings.contactDampingRatio",
                       "settings.contactPushMaxVelocity", "settings.baumgarte", "settings.restitutionThreshold",
                       "settings.linearSlop", "settings.speculativeDistance", "settings.sleepLinearVelocity",
                       "settings.sleepAngularVelocity", "settings.timeToSleep", "settings.workers"};
    // Every optional joint field of every type (api joint_capabilities.hpp names them).
    const auto joint = [&](const char* type, std::initializer_list<const char*> fields) {
        for (const char* field : fields) caps.parameters.insert(std::string("joint.") + type + "." + field);
    };
    for (const char* type : {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"})
        joint(type, {"breakForce", "breakTorque", "collideConnected"});
    joint("hinge", {"limits", "motor", "spring"});
    joint("slider", {"limits", "motor", "spring"});
    joint("distance", {"spring", "minLength", "maxLength"});
    joint("cone", {"swingLimit", "twistLimits"});
    joint("wheel", {"limits", "motor", "spring", "steering"});
    // Stability over the whole run, sleeping off, per solver and substep count
    // (tests/contract/test_stability.cpp: drift 1 cm, sink linearSlop per contact, lift 1 mm).
    caps.knownDeviations.insert({
        {"assemblies.ragdoll_limits",
         "an elbow goes 3.4 deg past its limit (median of the pile's nine draws, 4.3 while only kinematic bodies' friction arms turned within the step; bound 3 deg; the single run gave 3.2, and 4.8 before loaded contacts stiffened) as a ragdoll of the pile lands, at the default 8 substeps x 1 iteration. The pile is chaotic: before that, over 72 layouts with the bodies shifted by up to 2 mm the worst overshoot's median is 3.1 deg (4.1 before impacts got their friction) and 39 of 72 go past 3 deg"},
        {"planar.assemblies.ragdoll_limits",
         "an elbow goes 5.3 deg past its limit (median of the pile's nine draws; bound 3 deg; the single run gave 4.0, and 3.4 before loaded contacts stiffened) as a ragdoll of the planar pile lands, at the default 8 substeps x 1 iteration: the limit rows are soft there and give under the landing"},
        {"stability.pyramid20.pgs.s1",
         "PGS at 1 substep x 8 iterations: the 20-row pyramid's boxes drift 1.36 cm over 5 s (bound 1 cm) and its top sinks 4.9 cm: the velocity solve converges slowly through 20 rows (2.9 cm before a manifold was swept again after an impact)"},
        {"planar.stability.stack10.pgs.s1",
         "PGS at 1 substep x 8 iterations: the planar 10-box stack drifts 1.4 cm over 10 s (bound 1 cm; 9.4 cm before a manifold was swept again after an impact, solver/manifold_sweeps.hpp); the 3D stack passes"},
        {"planar.stability.pyramid20.pgs.s1",
         "PGS at 1 substep x 8 iterations: the planar 20-row pyramid's boxes drift 1.34 cm over 5 s (bound 1 cm; 0.93 cm before a manifold was swept again after an impact, solver/manifold_sweeps.hpp, which brought the planar 10-box stack from 9.4 to 1.4 cm): the velocity solve converges slowly through 20 rows, as in 3D (stability.pyramid20.pgs.s1)"},
        {"restitution.dead_heavy_ball_on_box",
         "a 65 kg ball with no restitution landing at 4 m/s on a 10 kg box resting on the ground rises 86 mm above "
         "the box (30 kg: 34 mm; bound 5 mm): the Gauss-Seidel passes, one per substep at the default 8 x 1, stop a "
         "ball 6.5 times the box's mass only part way. Traced at 4 m/s: it reaches the box's top at 3.3 m/s at a "
         "step's end, and the next step ends with it rising at 1.3 m/s. 4 iterations leave 1.6 mm, 32 substeps 26 mm; "
         "the pgs solver 450 mm. Running the restitution stage for such impacts with a target of 0 (a trial, not "
         "kept) left 60 mm. Passes with backendOptions.relaxIterations 4 (3.2 mm; pgs 8.2 mm)"},
        {"planar.restitution.dead_heavy_ball_on_box",
         "as restitution.dead_heavy_ball_on_box, planar: 95 mm; passes with backendOptions.relaxIterations 6 (3.2 mm)"},
    });
    backend.createWorld = [](const WorldSettings& settings) -> std::unique_ptr<WorldPeer> {
        return std::make_unique<native::NativeWorld>(settings);
    };
    // Ceilings of the declared misses above, in each test's measure (stability: the worst of
    // drift, sink and lift as a multiple of its bound; about 1.5 x the figure measured).
    caps.deviationCeilings = {
        {"assemblies.ragdoll_limits", 7.5},
        {"planar.assemblies.ragdoll_limits", 8.0},  // deg, measured 5.3
        {"stability.pyramid20.pgs.s1", 2.0},  // measured 1.36
        {"planar.stability.stack10.pgs.s1", 2.2},
        {"planar.stability.pyramid20.pgs.s1", 2.0},
        {"restitution.dead_heavy_ball_on_box", 0.13},  // m, measured 0.086
        {"planar.restitution.dead_heavy_ball_on_box", 0.14},  // m, measured 0.095
    };
    // Hard cases (`anyphys hardcases`, docs/hardcases.md) and the friction directions, measured
    // with sleeping off at the defaults; each ceiling is about 1.5 to 2 times the measured miss.
    caps.knownDeviations.insert({
        {"hard.overlap25.speed",
         "each overlap is pushed apart at up to settings.contactPushMaxVelocity (3 m/s, Box2D v3's default); the upper box, pushed off the lower one while that rises off the ground, reaches 3.4 m/s. Verified by the setting: 2 m/s gives 2.27, 1.5 gives 1.70 (within the 2.2 bound); 3 relax passes, which take the push back out of the velocity, 0.70 (backendOptions.relaxIterations 3)"},
        {"planar.hard.overlap25.speed",
         "as hard.overlap25.speed, planar: 3.1 m/s (0.76 with backendOptions.relaxIterations 3, before a manifold was swept again after an impact)"},
        {"hard.heavy_on_light.displacement",
         "the 1000 kg box sinks 6.4 cm into the 1 kg one as it settles and rests 4.4 cm in: a soft contact is a spring "
         "sized by its pair's mass, which the light box sets, and a loaded contact stiffens only up to a fifth of the "
         "substep rate (96 Hz at 8 substeps), beyond which Gauss-Seidel rings (twice that let hard_column_40 fall). "
         "Measured: 16 substeps 3.0 cm, 50 iterations 4.4 cm; the pgs solver lets the heavy box through (3.4 m)"},
        {"planar.hard.heavy_on_light.displacement",
         "as hard.heavy_on_light.displacement, planar: 7.8 cm"},
    });
    caps.deviationCeilings.insert({
        {"hard.overlap25.speed", 4.5},
        {"planar.hard.overlap25.speed", 4.5},
        {"hard.heavy_on_light.displacement", 0.1},          // m, measured 0.0643
        {"planar.hard.heavy_on_light.displacement", 0.125},  // m, measured 0.0775
    });
    return backend;
}

}  // namespace anyphys
