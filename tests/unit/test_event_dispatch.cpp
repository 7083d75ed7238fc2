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

/// Balls of restitution 0.6 dropped from several heights: they land, bounce off and land again
/// at different steps, so the steps have enters, stays and exits.
MaterialLibrary bouncyMaterial() {
    Material bouncy;
    bouncy.restitution = 0.6;
    MaterialLibrary library;
    library.add("bouncy", bouncy);
    return library;
}

World& bouncingBalls(World& world) {
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::plane({0, 1, 0}, 0.0);
    ground.material = "bouncy";
    world.createBody(ground);
    for (int i = 0; i < 4; ++i) {
        BodyDef ball;
        ball.shape = ShapeDef::sphere(0.25);
        ball.position = {1.0 * i, 0.6 + 0.3 * i, 0};
        ball.material = "bouncy";
        world.createBody(ball);
    }
    return world;
}

/// Bit for bit; with `unmeasured`, x may instead carry no impulses where y does (hasImpulses
/// false, every impulse 0), and is otherwise the same.
bool sameEvent(const ContactEvent& x, const ContactEvent& y, bool unmeasured = false) {
    const bool withoutImpulses = unmeasured && !x.hasImpulses;
    if (x.bodyA != y.bodyA || x.bodyB != y.bodyB || x.phase != y.phase || x.trigger != y.trigger ||
        x.removal != y.removal || (!withoutImpulses && x.hasImpulses != y.hasImpulses) || x.normal != y.normal ||
        x.points.size() != y.points.size())
        return false;
    for (std::size_t k = 0; k < x.points.size(); ++k)
        if (x.points[k].position != y.points[k].position || x.points[k].depth != y.points[k].depth ||
            x.points[k].normalImpulse != (withoutImpulses ? 0.0 : y.points[k].normalImpulse))
            return false;
    return true;
}

TEST(EventDispatch, EventsFirstReadLateAreTheLastStepsEvents) {
    // A world whose events nobody reads only diffs its touching pairs each step and writes the
    // events when first asked. What it then returns must be exactly the last step's events, as a
    // world that read them every step has them (same backend, same scene: bit-identical), on
    // every backend with the capabilities; except that an engine measuring impulses only for
    // the events (ODE) may not have measured the first read step's (it then says so), and has
    // the next step's.
    int backends = 0;
    for (const BackendInfo& info : availableBackends()) {
        const Capabilities& c = info.capabilities;
        if (!c.effects.has(Effect::Contacts) || !c.effects.has(Effect::Events) || !c.effects.has(Effect::Restitution) ||
            !c.shapes.contains(ShapeType::Sphere) || !c.shapes.contains(ShapeType::Plane))
            continue;
        ++backends;
        SCOPED_TRACE(info.name);
        constexpr int kSteps = 150;
        World reading(settingsFor(info.name), bouncyMaterial());
        bouncingBalls(reading);
        std::vector<std::vector<ContactEvent>> everyStep;  // [n]: the events of step n + 1
        (void)reading.lastEvents();  // read from before the first step
        for (int n = 0; n <= kSteps; ++n) {
            reading.step();
            everyStep.push_back(reading.lastEvents());
        }
        int exits = 0, enters = 0;
        for (const auto& events : everyStep)
            for (const ContactEvent& e : events) {
                exits += e.phase == ContactPhase::Exit;
                enters += e.phase == ContactPhase::Enter;
            }
        ASSERT_GE(enters, 8) << "each ball lands at least twice";
        ASSERT_GE(exits, 4) << "each ball bounces off at least once";
        // First reads after the first step, the first step with an exit (a bounce), the first
        // landing after it, and the last step.
        const auto firstStepWith = [&](ContactPhase phase, int after) {
            for (int n = after; n < kSteps; ++n)
                for (const ContactEvent& e : everyStep[static_cast<std::size_t>(n)])
                    if (e.phase == phase) return n + 1;
            return kSteps;
        };
        const int bounce = firstStepWith(ContactPhase::Exit, 0);
        const int landing = firstStepWith(ContactPhase::Enter, bounce);
        ASSERT_LT(landing, kSteps) << "a ball lands again after the first bounce";
        for (const int firstRead : {1, bounce, landing, kSteps}) {
            World late(settingsFor(info.name), bouncyMaterial());
            bouncingBalls(late);
            for (int n = 0; n < firstRead; ++n) late.step();
            const std::vector<ContactEvent>& events = late.lastEvents();
            const std::vector<ContactEvent>& expected = everyStep[static_cast<std::size_t>(firstRead - 1)];
            ASSERT_EQ(events.size(), expected.size()) << "first read after step " << firstRead;
            for (std::size_t k = 0; k < events.size(); ++k)
                EXPECT_TRUE(sameEvent(events[k], expected[k], true)) << "event " << k << " after step " << firstRead;
            // Read once, the reference follows every later step as well.
            late.step();
            const std::vector<ContactEvent>& next = everyStep[static_cast<std::size_t>(firstRead)];
            ASSERT_EQ(events.size(), next.size()) << "the step after the first read, " << firstRead + 1;
            for (std::size_t k = 0; k < events.size(); ++k)
                EXPECT_TRUE(sameEvent(events[k], next[k])) << "event " << k << " after step " << firstRead + 1;
        }
    }
    if (backends == 0) GTEST_SKIP() << "no backend with contacts, events, restitution, spheres and planes";
}

TEST(EventDispatch, ContactEventListenerTakesEveryEventInOrder) {
    // The one-function listener receives what the five callbacks would: every contact event of
    // each step, in the order of lastEvents(). Bouncing balls give enters, stays and exits.
    const std::string backend = eventBackend();
    if (backend.empty()) GTEST_SKIP() << "no backend with contacts, events, spheres and planes";
    struct Recorder final : ContactEventListener {
        std::vector<ContactEvent> received;
        void onContactEvent(const ContactEvent& e) override { received.push_back(e); }
    } recorder;
    World world(settingsFor(backend), bouncyMaterial());
    bouncingBalls(world);
    world.addListener(&recorder);
    int phases[3] = {0, 0, 0};
    for (int n = 0; n < 150; ++n) {
        recorder.received.clear();
        world.step();
        const std::vector<ContactEvent>& expected = world.lastEvents();
        ASSERT_EQ(recorder.received.size(), expected.size()) << "step " << n + 1;
        for (std::size_t k = 0; k < expected.size(); ++k) {
            EXPECT_TRUE(sameEvent(recorder.received[k], expected[k])) << "event " << k << " of step " << n + 1;
            ++phases[static_cast<int>(expected[k].phase)];
        }
    }
    EXPECT_GT(phases[static_cast<int>(ContactPhase::Enter)], 0) << "the balls land";
    EXPECT_GT(phases[static_cast<int>(ContactPhase::Stay)], 0) << "and stay in contact for a while";
    EXPECT_GT(phases[static_cast<int>(ContactPhase::Exit)], 0) << "and bounce off";
}

}  // namespace
}  // namespace anyphys
