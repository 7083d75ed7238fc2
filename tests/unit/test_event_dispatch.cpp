// World's event delivery, which reuses its buffers every step: a listener that steps the world
// from a callback does not disturb the events still being delivered, and a reference to
// lastEvents() always shows the last step's events.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys {
namespace {

/// The first built backend with everything these tests use (capabilities, never names).
std::string eventBackend() {
    for (const BackendInfo& info : availableBackends()) {
        const Capabilities& c = info.capabilities;
        if (c.effects.has(Effect::Contacts) && c.effects.has(Effect::Events) && c.shapes.contains(ShapeType::Sphere) &&
            c.shapes.contains(ShapeType::Plane))
            return info.name;
    }
    return "";
}

/// A row of balls dropped onto the ground, landing in the same step (several events per step).
World& dropBalls(World& world, int count) {
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::plane({0, 1, 0}, 0.0);
    world.createBody(ground);
    for (int i = 0; i < count; ++i) {
        BodyDef ball;
        ball.shape = ShapeDef::sphere(0.25);
        ball.position = {1.0 * i, 0.5, 0};
        world.createBody(ball);
    }
    return world;
}

WorldSettings settingsFor(const std::string& backend) {
    WorldSettings s;
    s.backend = backend;
    s.planar = backendInfo(backend).capabilities.dimensions == 2;
    return s;
}

TEST(EventDispatch, ListenerSteppingTheWorldKeepsTheEventsBeingDelivered) {
    const std::string backend = eventBackend();
    if (backend.empty()) GTEST_SKIP() << "no backend with contacts, events, spheres and planes";
    World world(settingsFor(backend));
    dropBalls(world, 6);
    struct Stepping : ContactListener {
        World* world = nullptr;
        int entered = 0;  // delivered in the step that lands
        bool stepped = false;
        void onCollisionEnter(const ContactEvent&) override {
            ++entered;
            if (!stepped) {
                stepped = true;
                world->step();  // replaces lastEvents() while this delivery is under way
            }
        }
    } listener;
    listener.world = &world;
    world.addListener(&listener);
    std::vector<ContactEvent> landing;
    for (int i = 0; i < 60 && !listener.stepped; ++i) {
        world.step();
        if (!listener.stepped) continue;
        // The nested step's events are the last ones now; the outer delivery went on with its own.
        landing = world.lastEvents();
    }
    ASSERT_TRUE(listener.stepped);
    EXPECT_EQ(listener.entered, 6) << "every ball's landing was delivered once";
    for (const ContactEvent& e : landing) EXPECT_NE(e.phase, ContactPhase::Enter) << "the nested step sees no new landings";
}

TEST(EventDispatch, ReferenceToLastEventsFollowsEveryStep) {
    const std::string backend = eventBackend();
    if (backend.empty()) GTEST_SKIP() << "no backend with contacts, events, spheres and planes";
    World world(settingsFor(backend));
    dropBalls(world, 3);
    const std::vector<ContactEvent>& events = world.lastEvents();
    int steps = 0;
    while (events.empty() && steps++ < 60) world.step();
    ASSERT_EQ(events.size(), 3u);
    for (const ContactEvent& e : events) {
        EXPECT_EQ(e.phase, ContactPhase::Enter);
        EXPECT_FALSE(e.points.empty());
    }
    world.step();
    ASSERT_EQ(events.size(), 3u);
    for (const ContactEvent& e : events) EXPECT_EQ(e.phase, ContactPhase::Stay);
    EXPECT_EQ(&events, &world.lastEvents());
}

}  // namespace
}  // namespace anyphys
