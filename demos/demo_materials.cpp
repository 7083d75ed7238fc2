// Multiple materials: ice, wood and rubber side by side. Three boxes launched along the floor
// stop after v0^2 / (2 mu g) (their friction with the floor); three balls dropped from 2 m
// rebound to e^2 h (their restitution).
#include <cstdio>

#include "thesis_demos.hpp"

namespace anyphys::demo {
namespace {

struct Sample {
    const char* name;
    Material material;
};

// friction, restitution, density. The floor's own friction is 1 and restitution 0: with the
// geometric mean for friction and max for restitution, each pair's values are the sample's
// friction times 1 under the square root and the sample's restitution.
const Sample kSamples[] = {{"ice", {0.05, 0.1, 917.0}}, {"wood", {0.4, 0.3, 600.0}}, {"rubber", {0.9, 0.8, 1100.0}}};

}  // namespace

int runMaterials(const DemoOptions& o) {
    MaterialLibrary materials;
    materials.add("floor", Material{1.0, 0.0, 2000.0});
    for (const Sample& s : kSamples) materials.add(s.name, s.material);
    WorldSettings settings = settingsFor(o.backend);
    settings.restitutionThreshold = 0.5;
    World world(settings, materials);
    BodyDef floor = groundPlane();
    floor.material = "floor";
    std::vector<Body> bodies{world.createBody(floor)};
    constexpr double kSpeed = 3.0, kDrop = 2.0;
    const bool planar = settings.planar;
    for (int i = 0; i < 3; ++i) {
        BodyDef box;
        box.name = std::string(kSamples[i].name) + "_box";
        box.shape = ShapeDef::box({0.2, 0.2, 0.2});
        box.material = kSamples[i].name;
        // In a planar world the samples line up along the one floor, far enough apart.
        box.position = planar ? Vec3(-30.0 + 12.0 * i, 0.2, 0) : Vec3(0, 0.2, -3.0 + 3.0 * i);
        box.linearVelocity = Vec3(kSpeed, 0, 0);
        bodies.push_back(world.createBody(box));
        BodyDef ball;
        ball.name = std::string(kSamples[i].name) + "_ball";
        ball.shape = ShapeDef::sphere(0.2);
        ball.material = kSamples[i].name;
        ball.position = planar ? Vec3(10.0 + 3.0 * i, 0.2 + kDrop, 0) : Vec3(-4, 0.2 + kDrop, -3.0 + 3.0 * i);
        bodies.push_back(world.createBody(ball));
    }
    double apex[3] = {0, 0, 0};
    bool rising[3] = {false, false, false}, done[3] = {false, false, false};
    StepHooks hooks;
    hooks.after = [&](long long) {
        for (int i = 0; i < 3; ++i) {
            const Body& ball = bodies[2 + 2 * i];
            if (!rising[i] && ball.linearVelocity().y() > 0) rising[i] = true;
            if (rising[i] && !done[i]) apex[i] = std::max(apex[i], ball.position().y() - 0.2);
            if (rising[i] && ball.linearVelocity().y() < 0) done[i] = true;
        }
    };
    const SimulationResult r = simulate(world, bodies, o, hooks);
    std::printf("materials on %s: %.3f ms per step (friction: geometric mean with the floor's 1; restitution: max)\n",
                o.backend.c_str(), r.msPerStep);
    for (int i = 0; i < 3; ++i) {
        const Sample& s = kSamples[i];
        const double mu = std::sqrt(s.material.friction * 1.0);
        const double slid = bodies[1 + 2 * i].position().x() - (planar ? -30.0 + 12.0 * i : 0.0);
        printCheck(std::string(s.name) + " box slid", slid, kSpeed * kSpeed / (2 * mu * 9.81), "m");
        printCheck(std::string(s.name) + " ball rebound", apex[i], s.material.restitution * s.material.restitution * kDrop, "m");
    }
    return r.finite ? 0 : 1;
}

}  // namespace anyphys::demo
