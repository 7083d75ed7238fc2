// Registration record of the ODE backend: its name, capabilities and world factory.
#include <memory>
#include <string>

#include "anyphys/peers/backend.hpp"
#include "ode_tuning.hpp"
#include "ode_world.hpp"

namespace anyphys {

Backend makeOdeBackend() {
    Backend backend;
    backend.name = "ode";
    backend.description =
        "Open Dynamics Engine 0.16 (double precision): quickstep (PGS) or dWorldStep (direct) solver, "
        "semi-implicit Euler, hash-space collision";
    Capabilities& caps = backend.capabilities;
    caps.dimensions = 3;
    caps.planar = true;  // dJointCreatePlane2D per dynamic body, drift projected out after each step
    caps.shapes = {ShapeType::Sphere, ShapeType::Box,  ShapeType::Capsule, ShapeType::Plane,
                   ShapeType::Convex, ShapeType::Mesh, ShapeType::Compound};
    caps.bodyTypes = {BodyType::Static, BodyType::Kinematic, BodyType::Dynamic};
    // Continuous collision is the backend's approximation (ode_continuous.cpp): ODE itself has none.
    caps.effects = Effects::all();
    // Joints (ode_joints.hpp): ODE's fixed, ball, slider, double ball (distance) and hinge2
    // (wheel) joints, ball joints with angular-motor rows (hinge, cone), and speculative stops.
    caps.jointTypes = {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"};
    caps.integrators = {Integrator::SemiImplicitEuler};  // ODE's own
    caps.solvers = {Solver::ProjectedGaussSeidel, Solver::Direct};
    caps.defaultSolver = Solver::ProjectedGaussSeidel;
    caps.defaultSubsteps = ode::kDefaultSubsteps;
    caps.defaultIterations = ode::kDefaultIterations;
    caps.gyroscopicModes = {GyroscopicMode::None, GyroscopicMode::Implicit};  // ODE 0.16 has no explicit term
    caps.forceEvaluation = ForceEvaluation::PerStep;  // forces are held constant over an ODE step
    caps.contactImpulses = true;                      // from the contact joints' feedback
    caps.queries = {"raycast", "overlap"};
    // Debian's ODE is built without libccd, and its convex-trimesh collider crashes: the pair is
    // never collided, so the layer refuses worlds that would need it.
    caps.missingShapePairs = {{ShapeType::Convex, ShapeType::Mesh}};
    caps.parameters = {"settings.gravity", "settings.timeStep", "settings.integrator", "settings.substeps",
                       "settings.effects", "settings.solver", "settings.iterations", "settings.baumgarte",
                       "settings.contactPushMaxVelocity", "settings.restitutionThreshold", "settings.linearSlop",
                       "settings.sleepLinearVelocity", "settings.sleepAngularVelocity", "settings.timeToSleep",
                       "body.type", "body.position", "body.orientation", "body.linearVelocity",
                       "body.angularVelocity", "body.shape", "body.mass", "body.density", "body.inertia",
                       "body.linearDamping", "body.angularDamping", "body.gravityScale", "body.gyroscopic",
                       "body.material", "body.isTrigger", "body.layer", "body.mask", "body.allowSleep",
                       "body.isAwake",
                       // Joints: only what ode_joints.cpp honours and tests/backends/ode/test_ode_joints.cpp
                       // checks.
                       "joint.hinge.limits", "joint.hinge.motor", "joint.hinge.spring",
                       "joint.slider.limits", "joint.slider.motor", "joint.slider.spring",
                       "joint.wheel.limits", "joint.wheel.motor", "joint.wheel.spring", "joint.wheel.steering",
                       "joint.distance.spring", "joint.distance.minLength", "joint.distance.maxLength",
                       "joint.cone.swingLimit", "joint.cone.twistLimits"};
    // Every type: collideConnected (the near callback skips joined pairs), and breaking, which the
    // layer does from the reactions (ODE's joint feedback, in N and N m).
    for (const char* type : {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"})
        for (const char* field : {"breakForce", "breakTorque", "collideConnected"})
            caps.parameters.insert(std::string("joint.") + type + "." + field);
    caps.options = {
        {"erp", "error reduction parameter: fraction of contact overlap (and of slider and wheel joint drift) "
                "corrected per step, in [0, 1]; default settings.baumgarte (0.2). Ball, hinge, cone, fixed and "
                "distance joints use their own 0.8"},
        {"cfm", "constraint force mixing: softness of resting contacts, >= 0; default 1e-6 (bouncing contacts "
                "use 1e-10 so softness does not absorb the rebound)"},
    };
    backend.createWorld = [](const WorldSettings& settings) -> std::unique_ptr<WorldPeer> {
        return std::make_unique<ode::OdeWorld>(settings);
    };
    return backend;
}

}  // namespace anyphys
