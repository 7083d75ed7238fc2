// anyphys_ragdoll: the built-in ragdoll on any backend (the planar one on a 2D engine), the same
// code for every engine. --mode drop: one ragdoll tumbles down a flight of stairs; pile: --count
// ragdolls dropped on each other; animated: hinge motors drive the limbs toward a keyframed wave,
// with --strength blending from limp (0) to fully driven (1), the way games mix animation and
// physics. Prints a summary; --out writes the trajectories in the `anyphys run` CSV format.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>

#include "anyphys/containers/assembly.hpp"
#include "demo_support.hpp"
#include "joint_gaps.hpp"

namespace anyphys::demo {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kMaxCount = 200;

struct RagdollOptions {
    DemoOptions common;
    std::string mode = "pile";
    int count = 20;
    double strength = 0.8;
};

BodyDef staticBox(const std::string& name, const Vec3& at, const Vec3& half) {
    BodyDef b;
    b.name = name;
    b.type = BodyType::Static;
    b.shape = ShapeDef::box(half);
    b.position = at;
    return b;
}

BodyDef groundPlane() {
    BodyDef g;
    g.name = "ground";
    g.type = BodyType::Static;
    g.shape = ShapeDef::plane(Vec3::UnitY(), 0.0);
    return g;
}

// Eight steps of 25 cm up and 40 cm deep, climbing toward -X, then a landing the ragdoll starts on.
void addStairs(Scene& scene, bool planar) {
    const double depth = planar ? 0.5 : 1.5;  // along Z (a planar world ignores it)
    for (int i = 0; i < 8; ++i) {
        const double top = 0.25 * (i + 1);
        scene.bodies.push_back(staticBox("step" + std::to_string(i), Vec3(-0.4 * i - 0.2, 0.5 * top, 0),
                                         Vec3(0.2, 0.5 * top, depth)));
    }
}

Scene buildScene(const RagdollOptions& o, bool planar) {
    const Scene& ragdoll = builtinAssembly(planar ? "ragdoll_planar" : "ragdoll");
    Scene scene;
    scene.settings = settingsFor(o.common.backend);
    scene.bodies.push_back(groundPlane());
    if (o.mode == "drop") {
        addStairs(scene, planar);
        // Standing on the top step's edge, leaning forward (toward +X, down the stairs).
        const Quat lean = Quat(Eigen::AngleAxisd(-0.3, Vec3::UnitZ()));
        appendInstance(scene, ragdoll, Transform{Vec3(-3.0, 2.05, 0), lean}, "r0/");
    } else if (o.mode == "pile") {
        for (int i = 0; i < o.count; ++i) {
            // Lying down, turned a different way each time, 0.5 m apart in height (a lying ragdoll is
            // 0.3 m thick).
            const Quat lie = planar ? Quat(Eigen::AngleAxisd(0.5 * kPi * (i % 2 ? 1 : -1), Vec3::UnitZ()))
                                    : Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX())) *
                                          Quat(Eigen::AngleAxisd(0.9 * i, Vec3::UnitY()));
            const Vec3 at = planar ? Vec3(0.9 * (i % 2 ? 1 : -1), 1.0 + 0.5 * i, 0) : Vec3(0.2 * (i % 3), 0.5 + 0.5 * i, -0.9);
            appendInstance(scene, ragdoll, Transform{at, lie}, "r" + std::to_string(i) + "/");
        }
    } else {  // animated: held by the pelvis above the ground, so the pose is free to follow
        appendInstance(scene, ragdoll, Transform{Vec3(0, 0.3, 0), Quat::Identity()}, "r0/");
        SceneJoint hold;
        hold.def.name = "hold";
        hold.def.type = JointType::Fixed;
        hold.def.anchor = Vec3(0, 1.36, 0);
        hold.bodyB = "r0/pelvis";
        scene.joints.push_back(hold);
    }
    for (BodyDef& b : scene.bodies) b.allowSleep = false;  // the demo shows the physics settle, not sleep
    return scene;
}

