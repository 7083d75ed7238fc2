// Native pipeline: stages a world does not need are not run at all.
#include <gtest/gtest.h>

#include "anyphys/backends.hpp"
#include "anyphys/peers/gyroscopic.hpp"
#include "native_world.hpp"

namespace anyphys::native {
namespace {

using Names = std::vector<std::string>;

// Default settings as the layer hands them to a peer: solver, substeps and iterations resolved.
WorldSettings resolvedDefaults() { return withBackendDefaults(WorldSettings{}, backendInfo("native").capabilities); }

BodyPeerDef dynamicBody(const Vec3& inertia, GyroscopicMode mode) {
    BodyPeerDef d;
    d.def.gyroscopic = mode;
    d.mass = {1.0, inertia};
    return d;
}

TEST(NativePipeline, EmptyWorldRunsNoStage) {
    NativeWorld world{resolvedDefaults()};
    EXPECT_EQ(world.activeStageNames(), Names{});
}

TEST(NativePipeline, OnlyNeededStagesRun) {
    NativeWorld world{resolvedDefaults()};
    auto sphere = world.createBody(dynamicBody(Vec3(1, 1, 1), GyroscopicMode::Implicit));
    world.setEffects(Effect::Gravity | Effect::Gyroscopic);
    // Isotropic inertia: the gyroscopic term is identically zero, so its stage is skipped.
    EXPECT_EQ(world.activeStageNames(), Names{"integrate"});
    auto box = world.createBody(dynamicBody(Vec3(1, 2, 3), GyroscopicMode::Implicit));
    EXPECT_EQ(world.activeStageNames(), (Names{"gyroscopic_implicit", "integrate"}));
    world.setEffects(Effect::Gravity | Effect::Gyroscopic | Effect::UserForces);
    EXPECT_EQ(world.activeStageNames(), (Names{"gyroscopic_implicit", "integrate", "clear_forces"}));
    world.setEffects(Effect::Gravity);
    EXPECT_EQ(world.activeStageNames(), Names{"integrate"});
    world.setEffects(Effect::Gravity | Effect::Contacts | Effect::Sleeping | Effect::ContinuousCollision);
    EXPECT_EQ(world.activeStageNames(),
              (Names{"collide", "collect_constraints", "integrate", "solve_constraints", "continuous", "sleep"}));
    world.setEffects(Effect::Gravity);
    world.destroyBody(*box);
    world.destroyBody(*sphere);
    EXPECT_EQ(world.activeStageNames(), Names{});
}

// Destroying a body in the middle keeps the others' peers pointing at their own state.
TEST(NativePipeline, DestroyKeepsOtherPeersConsistent) {
    NativeWorld world{resolvedDefaults()};
    std::vector<std::unique_ptr<BodyPeer>> peers;
    for (int i = 0; i < 4; ++i) {
        BodyPeerDef d = dynamicBody(Vec3(1, 1, 1), GyroscopicMode::None);
        d.def.position = Vec3(i, 0, 0);
        peers.push_back(world.createBody(d));
    }
    world.destroyBody(*peers[1]);
    peers[1].reset();
    EXPECT_EQ(peers[0]->state().position.x(), 0);
    EXPECT_EQ(peers[2]->state().position.x(), 2);
    EXPECT_EQ(peers[3]->state().position.x(), 3);
}

// A sleeping island goes when its last body is destroyed. It used to stay, empty, in the world's
// island map: the soak run (spawning and removing ragdolls and boxes, many of them asleep) grew
// its heap by about 22 bytes per spawn, 2 MiB of resident memory over 1e6 steps.
TEST(NativePipeline, DestroyingASleepingIslandsBodiesFreesTheIsland) {
    NativeWorld world{resolvedDefaults()};
    for (int round = 0; round < 50; ++round) {
        auto a = world.createBody(dynamicBody(Vec3(1, 1, 1), GyroscopicMode::None));
        auto b = world.createBody(dynamicBody(Vec3(1, 1, 1), GyroscopicMode::None));
        const std::uint32_t ia = static_cast<NativeBodyPeer&>(*a).index(), ib = static_cast<NativeBodyPeer&>(*b).index();
        world.sleepIsland({ia, ib});
        ASSERT_EQ(world.sleepingIslandCount(), 1u);
        world.destroyBody(*a);
        EXPECT_EQ(world.sleepingIslandCount(), 1u);  // b still sleeps in it
        world.destroyBody(*b);
        EXPECT_EQ(world.sleepingIslandCount(), 0u) << "round " << round;
    }
}

// The implicit gyroscopic solve is the backward-Euler solution: its residual vanishes.
TEST(NativeGyroscopic, ImplicitSolveSatisfiesBackwardEuler) {
    const Vec3 inertia(1, 2, 3), w0(0.3, 5, -1);
    const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    const double h = 1.0 / 60;
    const Vec3 w1 = q.conjugate() * gyroscopic::solveImplicit(q * w0, q, inertia, h);
    const Vec3 residual = inertia.cwiseProduct(w1 - w0) + h * w1.cross(inertia.cwiseProduct(w1));
    EXPECT_LT(residual.norm(), 1e-12);
    // Backward Euler never adds kinetic energy.
    EXPECT_LE(w1.dot(inertia.cwiseProduct(w1)), w0.dot(inertia.cwiseProduct(w0)));
}

// The explicit term is Euler's: I dw/dt = -w x I w.
TEST(NativeGyroscopic, ExplicitTermMatchesEulersEquations) {
    const Vec3 inertia(1, 2, 3), w(1, 2, 3);
    const Vec3 alpha = gyroscopic::acceleration(w, Quat::Identity(), inertia);
    const Vec3 expected = -(w.cross(inertia.cwiseProduct(w))).cwiseQuotient(inertia);
    EXPECT_LT((alpha - expected).norm(), 1e-15);
}

}  // namespace
}  // namespace anyphys::native
