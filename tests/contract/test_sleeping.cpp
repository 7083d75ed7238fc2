// Bodies at rest fall asleep by island and wake when something hits them or the user acts.
#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class SleepingTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
    std::string missing() const {
        return lacking(caps(), {ShapeType::Box, ShapeType::Sphere, ShapeType::Plane},
                       Effect::Contacts | Effect::Friction | Effect::Sleeping);
    }
};

/// A 2 x 2 x 2 pile of unit boxes resting on the ground, built touching (2 x 2 in a planar world).
std::vector<Body> buildPile(World& world) {
    world.createBody(groundDef());
    std::vector<Body> pile;
    const int depth = world.settings().planar ? 1 : 2;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int z = 0; z < depth; ++z)
                pile.push_back(world.createBody(boxDef("box_" + std::to_string(pile.size()), Vec3(0.5, 0.5, 0.5),
                                                       Vec3(x, 0.5 + y, z))));
    return pile;
}

bool allAsleep(const std::vector<Body>& bodies) {
    for (const Body& b : bodies)
        if (b.isAwake()) return false;
    return true;
}

/// Steps until every body sleeps or `limit` seconds pass; returns the time they all slept (or -1).
double stepUntilAsleep(World& world, const std::vector<Body>& bodies, double limit) {
    while (world.time() < limit) {
        world.step();
        if (allAsleep(bodies)) return world.time();
    }
    return -1.0;
}

// A settled pile falls asleep: at rest from the start, it needs timeToSleep (0.5 s) plus the
// time to settle; 3 s is six times that.
TEST_P(SleepingTest, SettledPileFallsAsleep) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    const std::vector<Body> pile = buildPile(world);
    const double asleepAt = stepUntilAsleep(world, pile, 3.0);
    report(backend() + " pile asleep at", asleepAt, "s");
    EXPECT_GT(asleepAt, 0.0) << "the pile was still awake after 3 s";
    EXPECT_GE(asleepAt, world.settings().timeToSleep - 1e-9) << "bodies must rest timeToSleep before sleeping";
}

// A fast ball hitting the sleeping pile wakes it, and the hit box moves.
TEST_P(SleepingTest, SleepingPileWakesWhenHit) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    const std::vector<Body> pile = buildPile(world);
    ASSERT_GT(stepUntilAsleep(world, pile, 3.0), 0.0) << "precondition: the pile sleeps";
    const Vec3 before = pile[0].position();  // bottom layer, x = 0, z = 0: the ball comes from -x

    BodyDef def = ballDef("ball", 0.25, Vec3(-3, 0.5, 0));
    def.linearVelocity = Vec3(20, 0, 0);
    def.density = 8000;  // a heavy ball: ~520 kg at 20 m/s against 1000 kg boxes
    world.createBody(def);
    bool woke = false;
    for (int i = 0; i < 30 && !woke; ++i) {  // reaches the pile after ~0.12 s
        world.step();
        woke = pile[0].isAwake();
    }
    EXPECT_TRUE(woke) << "the hit box stayed asleep";
    for (int i = 0; i < 30; ++i) world.step();
    const double moved = (pile[0].position() - before).norm();
    report(backend() + " hit box moved", moved, "m");
    // 5 cm: momentum 10400 N s shared with 1000 kg boxes moves the hit box decimetres in 0.5 s.
    EXPECT_GT(moved, 0.05);
}

// The user wakes a body with wake(); a body with allowSleep = false never sleeps.
TEST_P(SleepingTest, WakeAndAllowSleep) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    world.createBody(groundDef());
    Body sleeper = world.createBody(boxDef("sleeper", Vec3(0.5, 0.5, 0.5), Vec3(0, 0.5, 0)));
    BodyDef restless = boxDef("restless", Vec3(0.5, 0.5, 0.5), Vec3(3, 0.5, 0));
    restless.allowSleep = false;
    Body awake = world.createBody(restless);
    ASSERT_GT(stepUntilAsleep(world, {sleeper}, 3.0), 0.0);
    EXPECT_TRUE(awake.isAwake()) << "allowSleep = false";
    sleeper.wake();
    EXPECT_TRUE(sleeper.isAwake());
}

ANYPHYS_CONTRACT_SUITE(SleepingTest);

}  // namespace
}  // namespace anyphys::test
