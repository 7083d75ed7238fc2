// Registration record of the native backend: its name, capabilities and world factory.
#include <memory>

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
    caps.parameters = {"settings.gravity", "settings.timeStep", "settings.integrator", "settings.substeps",
                       "settings.effects", "body.type", "body.position", "body.orientation", "body.linearVelocity",
                       "body.angularVelocity", "body.shape", "body.mass", "body.density", "body.inertia",
                       "body.linearDamping", "body.angularDamping", "body.gravityScale", "body.gyroscopic",
                       "body.material", "body.isTrigger", "body.layer", "body.mask", "body.allowSleep", "body.isAwake",
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
    backend.createWorld = [](const WorldSettings& settings) -> std::unique_ptr<WorldPeer> {
        return std::make_unique<native::NativeWorld>(settings);
    };
    return backend;
}

}  // namespace anyphys
