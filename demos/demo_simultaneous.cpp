// Simultaneous simulations: the same scene (a small planar pyramid hit by a ball, so that every
// engine can run it) in one world per backend, all in one process and stepped together. The
// summary gives each world's step time and how far its bodies end from the first world's.
#include <chrono>
#include <cstdio>

#include "thesis_demos.hpp"

namespace anyphys::demo {
namespace {

Scene pyramidScene(const std::string& backend) {
    Scene scene;
    scene.settings = settingsFor(backend);
    scene.settings.planar = true;  // every backend here runs planar worlds
    scene.bodies.push_back(groundPlane());
    for (int row = 0; row < 5; ++row)
        for (int i = 0; i < 5 - row; ++i) {
            BodyDef box;
            box.name = "box_" + std::to_string(row) + "_" + std::to_string(i);
            box.shape = ShapeDef::box({0.25, 0.25, 0.25});
            box.position = Vec3(0.5 * i - 0.25 * (4 - row), 0.25 + 0.5 * row, 0);
            scene.bodies.push_back(box);
        }
    BodyDef ball;
    ball.name = "ball";
    ball.shape = ShapeDef::sphere(0.2);
    ball.position = Vec3(-6, 1.0, 0);
    ball.linearVelocity = Vec3(12, 2, 0);
    ball.mass = 20.0;
    scene.bodies.push_back(ball);
    return scene;
}

}  // namespace

int runSimultaneous(const DemoOptions& o, const std::vector<std::string>& backends) {
    struct Run {
        std::string backend;
        std::unique_ptr<World> world;
        std::vector<Body> bodies;
        std::chrono::steady_clock::duration stepping{};
    };
    std::vector<Run> runs;
    for (const std::string& name : backends) {
        if (!backendInfo(name).capabilities.planar) {
            std::printf("  %s skipped: no planar worlds\n", name.c_str());
            continue;
        }
        const Scene scene = pyramidScene(name);
        Run r{name, std::make_unique<World>(scene.settings, scene.materials), {}, {}};
        r.bodies = createSceneObjects(*r.world, scene).bodies;
        runs.push_back(std::move(r));
    }
    if (runs.empty()) throw Error("--backends: none of the given backends runs planar worlds");
    TrajectoryWriter trajectory(o.out);
    // Each world's bodies under the backend's name: "ode/box_0_1".
    const auto write = [&](long long step) {
        for (const Run& r : runs) {
            std::vector<Body> renamed;
            for (const Body& b : r.bodies) renamed.push_back(b);
            trajectory.write(step, r.world->time(), renamed, r.backend + "/");
        }
    };
    write(0);
    const long long steps = std::llround(o.seconds / runs.front().world->settings().timeStep);
    for (long long step = 1; step <= steps; ++step) {
        for (Run& r : runs) {  // stepped together: every world advances one step before the next
            const auto start = std::chrono::steady_clock::now();
            r.world->step();
            r.stepping += std::chrono::steady_clock::now() - start;
        }
        write(step);
        for (const Run& r : runs)
            if (const std::string bad = firstNonFinite(r.bodies); !bad.empty()) {
                trajectory.finish();
                std::fprintf(stderr, "non-finite state: body \"%s\" on %s at t = %g s\n", bad.c_str(), r.backend.c_str(), r.world->time());
                return 1;
            }
    }
    trajectory.finish();
    std::printf("simultaneous: the same planar pyramid hit by a ball in %zu worlds, %lld steps together\n", runs.size(), steps);
    for (const Run& r : runs) {
        double worst = 0.0;
        for (std::size_t i = 0; i < r.bodies.size(); ++i)
            worst = std::max(worst, (r.bodies[i].position() - runs.front().bodies[i].position()).norm());
        std::printf("  %-8s %.3f ms per step, farthest body from %s's: %.3f m\n", r.backend.c_str(),
                    std::chrono::duration<double, std::milli>(r.stepping).count() / static_cast<double>(steps),
                    runs.front().backend.c_str(), worst);
    }
    return 0;
}

}  // namespace anyphys::demo
