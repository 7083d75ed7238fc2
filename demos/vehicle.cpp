// anyphys_vehicle: the built-in car drives a course on any backend (the planar car on a 2D
// engine), the same code for every engine. Input: --throttle (fraction of the drive motors'
// torque, negative reverses) and --steer (front wheels' angle, rad), held for the whole run; or
// --control FILE (rows "time,throttle,steer[,brake]", each held until the next); or, with none
// of them, a built-in script: accelerate, turn, brake, turn back. Reports speed, heading,
// turning radius and wheel loads; --out writes the trajectories in the `anyphys run` CSV format.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <sstream>

#include "anyphys/containers/assembly.hpp"
#include "demo_support.hpp"

namespace anyphys::demo {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxDriveTorque = 400.0;  ///< N m per driven (rear) wheel at throttle 1
constexpr double kMaxWheelSpeed = 60.0;    ///< rad/s: 21 m/s with 0.35 m wheels
constexpr double kMaxBrakeTorque = 1500.0; ///< N m per rear wheel at brake 1
constexpr double kMaxSteer = 0.6;          ///< rad

struct Control {
    double time = 0.0, throttle = 0.0, steer = 0.0, brake = 0.0;
};

struct VehicleOptions {
    DemoOptions common;
    std::optional<double> throttle, steer;
    std::string controlFile;
};

/// Accelerate 4 s, turn left 3 s, brake 2 s, turn right at half throttle.
std::vector<Control> defaultScript(bool planar) {
    const double turn = planar ? 0.0 : 0.3;
    return {{0.0, 1.0, 0.0, 0.0}, {4.0, 0.4, turn, 0.0}, {7.0, 0.0, 0.0, 1.0}, {9.0, 0.5, -turn, 0.0}};
}

std::vector<Control> readControlFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(ErrorKind::Io, "", path + ": cannot open the control file");
    std::vector<Control> rows;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.empty() || line[0] == '#' || line.rfind("time", 0) == 0) continue;  // comments, header
        std::istringstream fields(line);
        Control c;
        char comma = 0;
        fields >> c.time >> comma >> c.throttle >> comma >> c.steer;
        if (fields >> comma) fields >> c.brake;
        const std::string where = path + ":" + std::to_string(number);
        if (!fields && !fields.eof()) throw Error(where + ": want time,throttle,steer[,brake], got \"" + line + "\"");
        if (!(c.throttle >= -1 && c.throttle <= 1)) throw Error::invalid(where + " throttle", c.throttle, "must be in [-1, 1]");
        if (!(std::abs(c.steer) <= kMaxSteer)) throw Error::invalid(where + " steer", c.steer, "must be in [-0.6, 0.6] rad");
        if (!(c.brake >= 0 && c.brake <= 1)) throw Error::invalid(where + " brake", c.brake, "must be in [0, 1]");
        if (!rows.empty() && !(c.time >= rows.back().time)) throw Error::invalid(where + " time", c.time, "must not go back");
        rows.push_back(c);
    }
    if (rows.empty()) throw Error(path + ": no control rows (want time,throttle,steer[,brake])");
    return rows;
}

Control controlAt(const std::vector<Control>& script, double t) {
    Control now = script.front();
    for (const Control& c : script)
        if (c.time <= t) now = c;
    return now;
}

// Flat ground with two low bumps across the road (capsules of radius 5 cm) at x = 25 and 32 m.
Scene buildScene(const VehicleOptions& o, bool planar) {
    Scene scene;
    scene.settings = settingsFor(o.common.backend);
    BodyDef ground;
    ground.name = "ground";
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::plane(Vec3::UnitY(), 0.0);
    scene.bodies.push_back(ground);
    for (double x : {25.0, 32.0}) {
        BodyDef bump;
        bump.name = "bump_" + std::to_string(static_cast<int>(x));
        bump.type = BodyType::Static;
        bump.shape = ShapeDef::capsule(0.05, planar ? 0.0 : 3.0);
        bump.position = Vec3(x, 0.0, 0);
        bump.orientation = planar ? Quat::Identity() : Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX()));  // across the road
        scene.bodies.push_back(bump);
    }
    appendInstance(scene, builtinAssembly(planar ? "vehicle_planar" : "vehicle"), Transform{}, "");
    for (BodyDef& b : scene.bodies) b.allowSleep = false;
    return scene;
}

double heading(const Body& chassis) {
    const Vec3 forward = chassis.orientation() * Vec3::UnitX();
    return std::atan2(-forward.z(), forward.x());  // rad, counter-clockwise seen from above
}

