// Native determinism: a pile of mixed shapes gives bit-identical trajectories run after run, for
// any number of workers, and with a task system that runs the work in a different order or late.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/thread_pool.hpp"
#include "contact_helpers.hpp"
#include "late_reverse_tasks.hpp"
#include "solver/contact_constraint.hpp"

namespace anyphys {
namespace {

using test::LateReverseTasks;

/// Every body's state, bit for bit, after `steps` steps of a tumbling pile. `planar`: the pile
/// in the XY plane (a planar world, which has its own contact kernels). `events`, if given,
/// receives every step's contact events flattened (ids, phase, normal, points): one worker
/// reports contacts in one walk, several in two over chunks, and both must give the same events.
std::vector<BodyState> runPile(int workers, TaskSystem* tasks, int steps, bool planar = false,
                               std::vector<double>* events = nullptr) {
    WorldSettings settings;
    settings.planar = planar;
    settings.workers = workers;
    settings.taskSystem = tasks;
    MaterialLibrary materials;
    materials.add("bouncy", {0.4, 0.5, 1000.0});
    World world(settings, materials);
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::box({20, 1, 20});
    ground.position = {0, -1, 0};
    world.createBody(ground);
    std::vector<Body> bodies;
    for (int i = 0; i < (planar ? 96 : 240); ++i) {
        BodyDef d;
        d.allowSleep = false;
        const int kind = i % 4;
        d.shape = kind == 0   ? ShapeDef::sphere(0.3)
                  : kind == 1 ? ShapeDef::capsule(0.2, 0.3)
                              : ShapeDef::box({0.4, 0.25, 0.3});
        d.material = i % 5 == 0 ? "bouncy" : "";
        if (planar) {
            d.position = {(i % 8) * 0.9 - 3.1, 0.5 + (i / 8) * 0.8, 0.0};
            d.orientation = Quat(Eigen::AngleAxisd(0.3 * i, Vec3::UnitZ()));
            d.angularVelocity = {0.0, 0.0, 0.1 * (i % 3) - 0.1};
        } else {
            d.position = {(i % 6) * 0.9 - 2.2, 0.5 + (i / 36) * 0.8, ((i / 6) % 6) * 0.9 - 2.2};
            d.orientation = Quat(Eigen::AngleAxisd(0.3 * i, Vec3(1, 2, 3).normalized()));
            d.angularVelocity = {0.1 * (i % 3), 0.2, -0.1 * (i % 2)};
        }
        bodies.push_back(world.createBody(d));
    }
    for (int s = 0; s < steps; ++s) {
        world.step();
        if (!events) continue;
        for (const ContactEvent& e : world.lastEvents()) {
            events->insert(events->end(), {double(s), double(e.bodyA.index), double(e.bodyB.index), double(e.phase),
                                           e.normal.x(), e.normal.y(), e.normal.z()});
            for (const ContactPoint& p : e.points)
                events->insert(events->end(), {p.position.x(), p.position.y(), p.position.z(), p.depth, p.normalImpulse});
        }
    }
    std::vector<BodyState> states;
    for (const Body& b : bodies) states.push_back(b.state());
    return states;
}

void expectIdentical(const std::vector<BodyState>& a, const std::vector<BodyState>& b, const char* what) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        const bool same = std::memcmp(a[i].position.data(), b[i].position.data(), sizeof(double) * 3) == 0 &&
                          std::memcmp(a[i].orientation.coeffs().data(), b[i].orientation.coeffs().data(), sizeof(double) * 4) == 0 &&
                          std::memcmp(a[i].linearVelocity.data(), b[i].linearVelocity.data(), sizeof(double) * 3) == 0 &&
                          std::memcmp(a[i].angularVelocity.data(), b[i].angularVelocity.data(), sizeof(double) * 3) == 0;
        ASSERT_TRUE(same) << what << ": body " << i << " differs: " << a[i].position.transpose() << " vs "
                          << b[i].position.transpose();
    }
}

constexpr int kSteps = 150;  // 2.5 s: the pile falls, collides and tumbles, so contacts come and go

TEST(NativeDeterminism, SameRunTwiceIsBitIdentical) {
    const auto first = runPile(1, nullptr, kSteps);
    expectIdentical(first, runPile(1, nullptr, kSteps), "second run");
    // The pile really moved and piled up: a run where nothing happens would prove nothing.
    double lowest = 1e9;
    for (const BodyState& s : first) lowest = std::min(lowest, s.position.y());
    EXPECT_LT(lowest, 0.5);
}

TEST(NativeDeterminism, WorkerCountDoesNotChangeTheResult) {
    std::vector<double> oneEvents, twoEvents, poolEvents;
    const auto one = runPile(1, nullptr, kSteps, false, &oneEvents);
    expectIdentical(one, runPile(2, nullptr, kSteps, false, &twoEvents), "2 workers");
    expectIdentical(one, runPile(4, nullptr, kSteps), "4 workers");
    ThreadPool shared(3);
    expectIdentical(one, runPile(1, &shared, kSteps, false, &poolEvents), "a game's pool of 3");
    EXPECT_GT(oneEvents.size(), 1000u);  // the pile touched: there were events to compare
    EXPECT_TRUE(oneEvents == twoEvents) << "2 workers report other contact events";
    EXPECT_TRUE(oneEvents == poolEvents) << "a game's pool of 3 reports other contact events";
}