/// The keyframed wave: each driven hinge's target angle at time t (rad). Elbows and knees in 3D;
/// in a planar ragdoll every joint is a hinge, so shoulders and hips wave too.
double targetAngle(const std::string& joint, double t) {
    const double phase = 2.0 * kPi * t / 1.6;  // one cycle in 1.6 s
    if (joint.find("elbow") != std::string::npos) return 1.2 + 0.8 * std::sin(phase);
    if (joint.find("knee") != std::string::npos) return 0.6 + 0.5 * std::sin(phase + (joint.find("_l") != std::string::npos ? 0 : kPi));
    if (joint.find("shoulder") != std::string::npos) return 1.4 + 0.9 * std::sin(phase);
    if (joint.find("hip") != std::string::npos) return 0.3 + 0.25 * std::sin(phase);
    return 0.0;  // neck, waist: held straight
}

struct Driven {
    Joint joint;
    double maxTorque;  // N m at full strength
};

int run(const RagdollOptions& o) {
    validate(o.common);
    const bool planar = planarOnly(o.common.backend);
    const Scene scene = buildScene(o, planar);
    World world(scene.settings, scene.materials);
    const SceneObjects objects = createSceneObjects(world, scene);
    JointMeter meter(scene, objects);
    RestTimer rest(0.1);

    // Animated: a motor on every hinge the backend can drive (capability joint.hinge.motor).
    std::vector<Driven> driven;
    if (o.mode == "animated" && backendInfo(o.common.backend).capabilities.parameters.contains("joint.hinge.motor"))
        for (const Joint& j : objects.joints)
            if (j.type() == JointType::Hinge) driven.push_back({j, j.name().find("knee") != std::string::npos ? 150.0 : 80.0});
    double squaredError = 0.0;
    long long samples = 0;

    StepHooks hooks;
    hooks.before = [&](long long) {
        const double t = world.time() + world.settings().timeStep;
        for (Driven& d : driven) {
            // A servo: speed toward the keyframe, proportional to the error, effort capped by strength.
            const double error = targetAngle(d.joint.name(), t) - d.joint.position();
            d.joint.setMotor(JointMotor{std::clamp(8.0 * error, -8.0, 8.0), o.strength * d.maxTorque});
        }
    };
    hooks.after = [&](long long) {
        meter.observe();
        rest.observe(world.time(), objects.bodies);
        for (const Driven& d : driven) {
            const double error = targetAngle(d.joint.name(), world.time()) - d.joint.position();
            squaredError += error * error;
            ++samples;
        }
    };
    const SimulationResult result = simulate(world, objects.bodies, o.common, hooks);

    std::printf("anyphys_ragdoll %s on %s%s: %zu bodies, %zu joints, %.1f s (%lld steps)\n", o.mode.c_str(),
                o.common.backend.c_str(), planar ? " (planar)" : "", objects.bodies.size(), objects.joints.size(),
                world.time(), result.steps);
    std::printf("  time per step       %.3f ms\n", result.msPerStep);
    std::printf("  worst joint gap     %.1f mm\n", 1e3 * meter.worstGap());
    std::printf("  worst hinge limit   %.2f deg beyond\n", meter.worstLimitViolation() * 180.0 / kPi);
    if (rest.restTime() >= 0)
        std::printf("  at rest from        %.2f s (every body slower than 0.1 m/s)\n", rest.restTime());
    else
        std::printf("  at rest from        not at rest at the end\n");
    if (o.mode == "animated") {
        if (driven.empty())
            std::printf("  driven joints       none: backend %s has no hinge motors\n", o.common.backend.c_str());
        else
            std::printf("  driven joints       %zu hinges, strength %.2f, RMS tracking error %.2f deg\n", driven.size(),
                        o.strength, std::sqrt(squaredError / static_cast<double>(std::max<long long>(1, samples))) * 180.0 / kPi);
    }
    return result.finite ? 0 : 1;
}

}  // namespace
}  // namespace anyphys::demo

int main(int argc, char** argv) {
    using namespace anyphys::demo;
    RagdollOptions o;
    CLI::App app{"anyphys_ragdoll: ragdolls on any backend (drop down stairs, a pile, or animated by motors)",
                 "anyphys_ragdoll"};
    addCommonOptions(app, o.common, 10.0);
    app.add_option("--mode", o.mode, "drop | pile | animated")->check(CLI::IsMember({"drop", "pile", "animated"}))->capture_default_str();
    app.add_option("--count", o.count, "Ragdolls in the pile, 1 to 200")->check(CLI::Range(1, kMaxCount))->capture_default_str();
    app.add_option("--strength", o.strength, "Animated: muscle strength, 0 (limp) to 1 (fully driven)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    return runMain(app, argc, argv, [&o] { return run(o); });
}
