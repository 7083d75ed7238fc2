// Worlds of every built backend stepped at the same time on different threads (docs/threads.md):
// one World per thread is the supported pattern, including two worlds of the same backend and
// worlds created on one thread and stepped on another. Run under ThreadSanitizer by
// scripts/tsan.sh; in the normal suite it checks that each world's results are bit-identical to
// the same world stepped alone (a shared global inside an engine shows up as a difference).
#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::test {
namespace {

constexpr int kSteps = 90;  // 1.5 s: the pile settles and the chain swings (contacts, joints, sleep off)

struct Job {
    std::string backend;
    int workers = 1;
};

WorldSettings settingsFor(const Job& job) {
    const BackendInfo info = backendInfo(job.backend);
    WorldSettings s;
    s.backend = job.backend;
    s.planar = info.capabilities.dimensions == 2;
    s.workers = job.workers;
    return s;
}

// A box pile on a ground box, a three-link hinge chain and a ball thrown into the pile.
void build(World& world) {
    const bool planar = world.settings().planar;
    BodyDef ground;
    ground.name = "ground";
    ground.type = BodyType::Static;
    ground.position = Vec3(0, -0.5, 0);
    ground.shape = ShapeDef::box(Vec3(20, 0.5, planar ? 0.5 : 20));
    world.createBody(ground);
    for (int i = 0; i < 6; ++i) {
        BodyDef box;
        box.name = "box" + std::to_string(i);
        box.position = Vec3(0.05 * (i % 2), 0.5 + 1.01 * i, 0);
        box.shape = ShapeDef::box(Vec3(0.5, 0.5, 0.5));
        box.allowSleep = false;
        world.createBody(box);
    }
    Body previous;
    for (int i = 0; i < 3; ++i) {
        BodyDef link;
        link.name = "link" + std::to_string(i);
        link.position = Vec3(4 + 0.6 * i, 5, 0);
        link.shape = ShapeDef::capsule(0.1, 0.2);
        link.allowSleep = false;
        Body b = world.createBody(link);
        JointDef j;
        j.type = JointType::Hinge;
        j.bodyA = previous;
        j.bodyB = b;
        j.anchor = Vec3(4 + 0.6 * i - 0.3, 5, 0);
        j.axis = Vec3::UnitZ();
        world.createJoint(j);
        previous = b;
    }
    BodyDef ball;
    ball.name = "ball";
    ball.position = Vec3(-4, 2, 0);
    ball.linearVelocity = Vec3(8, 2, 0);
    ball.shape = ShapeDef::sphere(0.3);
    world.createBody(ball);
}

// Steps the world, querying it on the way as a game would; returns every body's final state.
std::vector<BodyState> run(World& world) {
    for (int i = 0; i < kSteps; ++i) {
        world.step();
        (void)world.raycast(Vec3(-10, 1, 0), Vec3(1, 0, 0), 30);
    }
    std::vector<BodyState> out;
    for (const Body& b : world.bodies()) out.push_back(b.state());
    return out;
}

std::vector<Job> jobs() {
    std::vector<Job> out;
    for (const BackendInfo& b : availableBackends()) {
        out.push_back({b.name, 1});
        out.push_back({b.name, 1});  // a second world of the same backend at the same time
        if (b.capabilities.parameters.count("settings.workers")) out.push_back({b.name, 2});  // with its own pool
    }
    return out;
}

void expectSame(const std::vector<BodyState>& alone, const std::vector<BodyState>& together, const Job& job) {
    ASSERT_EQ(alone.size(), together.size()) << job.backend;
    for (std::size_t i = 0; i < alone.size(); ++i) {
        // Bit-identical: the same world stepped alone and beside others must not differ at all.
        EXPECT_EQ(alone[i].position, together[i].position) << job.backend << " workers " << job.workers << " body " << i;
        EXPECT_EQ(alone[i].linearVelocity, together[i].linearVelocity) << job.backend << " body " << i;
        EXPECT_TRUE(alone[i].position.allFinite()) << job.backend << " body " << i;
    }
}

// Every world created on this thread, then each stepped on a thread of its own, all at once.
TEST(ConcurrentWorlds, EveryBackendSteppedOnItsOwnThreadMatchesSteppingAlone) {
    const std::vector<Job> all = jobs();
    std::vector<std::vector<BodyState>> alone;
    for (const Job& job : all) {
        World world(settingsFor(job));
        build(world);
        alone.push_back(run(world));
    }
    std::vector<std::unique_ptr<World>> worlds;
    for (const Job& job : all) {
        worlds.push_back(std::make_unique<World>(settingsFor(job)));
        build(*worlds.back());
    }
    std::vector<std::vector<BodyState>> together(all.size());
    {
        std::vector<std::jthread> threads;
        for (std::size_t i = 0; i < all.size(); ++i)
            threads.emplace_back([&, i] { together[i] = run(*worlds[i]); });
    }
    for (std::size_t i = 0; i < all.size(); ++i) expectSame(alone[i], together[i], all[i]);
}

// Two threads, each creating, stepping and destroying worlds of every backend in turn, offset so
// that different backends (and the same one) overlap: construction and teardown race-free too.
TEST(ConcurrentWorlds, WorldsMadeAndDestroyedOnTwoThreads) {
    const std::vector<BackendInfo> backends = availableBackends();
    auto worker = [&](std::size_t offset, std::vector<std::vector<BodyState>>& out) {
        for (std::size_t k = 0; k < backends.size(); ++k) {
            World world(settingsFor({backends[(k + offset) % backends.size()].name, 1}));
            build(world);
            out.push_back(run(world));
        }
    };
    std::vector<std::vector<BodyState>> first, second;
    {
        std::jthread a([&] { worker(0, first); });
        std::jthread b([&] { worker(1, second); });
    }
    for (std::size_t k = 0; k < backends.size(); ++k) {
        World world(settingsFor({backends[k].name, 1}));
        build(world);
        const std::vector<BodyState> alone = run(world);
        expectSame(alone, first[k], {backends[k].name, 1});
        expectSame(alone, second[(k + backends.size() - 1) % backends.size()], {backends[k].name, 1});
    }
}

}  // namespace
}  // namespace anyphys::test