int run(const VehicleOptions& o) {
    validate(o.common);
    const bool planar = planarOnly(o.common.backend);
    if (o.throttle && !(*o.throttle >= -1 && *o.throttle <= 1)) throw Error::invalid("--throttle", *o.throttle, "must be in [-1, 1]");
    if (o.steer && !(std::abs(*o.steer) <= kMaxSteer)) throw Error::invalid("--steer", *o.steer, "must be in [-0.6, 0.6] rad");
    if (o.steer && *o.steer != 0.0 && planar) throw Error::invalid("--steer", *o.steer, "must be 0 on a planar (2D) backend: the planar car cannot steer");
    std::vector<Control> script;
    if (!o.controlFile.empty()) script = readControlFile(o.controlFile);
    else if (o.throttle || o.steer) script = {{0.0, o.throttle.value_or(0.0), o.steer.value_or(0.0), 0.0}};
    else script = defaultScript(planar);
    if (planar)
        for (const Control& c : script)
            if (c.steer != 0.0) throw Error::invalid("steer", c.steer, "must be 0 on a planar (2D) backend");

    const Scene scene = buildScene(o, planar);
    World world(scene.settings, scene.materials);
    const SceneObjects objects = createSceneObjects(world, scene);
    const Body chassis = objects.body("chassis");
    std::vector<Joint> driven, steered, suspensions;
    for (const Joint& j : objects.joints) {
        suspensions.push_back(j);
        if (j.def().motor) driven.push_back(j);
        if (j.def().steering) steered.push_back(j);
    }

    double maxSpeed = 0.0, distance = 0.0, yawRateSum = 0.0, speedSum = 0.0;
    int tail = 0;
    Vec3 last = chassis.position();
    StepHooks hooks;
    hooks.before = [&](long long) {
        const Control c = controlAt(script, world.time());
        for (Joint& j : driven) {
            if (c.brake > 0) j.setMotor(JointMotor{0.0, c.brake * kMaxBrakeTorque});
            else j.setMotor(JointMotor{c.throttle >= 0 ? kMaxWheelSpeed : -kMaxWheelSpeed, std::abs(c.throttle) * kMaxDriveTorque});
        }
        for (Joint& j : steered) j.setSteeringAngle(c.steer);
    };
    hooks.after = [&](long long) {
        const Vec3 v = chassis.linearVelocity();
        const double speed = std::hypot(v.x(), v.z());
        maxSpeed = std::max(maxSpeed, speed);
        distance += (chassis.position() - last).norm();
        last = chassis.position();
        if (world.time() > o.common.seconds - 1.0) {  // the last second: steady turning
            yawRateSum += chassis.angularVelocity().y();
            speedSum += speed;
            ++tail;
        }
    };
    const SimulationResult result = simulate(world, objects.bodies, o.common, hooks);

    const Vec3 v = chassis.linearVelocity();
    std::printf("anyphys_vehicle on %s%s: %.1f s (%lld steps), %.3f ms per step\n", o.common.backend.c_str(),
                planar ? " (planar)" : "", world.time(), result.steps, result.msPerStep);
    std::printf("  speed now / top     %.2f / %.2f m/s\n", std::hypot(v.x(), v.z()), maxSpeed);
    std::printf("  distance            %.1f m, chassis at (%.2f, %.2f, %.2f)\n", distance, chassis.position().x(),
                chassis.position().y(), chassis.position().z());
    std::printf("  heading             %.1f deg\n", heading(chassis) * 180.0 / kPi);
    const double yawRate = tail ? yawRateSum / tail : 0.0, meanSpeed = tail ? speedSum / tail : 0.0;
    if (std::abs(yawRate) > 1e-3)
        std::printf("  turning radius      %.2f m (last second: %.2f m/s at %.3f rad/s)\n", meanSpeed / std::abs(yawRate),
                    meanSpeed, yawRate);
    else
        std::printf("  turning radius      straight (last second)\n");
    // The suspension pushes each wheel down with the load it carries (reaction on the wheel, -y).
    for (const Joint& j : suspensions)
        std::printf("  wheel load %-9s %.0f N\n", j.name().substr(11).c_str(), -j.reactionForce().y());
    return result.finite ? 0 : 1;
}

}  // namespace
}  // namespace anyphys::demo

int main(int argc, char** argv) {
    using namespace anyphys::demo;
    VehicleOptions o;
    CLI::App app{"anyphys_vehicle: the built-in car drives a course on any backend", "anyphys_vehicle"};
    addCommonOptions(app, o.common, 12.0);
    app.add_option("--throttle", o.throttle, "Fraction of the drive motors' torque (400 N m per rear wheel), -1 to 1");
    app.add_option("--steer", o.steer, "Front wheels' angle in rad, -0.6 to 0.6 (3D only); positive turns left");
    app.add_option("--control", o.controlFile,
                   "Control file: rows time,throttle,steer[,brake] (s, [-1,1], rad, [0,1]), each held until the next")
        ->excludes("--throttle")
        ->excludes("--steer");
    return runMain(app, argc, argv, [&o] { return run(o); });
}