TEST(NativeDeterminism, PlanarWorkerCountDoesNotChangeTheResult) {
    std::vector<double> oneEvents, twoEvents;
    const auto one = runPile(1, nullptr, kSteps, true, &oneEvents);
    expectIdentical(one, runPile(2, nullptr, kSteps, true, &twoEvents), "planar, 2 workers");
    EXPECT_GT(oneEvents.size(), 1000u);
    EXPECT_TRUE(oneEvents == twoEvents) << "planar, 2 workers report other contact events";
    LateReverseTasks tasks(3);
    expectIdentical(one, runPile(1, &tasks, kSteps, true), "planar, late, reversed task system");
    double lowest = 1e9;  // the planar pile fell and piled up too
    for (const BodyState& s : one) lowest = std::min(lowest, s.position.y());
    EXPECT_LT(lowest, 0.5);
}

TEST(NativeDeterminism, LateAndReversedTasksGiveTheSameResult) {
    LateReverseTasks tasks(3);
    expectIdentical(runPile(1, nullptr, kSteps), runPile(1, &tasks, kSteps), "late, reversed task system");
}

/// The state after `steps` of a box landing on a corner at 6 m/s (a 1-point manifold, whose friction
/// turns the box and so moves its normal row) on a wide ground, alone or beside `companions` boxes
/// resting on the same ground 3 m apart. All those ground contacts share one colour, so the resting
/// boxes' 4-point manifolds sit in the landing box's wide records.
BodyState cornerBesideBoxes(int companions, bool planar, int steps) {
    WorldSettings settings;
    settings.planar = planar;
    World world(settings);
    BodyDef ground = test::boxDef("ground", {100, 1, 2}, {40, -1, 0});
    ground.type = BodyType::Static;
    world.createBody(ground);
    BodyDef corner;
    corner.allowSleep = false;
    corner.shape = ShapeDef::box({0.3, 0.3, 0.3});
    corner.position = {0, 2.1, 0};
    // A corner lowest (in a planar world an edge seen end on: one point), sliding across as it lands.
    corner.orientation = planar ? Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()))
                                : Quat(Eigen::AngleAxisd(0.6, Vec3(1, 0, 1).normalized()));
    corner.linearVelocity = {1.0, 0, 0};
    const Body probe = world.createBody(corner);
    for (int i = 0; i < companions; ++i) {
        BodyDef box;
        box.allowSleep = false;
        box.shape = ShapeDef::box({0.5, 0.5, 0.5});
        box.position = {3.0 * (i + 1), 0.5, 0};
        world.createBody(box);
    }
    for (int s = 0; s < steps; ++s) world.step();
    return probe.state();
}

// A manifold's lane in a wide record computes what it would alone: a lane whose sweep an impact
// moved is swept again only in the rows it has (a 1-point landing's row is not swept again because
// a resting box's 4-point manifold shares its record), and only lanes that bounced take the
// restitution stage's later passes. So what a body does never hangs on which constraints fill the
// other lanes, and the lane count is the solver's own choice. (Before, the box landing beside 11
// boxes ended elsewhere than alone.)
TEST(NativeDeterminism, ABodyDoesNotFeelTheOtherLanesOfItsRecords) {
    constexpr int kLandingSteps = 90;  // lands near step 36, tips onto a face and slides
    for (const bool planar : {false, true}) {
        const BodyState alone = cornerBesideBoxes(0, planar, kLandingSteps);
        expectIdentical({alone}, {cornerBesideBoxes(11, planar, kLandingSteps)}, planar ? "planar, beside boxes" : "beside boxes");
        EXPECT_LT(alone.position.y(), 0.45);  // it landed: the impact happened inside the run
    }
}

// The per-pass kernels exist in a baseline (SSE2) and an AVX2 build, chosen by the CPU: both do
// the same lane-by-lane arithmetic in the same order without fused multiply-add.
TEST(NativeDeterminism, InstructionSetDoesNotChangeTheResult) {
    const bool initial = native::contactKernelsUseAvx2();
    native::setContactKernelsAvx2(false);
    const auto baseline = runPile(1, nullptr, kSteps);
    if (!native::setContactKernelsAvx2(true)) {
        native::setContactKernelsAvx2(initial);
        GTEST_SKIP() << "this CPU has no AVX2: only the baseline kernels can run";
    }
    const auto avx2 = runPile(1, nullptr, kSteps);
    native::setContactKernelsAvx2(false);
    const auto planarBaseline = runPile(1, nullptr, kSteps, true);
    native::setContactKernelsAvx2(true);
    const auto planarAvx2 = runPile(1, nullptr, kSteps, true);
    native::setContactKernelsAvx2(initial);
    expectIdentical(baseline, avx2, "AVX2 kernels");
    expectIdentical(planarBaseline, planarAvx2, "planar AVX2 kernels");
}

}  // namespace
}  // namespace anyphys
