// Dynamics: forces, torques, impulses and gyroscopic motion on free bodies (gravity off), each
// against its closed form: x = F t^2 / 2m, w = tau t / I, dv = J / m, and a body spun about its
// intermediate principal axis flipping over (the Dzhanibekov effect, 3D only).
#include <cstdio>

#include "thesis_demos.hpp"

namespace anyphys::demo {

int runDynamics(const DemoOptions& o) {
    WorldSettings settings = settingsFor(o.backend);
    settings.gravity = Vec3::Zero();
    World world(settings);
    const auto body = [&world](const std::string& name, const Vec3& at, const Vec3& inertia) {
        BodyDef def;
        def.name = name;
        def.shape = ShapeDef::box({0.3, 0.2, 0.1});
        def.position = at;
        def.mass = 2.0;
        def.inertia = inertia;
        def.allowSleep = false;
        return world.createBody(def);
    };
    Body pushed = body("pushed", {0, 0, 0}, {1, 1, 1});
    Body twisted = body("twisted", {0, 3, 0}, {1, 1, 0.5});
    Body kicked = body("kicked", {0, -3, 0}, {1, 1, 1});
    std::vector<Body> bodies{pushed, twisted, kicked};
    const bool spins = !settings.planar && backendInfo(o.backend).capabilities.gyroscopicModes.contains(GyroscopicMode::Implicit);
    Body tumbler;
    if (spins) {
        // Principal moments 1, 2, 3: spun at 5 rad/s about Y (the intermediate axis) with a
        // 1e-3 rad/s nudge about X, it flips end over end.
        BodyDef def;
        def.name = "tumbler";
        def.shape = ShapeDef::box({0.3, 0.2, 0.1});
        def.position = {0, 6, 0};  // clear of the pushed body's path
        def.mass = 2.0;
        def.inertia = Vec3(1, 2, 3);
        def.angularVelocity = Vec3(1e-3, 5, 0);
        def.allowSleep = false;
        tumbler = world.createBody(def);
        bodies.push_back(tumbler);
    }
    kicked.applyLinearImpulse(Vec3(3, 0, 0));
    double flipTime = -1.0;
    StepHooks hooks;
    hooks.before = [&](long long) {
        pushed.applyForce(Vec3(4, 0, 0));
        twisted.applyTorque(Vec3(0, 0, 1));
    };
    hooks.after = [&](long long) {
        // Flipped: the body's Y axis has turned past horizontal.
        if (spins && flipTime < 0 && (tumbler.orientation() * Vec3::UnitY()).y() < 0) flipTime = world.time();
    };
    const SimulationResult r = simulate(world, bodies, o, hooks);
    const double t = world.time(), h = settings.timeStep;
    std::printf("dynamics on %s: %.1f s, %.3f ms per step\n", o.backend.c_str(), t, r.msPerStep);
    // Semi-implicit Euler moves each step with the velocity after it: x = F/m h^2 n(n+1)/2.
    const double n = t / h;
    printCheck("constant force 4 N on 2 kg: x", pushed.position().x(), 4.0 / 2.0 * h * h * n * (n + 1) / 2, "m");
    printCheck("constant torque 1 N m on I = 0.5: w", twisted.angularVelocity().z(), 1.0 / 0.5 * t, "rad/s");
    printCheck("impulse 3 N s on 2 kg: v", kicked.linearVelocity().x(), 1.5, "m/s");
    if (spins)
        std::printf("  %-36s %s\n", "spin about the intermediate axis:",
                    flipTime > 0 ? ("flipped after " + std::to_string(flipTime) + " s").c_str() : "no flip within the run");
    else
        std::printf("  %-36s skipped (%s)\n", "spin about the intermediate axis:",
                    settings.planar ? "a planar world turns about Z only" : "no implicit gyroscopic mode");
    return r.finite ? 0 : 1;
}

}  // namespace anyphys::demo
