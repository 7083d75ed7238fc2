// The Box2D backend's contact reports: the inline world manifold is Box2D's own, steady steps with
// events on allocate nothing in the layer or glue, and a world whose bodies all sleep reports nothing.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "../step_allocations.hpp"
#include "box2d_manifold.hpp"
#include "box2d_test_helpers.hpp"

namespace anyphys::box2d::test {
namespace {

// Balls side by side (e_circles), boxes and balls on the ground edge and on boxes (e_faceA), a
// tilted box landing corner first on a flat box created after it (the flat face, fixture B's, is
// the reference: e_faceB), a capsule's pieces: every touching contact's manifold matches
// b2Contact::GetWorldManifold.
TEST(Box2dContacts, InlineWorldManifoldIsBox2dsOwn) {
    World world(planarSettings());
    world.createBody(ground());
    BodyDef tilted = box("", Vec3(0.5, 0.5, 0.5), Vec3(20, 2, 0));
    tilted.orientation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()));
    world.createBody(tilted);
    world.createBody(box("", Vec3(2, 0.25, 0.5), Vec3(20, 0.25, 0)));
    world.createBody(ball("", 0.25, Vec3(-6, 0.25, 0)));
    world.createBody(ball("", 0.25, Vec3(-5.5, 0.25, 0)));
    for (int i = 0; i < 6; ++i) {
        world.createBody(box("", Vec3(0.5, 0.3, 0.5), Vec3(1.5 * i, 0.3 + 0.6 * (i % 2), 0)));
        world.createBody(ball("", 0.25, Vec3(1.5 * i + 0.2, 1.5 + 0.5 * i, 0)));
    }
    BodyDef capsule = anyphys::test::boxDef("", Vec3(0.5, 0.5, 0.5), Vec3(-3, 1, 0));
    capsule.shape = ShapeDef::capsule(0.3, 0.4);
    world.createBody(capsule);
    int compared = 0;
    std::set<int> types;
    for (int step = 0; step < 90; ++step) {
        world.step();
        for (b2Contact* c = world.native<b2World>()->GetContactList(); c; c = c->GetNext()) {
            if (!c->IsTouching()) continue;
            b2WorldManifold expected;
            c->GetWorldManifold(&expected);
            const WorldManifold got = worldManifold(*c);
            types.insert(c->GetManifold()->type);
            EXPECT_FLOAT_EQ(got.normal.x, expected.normal.x);
            EXPECT_FLOAT_EQ(got.normal.y, expected.normal.y);
            for (int32 p = 0; p < c->GetManifold()->pointCount; ++p) {
                EXPECT_FLOAT_EQ(got.points[p].x, expected.points[p].x);
                EXPECT_FLOAT_EQ(got.points[p].y, expected.points[p].y);
                EXPECT_FLOAT_EQ(got.separations[p], expected.separations[p]);
            }
            ++compared;
        }
    }
    EXPECT_GT(compared, 100);
    EXPECT_EQ(types.size(), 3u) << "circles, faceA and faceB manifolds should all occur";
}

TEST(Box2dContacts, SteadyStepsWithEventsAllocateNothing) {
    World world(planarSettings());
    world.createBody(ground());
    for (int x = 0; x < 10; ++x)
        for (int y = 0; y < 3; ++y) {
            BodyDef def = box("", Vec3(0.5, 0.5, 0.5), Vec3(1.2 * x, 0.5 + y, 0));
            def.allowSleep = false;
            world.createBody(def);
        }
    ASSERT_TRUE(world.activeEffects().has(Effect::Events));
    struct Counting : ContactListener {
        int stays = 0;
        void onCollisionStay(const ContactEvent&) override { ++stays; }
    } listener;
    for (bool listening : {false, true}) {
        SCOPED_TRACE(listening ? "with a listener" : "without listeners");
        if (listening) world.addListener(&listener);
        for (int i = 0; i < 30; ++i) world.step();
        anyphys::test::StepAllocations::start();
        for (int i = 0; i < 30; ++i) world.step();
        EXPECT_EQ(anyphys::test::StepAllocations::stop(), 0u);
        EXPECT_GE(world.lastEvents().size(), 30u);  // every box touches the one below or the ground
    }
    EXPECT_GE(listener.stays, 30 * 30);
}

TEST(Box2dContacts, AllAsleepReportsNothing) {
    World world(planarSettings());
    world.createBody(ground());
    std::vector<Body> boxes;
    for (int x = 0; x < 4; ++x) boxes.push_back(world.createBody(box("", Vec3(0.5, 0.5, 0.5), Vec3(1.2 * x, 0.5, 0))));
    for (int i = 0; i < 300 && boxes.front().isAwake(); ++i) world.step();
    for (const Body& b : boxes) ASSERT_FALSE(b.isAwake());
    world.step();
    EXPECT_TRUE(world.lastEvents().empty());
    boxes.front().wake();
    world.step();
    ASSERT_EQ(world.lastEvents().size(), 1u);  // its pair with the ground: kept asleep, now a stay
    EXPECT_EQ(world.lastEvents().front().phase, ContactPhase::Stay);
}

// A plane is a run of Box2D edges (box2d_shapes.cpp), joined 1 km from the origin. A box resting
// across that joint touches two of them: one contact for the pair (the layer's events are per body
// pair) holding the points of both, so the event has the whole face and carries the whole
// weight; a box on one edge alone is one contact of its own points (the report merges only when
// a pair touches twice: box2d_world.cpp).
TEST(Box2dContacts, BoxAcrossTwoPlaneEdgesIsOneContact) {
    for (const double x : {1000.0, 1000.4, 500.0}) {
        World world(planarSettings());
        world.createBody(ground());
        BodyDef def = box("box", Vec3(0.5, 0.5, 0.5), Vec3(x, 0.5, 0));
        def.allowSleep = false;  // a sleeping pair has no events
        Body b = world.createBody(def);
        for (int i = 0; i < 60; ++i) world.step();
        const auto& events = world.lastEvents();
        ASSERT_EQ(events.size(), 1u) << "box at x = " << x;
        double impulse = 0.0, left = x, right = x;
        for (const ContactPoint& p : events.front().points) {
            impulse += p.normalImpulse;
            left = std::min(left, p.position.x());
            right = std::max(right, p.position.x());
        }
        // The whole bottom face, both corners (within the 2.5 mm skin): across the joint, one
        // edge's contact alone holds only the corner on its side.
        EXPECT_LT(left, x - 0.49) << "box at x = " << x;
        EXPECT_GT(right, x + 0.49) << "box at x = " << x;
        // Resting: one step's impulse is the box's weight times the step, within 1 % (the solver's
        // iterations leave a fraction of a per cent of a settling box's load unsettled).
        const double weight = b.massProperties().mass * 9.81 / 60.0;
        EXPECT_NEAR(impulse, weight, 0.01 * weight) << "box at x = " << x;
        EXPECT_NEAR(b.position().y(), 0.5, 1e-3) << "box at x = " << x;
        report("box across plane edges at x = " + std::to_string(x) + ": points", static_cast<double>(events.front().points.size()));
    }
}

}  // namespace
}  // namespace anyphys::box2d::test
