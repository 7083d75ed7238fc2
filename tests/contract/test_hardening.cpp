// Reliability on every backend: errors say what kind they are and which field they concern,
// handles that outlive their body, joint or world throw StaleHandle, absurd finite inputs are
// refused up front, and a step never hands back a diverged state silently.
#include <gmock/gmock.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "anyphys/containers/scene.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

using ::testing::HasSubstr;

class HardeningTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }

    BodyDef ball(const std::string& name, const Vec3& position) const {
        BodyDef d;
        d.name = name;
        d.position = position;
        d.shape = ShapeDef::sphere(0.5);
        return d;
    }
};

// Runs `call`; expects an Error of `kind` whose field is `field` and whose message holds every fragment.
template <class F>
void expectError(F&& call, ErrorKind kind, const std::string& field, std::initializer_list<const char*> fragments = {}) {
    try {
        call();
        ADD_FAILURE() << "expected anyphys::Error of kind " << toString(kind);
    } catch (const Error& e) {
        EXPECT_EQ(toString(e.kind()), toString(kind)) << e.what();
        EXPECT_EQ(e.field(), field) << e.what();
        for (const char* f : fragments) EXPECT_THAT(e.what(), HasSubstr(f));
    }
}

TEST_P(HardeningTest, ErrorsCarryKindAndField) {
    World world(settings());
    BodyDef bad = ball("b", Vec3(0, 1, 0));
    bad.shape = ShapeDef::sphere(-1);
    expectError([&] { world.createBody(bad); }, ErrorKind::InvalidArgument, "BodyDef.shape.radius", {"must be > 0", "got -1"});

    WorldSettings s = settings();
    s.timeStep = -1;
    expectError([&] { World w(s); }, ErrorKind::InvalidArgument, "WorldSettings.timeStep", {"must be > 0"});

    s = settings();
    s.backendOptions["no_such_option"] = 1.0;  // no backend has it: a missing capability
    expectError([&] { World w(s); }, ErrorKind::Unsupported, "WorldSettings", {"no_such_option"});

    // A mode the backend lacks is named with its field and the modes it has instead.
    for (const GyroscopicMode mode : {GyroscopicMode::None, GyroscopicMode::Implicit, GyroscopicMode::Explicit}) {
        if (caps().gyroscopicModes.count(mode)) continue;
        BodyDef def = ball("g", Vec3(0, 1, 0));
        def.gyroscopic = mode;
        expectError([&] { world.createBody(def); }, ErrorKind::Unsupported, "BodyDef",
                    {"gyroscopic mode", "(BodyDef.gyroscopic; it has "});
    }

    expectError([&] { world.step(-0.5); }, ErrorKind::InvalidArgument, "World.step.dt");
    expectError([&] { Body().position(); }, ErrorKind::StaleHandle, "", {"null body handle"});

    // Scene text: syntax and shape are Parse errors, broken rules InvalidArgument, both with the JSON path.
    expectError([] { (void)parseScene("{ \"settings\": "); }, ErrorKind::Parse, "", {"invalid JSON"});
    expectError([] { (void)parseScene(R"({"settings": {"gravityy": [0, 0, 0]}})"); }, ErrorKind::Parse, "settings.gravityy",
                {"unknown key"});
    expectError([] { (void)parseScene(R"({"settings": {"timeStep": "fast"}})"); }, ErrorKind::Parse, "settings.timeStep",
                {"must be a number"});
    expectError([] { (void)parseScene(R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0}}]})"); },
                ErrorKind::InvalidArgument, "bodies[0].shape.radius", {"must be > 0"});
    expectError([] { (void)parseScene(R"({"settings": {"divergencePolicy": "explode"}})"); }, ErrorKind::InvalidArgument,
                "settings.divergencePolicy", {"throw, freeze"});
    EXPECT_EQ(world.bodyCount(), 0u);
}

TEST_P(HardeningTest, ErrorsWhileSteppingAreInvalidState) {
    World world(settings());
    Body b = world.createBody(ball("b", Vec3(0, 1, 0)));
    bool called = false;
    world.setForceCallback([&](ForceContext&) {
        if (called) return;
        called = true;
        expectError([&] { world.createBody(ball("c", Vec3(0, 3, 0))); }, ErrorKind::InvalidState, "",
                    {"while the world is stepping"});
    });
    world.step();
    EXPECT_TRUE(called);
    EXPECT_TRUE(b.isValid());
}

TEST_P(HardeningTest, AbsurdFiniteValuesAreRefusedNamingTheField) {
    World world(settings());
    BodyDef far = ball("far", Vec3(1e308, 0, 0));
    expectError([&] { world.createBody(far); }, ErrorKind::InvalidArgument, "BodyDef.position",
                {"e+308", "within +-1e+07 m", "kMaxCoordinate"});
    BodyDef spin = ball("spin", Vec3(0, 1, 0));
    spin.angularVelocity = Vec3(0, 0, 1e308);
    expectError([&] { world.createBody(spin); }, ErrorKind::InvalidArgument, "BodyDef.angularVelocity",
                {"WorldSettings.maxAngularSpeed", "100000 rad/s"});
    BodyDef fast = ball("fast", Vec3(0, 1, 0));
    fast.linearVelocity = Vec3(2e5, 0, 0);
    expectError([&] { world.createBody(fast); }, ErrorKind::InvalidArgument, "BodyDef.linearVelocity",
                {"WorldSettings.maxSpeed"});
    BodyDef huge = ball("huge", Vec3(0, 1, 0));
    huge.shape = ShapeDef::sphere(1e300);
    expectError([&] { world.createBody(huge); }, ErrorKind::InvalidArgument, "BodyDef.shape.radius", {"kMaxCoordinate"});
    EXPECT_EQ(world.bodyCount(), 0u);

    WorldSettings s = settings();
    s.gravity = Vec3(0, -1e19, 0);
    expectError([&] { World w(s); }, ErrorKind::InvalidArgument, "WorldSettings.gravity", {"kMaxGravity"});
    s = settings();
    s.timeStep = 1e300;
    expectError([&] { World w(s); }, ErrorKind::InvalidArgument, "WorldSettings.timeStep", {"kMaxTimeStep"});

    // Setters and impulses on a live body: refused, and the body is untouched.
    Body b = world.createBody(ball("b", Vec3(0, 1, 0)));
    const BodyState before = b.state();
    expectError([&] { b.setTransform(Vec3(0, 1e308, 0), Quat::Identity()); }, ErrorKind::InvalidArgument,
                "Body.setTransform.position");
    expectError([&] { b.setLinearVelocity(Vec3(1e308, 0, 0)); }, ErrorKind::InvalidArgument,
                "Body.setLinearVelocity.velocity", {"WorldSettings.maxSpeed"});
    expectError([&] { b.setAngularVelocity(Vec3(0, 0, 1e308)); }, ErrorKind::InvalidArgument,
                "Body.setAngularVelocity.velocity", {"WorldSettings.maxAngularSpeed"});
    expectError([&] { b.applyLinearImpulse(Vec3(1e300, 0, 0)); }, ErrorKind::InvalidArgument,
                "Body.applyLinearImpulse.impulse", {"WorldSettings.maxSpeed"});
    expectError([&] { b.applyAngularImpulse(Vec3(0, 0, 1e300)); }, ErrorKind::InvalidArgument,
                "Body.applyAngularImpulse.impulse", {"WorldSettings.maxAngularSpeed"});
    expectError([&] { b.applyForce(Vec3(1e300, 0, 0)); }, ErrorKind::InvalidArgument, "Body.applyForce.force",
                {"in one step"});
    expectError([&] { b.applyTorque(Vec3(0, 0, 1e300)); }, ErrorKind::InvalidArgument, "Body.applyTorque.torque",
                {"in one step", "WorldSettings.maxAngularSpeed"});
    const BodyState after = b.state();
    EXPECT_EQ(after.position, before.position);
    EXPECT_EQ(after.linearVelocity, before.linearVelocity);
    EXPECT_EQ(after.angularVelocity, before.angularVelocity);

    // A force callback's absurd force is refused inside the step, before the engine integrates it
    // (ODE aborted the process on a 1e300 N force).
    world.setForceCallback([&](ForceContext& c) { c.addForce(b, Vec3(1e300, 0, 0)); });
    expectError([&] { world.step(); }, ErrorKind::InvalidArgument, "ForceContext.addForce.force", {"in one step"});
    world.setForceCallback([&](ForceContext& c) { c.addTorque(b, Vec3(0, 0, 1e300)); });
    expectError([&] { world.step(); }, ErrorKind::InvalidArgument, "ForceContext.addTorque.torque", {"in one step"});
    world.setForceCallback({});

    // The same values in a scene file name the JSON path.
    expectError([] { (void)parseScene(R"({"bodies": [{"name": "a", "position": [1e308, 0, 0], "shape": {"type": "sphere", "radius": 0.5}}]})"); },
                ErrorKind::InvalidArgument, "bodies[0].position", {"kMaxCoordinate"});
    expectError([] { (void)parseScene(R"({"bodies": [{"name": "a", "angularVelocity": [0, 0, 1e308], "shape": {"type": "sphere", "radius": 0.5}}]})"); },
                ErrorKind::InvalidArgument, "bodies[0].angularVelocity", {"settings.maxAngularSpeed"});
    expectError([] { (void)parseScene(R"({"settings": {"gravity": [0, -1e19, 0]}})"); }, ErrorKind::InvalidArgument,
                "settings.gravity", {"kMaxGravity"});
}

TEST_P(HardeningTest, BodyHandleOfDestroyedBodyOrWorldIsStale) {
    Body kept;
    {
        World world(settings());
        Body gone = world.createBody(ball("gone", Vec3(0, 1, 0)));
        kept = world.createBody(ball("kept", Vec3(2, 1, 0)));
        world.destroyBody(gone);
        EXPECT_FALSE(gone.isValid());
        expectError([&] { gone.position(); }, ErrorKind::StaleHandle, "", {"Body.position", "stale body handle"});
        world.createBody(ball("reuses the slot", Vec3(0, 1, 0)));
        EXPECT_FALSE(gone.isValid());
        expectError([&] { gone.setLinearVelocity(Vec3(1, 0, 0)); }, ErrorKind::StaleHandle, "");
        EXPECT_TRUE(kept.isValid());
    }
    // The world is gone: every use throws instead of touching freed memory.
    EXPECT_FALSE(kept.isValid());
    EXPECT_EQ(kept.world(), nullptr);
    expectError([&] { kept.position(); }, ErrorKind::StaleHandle, "", {"Body.position", "world was destroyed"});
    expectError([&] { kept.applyForce(Vec3(1, 0, 0)); }, ErrorKind::StaleHandle, "", {"world was destroyed"});
    expectError([&] { kept.name(); }, ErrorKind::StaleHandle, "");

    // A new world (perhaps at the same address, with a body in the same slot) does not revive it.
    auto again = std::make_unique<World>(settings());
    again->createBody(ball("first", Vec3(0, 1, 0)));
    Body fresh = again->createBody(ball("fresh", Vec3(2, 1, 0)));
    EXPECT_TRUE(fresh.id() == kept.id());
    EXPECT_FALSE(kept.isValid());
    EXPECT_FALSE(kept == fresh);
    expectError([&] { again->destroyBody(kept); }, ErrorKind::StaleHandle, "", {"world was destroyed"});
    JointDef def;
    def.type = JointType::Hinge;
    def.bodyB = kept;
    def.axis = Vec3::UnitZ();
    expectError([&] { again->createJoint(def); }, ErrorKind::StaleHandle, "JointDef.bodyB", {"world was destroyed"});
    EXPECT_EQ(again->bodyCount(), 2u);
}

TEST_P(HardeningTest, JointHandleOfDestroyedJointBodyOrWorldIsStale) {
    ANYPHYS_REQUIRE(caps().effects.has(Effect::Joints) && caps().jointTypes.contains("hinge"), "hinge joints");
    Joint kept;
    {
        World world(settings());
        Body a = world.createBody(ball("a", Vec3(0, 1, 0)));
        Body b = world.createBody(ball("b", Vec3(3, 1, 0)));
        JointDef def;
        def.type = JointType::Hinge;
        def.axis = Vec3::UnitZ();
        def.bodyB = a;
        def.anchor = Vec3(0, 2, 0);
        Joint j = world.createJoint(def);
        world.destroyJoint(j);
        EXPECT_FALSE(j.isValid());
        expectError([&] { j.position(); }, ErrorKind::StaleHandle, "", {"Joint.position", "stale joint handle"});

        Joint viaBody = world.createJoint(def);
        world.destroyBody(a);
        EXPECT_FALSE(viaBody.isValid());
        expectError([&] { viaBody.reactionForce(); }, ErrorKind::StaleHandle, "");

        def.bodyB = b;
        def.anchor = Vec3(3, 2, 0);
        kept = world.createJoint(def);
        world.step();
        EXPECT_TRUE(kept.isValid());
    }
    EXPECT_FALSE(kept.isValid());
    EXPECT_EQ(kept.world(), nullptr);
    expectError([&] { kept.position(); }, ErrorKind::StaleHandle, "", {"Joint.position", "world was destroyed"});
    expectError([&] { kept.bodyB(); }, ErrorKind::StaleHandle, "");
    expectError([&] { kept.setMotor(std::nullopt); }, ErrorKind::StaleHandle, "");
    World other(settings());
    expectError([&] { other.destroyJoint(kept); }, ErrorKind::StaleHandle, "", {"world was destroyed"});
}

// A rocket gains 10 m/s every step (one step's force stays below the ceiling, so each call is
// accepted); with maxSpeed 25 m/s it passes the ceiling on its third step. Every backend can
// reach that speed (Box2D clamps at 2 m per step, 120 m/s at 60 Hz).
class DivergenceTest : public HardeningTest {
protected:
    static constexpr double kMaxSpeed = 25.0;
    static constexpr double kGain = 10.0;  // m/s per step

    WorldSettings divergenceSettings(DivergencePolicy policy) const {
        WorldSettings s = settings();
        s.gravity = Vec3::Zero();
        s.maxSpeed = kMaxSpeed;
        s.divergencePolicy = policy;
        return s;
    }
    void push(World& world, Body rocket) const {
        rocket.applyForce(Vec3(rocket.massProperties().mass * kGain / world.settings().timeStep, 0, 0));
    }
    // Pushes and steps until a step throws Diverged (true), for at most 10 steps.
    bool pushUntilDiverged(World& world, Body rocket) const {
        for (int step = 0; step < 10; ++step) {
            push(world, rocket);
            try {
                world.step();
            } catch (const Error& e) {
                if (e.kind() == ErrorKind::Diverged) return true;
            }
        }
        return false;
    }
};

TEST_P(DivergenceTest, ThrowPolicyNamesTheBody) {
    World world(divergenceSettings(DivergencePolicy::Throw));
    Body rocket = world.createBody(ball("rocket", Vec3(0, 0, 0)));
    BodyDef walkerDef = ball("walker", Vec3(0, 10, 0));
    walkerDef.linearVelocity = Vec3(1, 0, 0);
    world.createBody(walkerDef);
    int steps = 0;
    try {
        for (; steps < 10; ++steps) {
            push(world, rocket);
            world.step();
        }
        ADD_FAILURE() << "no Diverged error after 10 steps; speed " << rocket.linearVelocity().norm();
    } catch (const Error& e) {
        EXPECT_EQ(toString(e.kind()), toString(ErrorKind::Diverged)) << e.what();
        EXPECT_EQ(e.field(), "body \"rocket\".linearVelocity");
        EXPECT_THAT(e.what(), HasSubstr("body \"rocket\""));
        EXPECT_THAT(e.what(), HasSubstr("WorldSettings.maxSpeed 25"));
        EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("walker")));
        EXPECT_EQ(steps, 2) << e.what();  // 10, 20, then 30 m/s
    }
    ASSERT_EQ(world.lastDiverged().size(), 1u);
    EXPECT_EQ(world.lastDiverged()[0].name, "rocket");
    EXPECT_TRUE(world.lastDiverged()[0].body == rocket);
    EXPECT_FALSE(rocket.isFrozen());
}

// After a Diverged throw the engine keeps the diverged states (for the caller to read); stepping
// on must not hand them to the engine again (engines abort on non-finite and out-of-world states).
// The next step throws until the body is set right or destroyed, and changes nothing meanwhile.
TEST_P(DivergenceTest, StepAfterAThrowWaitsUntilTheBodyIsSetRight) {
    World world(divergenceSettings(DivergencePolicy::Throw));
    Body rocket = world.createBody(ball("rocket", Vec3(0, 0, 0)));
    BodyDef walkerDef = ball("walker", Vec3(0, 10, 0));
    walkerDef.linearVelocity = Vec3(1, 0, 0);
    Body walker = world.createBody(walkerDef);
    const bool diverged = pushUntilDiverged(world, rocket);
    ASSERT_TRUE(diverged) << "the rocket never passed maxSpeed; speed " << rocket.linearVelocity().norm();

    const double time = world.time();
    const Vec3 walkerAt = walker.position();
    for (int again = 0; again < 3; ++again)
        expectError([&] { world.step(); }, ErrorKind::Diverged, "body \"rocket\".linearVelocity",
                    {"still diverged", "WorldSettings.maxSpeed 25", "set it right"});
    EXPECT_EQ(world.time(), time);  // refused before the engine stepped
    EXPECT_EQ(walker.position(), walkerAt);

    rocket.setLinearVelocity(Vec3(5, 0, 0));  // within the ceiling again
    ASSERT_NO_THROW(world.step());
    EXPECT_GT(walker.position().x(), walkerAt.x());  // the world moves on
    EXPECT_TRUE(world.lastDiverged().empty());
}

TEST_P(DivergenceTest, StepAfterAThrowGoesOnOnceTheBodyIsDestroyed) {
    World world(divergenceSettings(DivergencePolicy::Throw));
    Body rocket = world.createBody(ball("rocket", Vec3(0, 0, 0)));
    const bool diverged = pushUntilDiverged(world, rocket);
    ASSERT_TRUE(diverged);
    world.destroyBody(rocket);
    EXPECT_NO_THROW(world.step());
}

// Each backend scans its own bodies for the throw policy (WorldPeer::findUnsound); the layer
// then names them in body-slot order, whatever order the backend keeps. "rocket" takes the slot a
// destroyed body freed, so the backend lists it after "spinner" while the layer numbers it first.
// Both pass a ceiling in the same step: the rocket its speed, the spinner its angular speed
// (+10 rad/s per step about Z, a planar world's axis too: 10, 20, then 30 rad/s > 25).
TEST_P(DivergenceTest, ThrowPolicyNamesEveryDivergedBodyInSlotOrder) {
    WorldSettings s = divergenceSettings(DivergencePolicy::Throw);
    s.maxAngularSpeed = kMaxSpeed;
    World world(s);
    Body placeholder = world.createBody(ball("placeholder", Vec3(0, 0, 0)));
    Body spinner = world.createBody(ball("spinner", Vec3(0, 5, 0)));
    world.destroyBody(placeholder);
    Body rocket = world.createBody(ball("rocket", Vec3(0, 0, 0)));
    ASSERT_LT(rocket.id().index, spinner.id().index);
    const double spinTorque = spinner.massProperties().inertia.z() * kGain / s.timeStep;
    int steps = 0;
    try {
        for (; steps < 10; ++steps) {
            push(world, rocket);
            spinner.applyTorque(Vec3(0, 0, spinTorque));
            world.step();
        }
        ADD_FAILURE() << "no Diverged error after 10 steps; angular speed " << spinner.angularVelocity().norm();
    } catch (const Error& e) {
        EXPECT_EQ(toString(e.kind()), toString(ErrorKind::Diverged)) << e.what();
        EXPECT_EQ(e.field(), "body \"rocket\".linearVelocity") << e.what();  // the first in slot order
        EXPECT_THAT(e.what(), HasSubstr("body \"spinner\" angular speed"));
        EXPECT_THAT(e.what(), HasSubstr("WorldSettings.maxAngularSpeed 25"));
        EXPECT_EQ(steps, 2) << e.what();
    }
    ASSERT_EQ(world.lastDiverged().size(), 2u);
    EXPECT_EQ(world.lastDiverged()[0].name, "rocket");
    EXPECT_EQ(world.lastDiverged()[1].name, "spinner");
}

// A body leaving the world: one 1 s step at 20 m/s takes it from 1 m inside kMaxCoordinate to
// beyond it (Box2D clamps a step's move at 2 m: still 1 m beyond; its floats hold whole metres there).
TEST_P(DivergenceTest, ThrowPolicyNamesABodyBeyondTheCoordinateCeiling) {
    World world(divergenceSettings(DivergencePolicy::Throw));
    BodyDef farDef = ball("far", Vec3(kMaxCoordinate - 1.0, 0, 0));
    farDef.linearVelocity = Vec3(20, 0, 0);
    world.createBody(farDef);
    expectError([&] { world.step(1.0); }, ErrorKind::Diverged, "body \"far\".position", {"beyond +-1e+07 m"});
    ASSERT_EQ(world.lastDiverged().size(), 1u);
    EXPECT_EQ(world.lastDiverged()[0].name, "far");
}

TEST_P(DivergenceTest, FreezePolicyHoldsTheBodyAndWarns) {
    World world(divergenceSettings(DivergencePolicy::Freeze));
    std::vector<std::string> warnings;
    world.setWarningHandler([&](const std::string& w) { warnings.push_back(w); });
    Body rocket = world.createBody(ball("rocket", Vec3(0, 0, 0)));
    BodyDef walkerDef = ball("walker", Vec3(0, 10, 0));
    walkerDef.linearVelocity = Vec3(1, 0, 0);
    Body walker = world.createBody(walkerDef);
    Vec3 frozenAt = Vec3::Zero();
    for (int step = 0; step < 60; ++step) {
        push(world, rocket);  // the game keeps pushing: the frozen body stays put
        ASSERT_NO_THROW(world.step());
        const BodyState s = rocket.state();
        ASSERT_TRUE(s.position.allFinite() && s.linearVelocity.allFinite());
        EXPECT_LE(s.linearVelocity.norm(), kMaxSpeed);
        if (step == 2) {
            ASSERT_EQ(world.lastDiverged().size(), 1u);
            EXPECT_EQ(world.lastDiverged()[0].name, "rocket");
            frozenAt = s.position;
        }
        if (step >= 2) {
            EXPECT_TRUE(rocket.isFrozen());
            EXPECT_EQ(s.position, frozenAt) << "step " << step;
            EXPECT_TRUE(s.linearVelocity.isZero(0));
        }
    }
    EXPECT_TRUE(world.lastDiverged().empty());  // frozen bodies are not found again
    EXPECT_NEAR(frozenAt.x(), (10 + 20) * world.settings().timeStep, 1e-3);  // held where the last check found it
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0], HasSubstr("body \"rocket\""));
    EXPECT_THAT(warnings[0], HasSubstr("frozen"));
    EXPECT_EQ(world.warnings(), warnings);
    EXPECT_FALSE(walker.isFrozen());
    EXPECT_NEAR(walker.position().x(), world.time(), 1e-3);  // the rest of the world keeps stepping
}

// A shape's sizes have no default: a box without half extents is refused naming the field, never
// a silent 1 m cube, and the refusal leaves the world as it was.
TEST_P(HardeningTest, ShapesWithoutTheirSizesAreRefusedNamingTheField) {
    World world(settings());
    const auto refused = [&](ShapeDef shape, const std::string& field) {
        BodyDef d = ball("b", Vec3(0, 1, 0));
        d.shape = std::move(shape);
        expectError([&] { world.createBody(d); }, ErrorKind::InvalidArgument, field, {"not set", "no default"});
    };
    ShapeDef s;
    s.type = ShapeType::Sphere;
    refused(s, "BodyDef.shape.radius");
    s.type = ShapeType::Box;
    refused(s, "BodyDef.shape.halfExtents[0]");
    s.halfExtents = Vec3(0.5, kUnset, 0.5);
    refused(s, "BodyDef.shape.halfExtents[1]");
    s = ShapeDef();
    s.type = ShapeType::Capsule;
    refused(s, "BodyDef.shape.radius");
    s.radius = 0.2;
    refused(s, "BodyDef.shape.halfHeight");
    refused(ShapeDef::compound({ShapeDef::sphere(0.3), ShapeDef()}), "BodyDef.shape.shapes[1].radius");

    BodyDef noShape;  // no shape at all: the default ShapeDef is a sphere without a radius
    noShape.name = "shapeless";
    expectError([&] { world.createBody(noShape); }, ErrorKind::InvalidArgument, "BodyDef.shape.radius", {"ShapeDef::sphere"});

    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape.type = ShapeType::Plane;  // a plane has no size: without a normal it faces up (+Y)
    ground.shape.normal = Vec3(0, 0, 0);
    expectError([&] { world.createBody(ground); }, ErrorKind::InvalidArgument, "BodyDef.shape.normal", {"non-zero"});
    EXPECT_EQ(world.bodyCount(), 0u);
    // The same shapes in queries.
    expectError([&] { world.overlap(ShapeDef(), Transform{}); }, ErrorKind::InvalidArgument, "World.overlap.shape.radius");
}

// A joint anchored 1e308 m away made Box2D's state NaN in the first step: anchors have the
// bodies' coordinate ceiling, and the refusal leaves the world without the joint.
TEST_P(HardeningTest, JointAnchorsBeyondTheCeilingAreRefused) {
    World world(settings());
    Body b = world.createBody(ball("b", Vec3(0, 2, 0)));
    JointDef j;
    j.type = JointType::Ball;
    j.bodyB = b;
    j.anchor = Vec3(1e308, 0, 0);
    expectError([&] { world.createJoint(j); }, ErrorKind::InvalidArgument, "JointDef.anchor", {"kMaxCoordinate"});
    j.type = JointType::Distance;
    j.anchor = Vec3::Zero();
    j.anchorA = Vec3(0, 2e7, 0);
    j.anchorB = b.position();
    expectError([&] { world.createJoint(j); }, ErrorKind::InvalidArgument, "JointDef.anchorA", {"kMaxCoordinate"});
    EXPECT_EQ(world.jointCount(), 0u);
}

// Found by the API fuzzer: a ball joint anchored 1.7e7 m from a 5 cm ball (5e8 of its radii of
// gyration) left ODE's direct solver a matrix past double precision; the ball's rotation came out
// NaN and ODE aborted the process. A joint's lever is refused beyond 1e6 radii of gyration of a
// dynamic body (3.2e4 m for that 5 cm ball), the world left without the joint and stepping on; a long
// lever within it (a 1 km cable) is kept.
TEST_P(HardeningTest, JointLeversBeyondTheBodiesReachAreRefused) {
    World world(settings());
    Body b = world.createBody(ball("b", Vec3(0, 2, 0)));  // radius 0.5 m: radius of gyration 0.32 m
    const double radiusOfGyration = std::sqrt(b.massProperties().inertia.minCoeff() / b.massProperties().mass);
    JointDef j;
    j.type = JointType::Ball;
    j.bodyB = b;
    j.anchor = Vec3(0, 2 + 1.01e6 * radiusOfGyration, 0);
    expectError([&] { world.createJoint(j); }, ErrorKind::InvalidArgument, "JointDef.anchor", {"radii of gyration", "bodyB"});
    j.type = JointType::Distance;
    j.anchorA = Vec3::Zero();
    j.anchorB = Vec3(1e7, 2, 0);
    expectError([&] { world.createJoint(j); }, ErrorKind::InvalidArgument, "JointDef.anchorB", {"radii of gyration"});
    // A fixed joint's lever is the other body's centre as well (ODE welds the centres): a kinematic
    // body 1.4e7 m away, anchor at the ball, aborted ODE's direct solver (API fuzzer).
    BodyDef far = ball("far", Vec3(-0.83, 1e7, planarWorld() ? 0.0 : 1e7));
    far.type = BodyType::Kinematic;
    j.type = JointType::Fixed;
    j.bodyA = world.createBody(far);
    j.anchor = Vec3(0, 2, 0);
    expectError([&] { world.createJoint(j); }, ErrorKind::InvalidArgument, "JointDef.bodyA", {"radii of gyration", "bodyB"});
    j.bodyA = Body();
    EXPECT_EQ(world.jointCount(), 0u);
    j.type = JointType::Ball;
    j.anchor = Vec3(0, 1002, 0);  // a 1 km cable: 3 200 radii
    EXPECT_NO_THROW(world.createJoint(j));
    EXPECT_EQ(world.jointCount(), 1u);
    for (int i = 0; i < 10; ++i) world.step();
    EXPECT_TRUE(b.position().allFinite());
}

// Found by the API fuzzer: a ray direction of (1e308, 1e308, 0) has a norm that overflows to inf,
// and normalising by it handed ODE a zero direction, which it aborted the process on. Huge
// directions now work as their unit direction, huge lengths are cut to the world's extent, and a
// zero quaternion for an overlap pose is refused instead of reaching the engines as NaN.
TEST_P(HardeningTest, QueriesWithHugeOrDegenerateInputsAreSafe) {
    ANYPHYS_REQUIRE(caps().queries.count("raycast") && caps().queries.count("overlap"), "queries raycast and overlap");
    World world(settings());
    BodyDef target = ball("target", Vec3(3, 3, 0));
    target.type = BodyType::Static;
    world.createBody(target);
    const auto hit = world.raycast(Vec3::Zero(), Vec3(1e308, 1e308, 0), 1e308);
    ASSERT_TRUE(hit.has_value());
    // The ray along (1, 1, 0) meets the sphere of radius 0.5 about (3, 3, 0) at 3 sqrt(2) - 0.5;
    // 1e-6 m covers every engine's ray-sphere arithmetic (Box2D's is float: ~4e-7 relative).
    EXPECT_NEAR(hit->distance, 3 * std::sqrt(2.0) - 0.5, 1e-6);
    EXPECT_EQ(world.raycastAll(Vec3::Zero(), Vec3(-1e308, 0, 0), 1e308).size(), 0u);
    expectError([&] { world.raycast(Vec3(1e308, 0, 0), Vec3(1, 0, 0), 1); }, ErrorKind::InvalidArgument,
                "World.raycast.origin", {"kMaxCoordinate"});
    expectError([&] { world.raycast(Vec3::Zero(), Vec3(1e-300, 0, 0), 1); }, ErrorKind::InvalidArgument,
                "World.raycast.direction", {"non-zero"});
    expectError([&] { world.overlap(ShapeDef::sphere(1), Transform{Vec3::Zero(), Quat(0, 0, 0, 0)}); },
                ErrorKind::InvalidArgument, "World.overlap.pose.orientation", {"unit quaternion"});
    EXPECT_EQ(world.overlap(ShapeDef::sphere(1), Transform{Vec3(3, 3, 0), Quat::Identity()}).size(), 1u);
}

// Found by the API fuzzer: a dynamic sphere of radius 1e-300 m and mass 1e-300 kg had an inertia
// that underflowed to 0 and principal axes of NaN, and Box2D aborted the process on the NaN pose.
// Sizes have a floor and a dynamic body's mass and inertia a range, each refused naming the field.
TEST_P(HardeningTest, VanishingOrHugeMassesAreRefusedNamingTheField) {
    World world(settings());
    BodyDef d = ball("dust", Vec3(0, 1, 0));
    d.shape = ShapeDef::sphere(1e-300);
    expectError([&] { world.createBody(d); }, ErrorKind::InvalidArgument, "BodyDef.shape.radius", {"kMinLength"});
    d.shape = ShapeDef::sphere(0.5);
    d.mass = 1e-300;
    expectError([&] { world.createBody(d); }, ErrorKind::InvalidArgument, "BodyDef.mass", {"kMinMass"});
    d.mass = 1e308;
    expectError([&] { world.createBody(d); }, ErrorKind::InvalidArgument, "BodyDef.mass", {"kMaxMass"});
    d.mass.reset();
    d.density = 1e-300;
    expectError([&] { world.createBody(d); }, ErrorKind::InvalidArgument, "BodyDef.density", {"kMinMass"});
    d.density.reset();
    d.inertia = Vec3(1, 1e-40, 1);
    expectError([&] { world.createBody(d); }, ErrorKind::InvalidArgument, "BodyDef.inertia");
    EXPECT_EQ(world.bodyCount(), 0u);
    d.inertia.reset();
    d.shape = ShapeDef::sphere(1e-3);  // a 1 mm pebble of 4 mg is fine
    EXPECT_NEAR(world.createBody(d).massProperties().mass, 4.0 / 3.0 * std::numbers::pi * 1e-9 * 1000, 1e-15);
}

// Found by the API fuzzer: a 1e20 kg box of 0.1 m given 2.07 kg m^2 of inertia, 1e-17 of what
// its mass would have at its corners, made ODE's direct solver fail on the box's contact rows and
// then abort the process on a non-finite rotation. Inertia below kMinInertiaRatio x mass x the
// squared reach about each axis is refused, naming the given inertia (or the shape whose
// densities made it); at twice the bound the box is accepted and rests on the ground, finite,
// with every solver.
TEST_P(HardeningTest, InertiaTooLightForTheMassIsRefusedNamingTheField) {
    const Vec3 half(0.05, 0.05, 0.05);
    BodyDef core = boxDef("core", half, Vec3(0, half.y(), 0));
    core.mass = 1e20;
    core.inertia = Vec3::Constant(2.07);
    {
        World world(settings());
        expectError([&] { world.createBody(core); }, ErrorKind::InvalidArgument, "BodyDef.inertia",
                    {"kMinInertiaRatio", "got [2.07, 2.07, 2.07]"});
        EXPECT_EQ(world.bodyCount(), 0u);
        // A compound of a 2 um sphere of 420 kg and a 2 cm box of 8 picograms 1 m away: the
        // densities put the mass where it barely turns (2e-10 kg m^2 about Y and Z, the bound
        // 4e-10 there).
        BodyDef dumbbell;
        ShapeDef grain = ShapeDef::sphere(1e-6);
        grain.density = 1e20;
        ShapeDef far = ShapeDef::box(Vec3(0.01, 0.01, 0.01)).placed(Vec3(1, 0, 0), Quat::Identity());
        far.density = 1e-6;
        dumbbell.shape = ShapeDef::compound({grain, far});
        dumbbell.position = Vec3(0, 2, 0);
        expectError([&] { world.createBody(dumbbell); }, ErrorKind::InvalidArgument, "BodyDef.shape", {"kMinInertiaRatio"});
        EXPECT_EQ(world.bodyCount(), 0u);
    }
    // Twice the bound, on a 1 kg box: 2e-12 x 1 kg x (0.05^2 + 0.05^2) m^2 = 1e-14 kg m^2. Accepted,
    // and it steps finite with every solver. Nothing more is promised: its contact rows weigh its
    // turning 1e11 times its translation, which no solver here resolves (measured, 2026-12-02:
    // some keep it on the ground, some let it fall through), and the height is printed. Its spin is
    // chaotic and may pass WorldSettings::maxAngularSpeed, so the divergence check may stop the run
    // with an error of kind Diverged, the state still finite (native, 20 s at 1e-14 to 1e-13 kg m^2,
    // 2026-12-06: 10 of 16 runs before manifolds were swept again after impacts, 7 of 16 after);
    // any other error fails the test.
    core.mass = 1.0;
    core.inertia = Vec3::Constant(1e-14);
    for (Solver solver : caps().solvers) {
        SCOPED_TRACE(toString(solver));
        WorldSettings s = settings();
        s.solver = solver;
        World world(s);
        world.createBody(groundDef());
        Body box = world.createBody(core);
        int firstNonFinite = -1;  // at every step, not only at the end
        for (int i = 0; i < 120 && firstNonFinite < 0; ++i) {
            try {
                world.step();
            } catch (const Error& e) {
                ASSERT_EQ(toString(e.kind()), toString(ErrorKind::Diverged)) << e.what();
                report(backend() + " " + std::string(toString(solver)) + ": spin when the divergence check stopped it at step " +
                           std::to_string(i),
                       box.state().angularVelocity.norm(), "rad/s");
                break;
            }
            const BodyState state = box.state();
            if (!(state.position.allFinite() && state.orientation.coeffs().allFinite() && state.linearVelocity.allFinite() &&
                  state.angularVelocity.allFinite()))
                firstNonFinite = i;
        }
        EXPECT_EQ(firstNonFinite, -1) << "the state went non-finite at step " << firstNonFinite;
        const BodyState state = box.state();  // also where the divergence check stopped the run
        EXPECT_TRUE(state.position.allFinite() && state.orientation.coeffs().allFinite() && state.linearVelocity.allFinite() &&
                    state.angularVelocity.allFinite())
            << "the state is not finite at the end";
        report(backend() + " " + std::string(toString(solver)) + ": height of a 1 kg box of 1e-14 kg m^2 after 2 s or where the check stopped it (m)",
               state.position.y());
    }
}

// The masses a backend holds up on its contacts (Capabilities::lightestBody and heaviestBody, else
// the layer's whole range): a 0.1 m box at either end rests on the ground with every solver. Past
// their declared limits Bullet's box sank through and Box2D's went non-finite (measured by
// decade, 2026-12-02), so a body there is refused naming the field, or simulated with a warning
// under the lenient policy.
TEST_P(HardeningTest, BodiesAtTheBackendsMassLimitsRestOnTheGround) {
    const Capabilities c = caps();
    // Without declared limits: 1e-25 kg (a lighter 0.1 m box's inertia nears kMinMass) and 1e29.
    const double lightest = c.lightestBody > 0.0 ? c.lightestBody : 1e-25;
    const double heaviest = c.heaviestBody > 0.0 ? c.heaviestBody : 1e29;
    BodyDef def = boxDef("box", Vec3(0.05, 0.05, 0.05), Vec3(0, 0.05, 0));
    def.allowSleep = false;
    for (Solver solver : c.solvers)
        for (double mass : {lightest, heaviest}) {
            SCOPED_TRACE(std::string(toString(solver)) + " at " + std::to_string(mass) + " kg");
            WorldSettings s = settings();
            s.solver = solver;
            World world(s);
            world.createBody(groundDef());
            def.mass = mass;
            const Body box = world.createBody(def);
            test::WorstCheck worstHeight;  // over every step, not only at the end; a NaN is kept
            for (int i = 0; i < 120; ++i) {
                world.step();
                worstHeight.check(std::abs(box.position().y() - 0.05), "height");
            }
            // As a 1 kg box rests: within 2 mm of its height at every step (ODE's quickstep, the
            // softest contacts here, 1.2 mm deep above 1 t), still at the end.
            EXPECT_LT(worstHeight.value, 2e-3);
            EXPECT_LT(box.linearVelocity().norm(), 1e-2);
        }
    for (const auto& [limit, beyond] : {std::pair{c.lightestBody, c.lightestBody / 10}, std::pair{c.heaviestBody, c.heaviestBody * 10}}) {
        if (limit == 0.0) continue;  // no declared limit on this side
        def.mass = beyond;
        World strict(settings());
        expectError([&] { strict.createBody(def); }, ErrorKind::Unsupported, "BodyDef.mass", {"does not support", "Body"});
        EXPECT_EQ(strict.bodyCount(), 0u);
        WorldSettings s = settings();
        s.capabilityPolicy = CapabilityPolicy::Lenient;
        World lenient(s);
        std::vector<std::string> warnings;
        lenient.setWarningHandler([&](const std::string& w) { warnings.push_back(w); });
        lenient.createBody(def);
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_THAT(warnings[0], HasSubstr("BodyDef.mass"));
    }
}

// userData is the game's: kept on the def, readable and replaceable through the handles, never
// touched by a step, refused (StaleHandle) once the body or joint is gone.
TEST_P(HardeningTest, UserDataIsKeptOnBodiesAndJoints) {
    World world(settings());
    BodyDef d = ball("a", Vec3(0, 2, 0));
    d.userData = 0xFEEDFACECAFEBEEFull;
    Body a = world.createBody(d);
    Body b = world.createBody(ball("b", Vec3(2, 2, 0)));
    EXPECT_EQ(a.userData(), 0xFEEDFACECAFEBEEFull);
    EXPECT_EQ(b.userData(), 0u);
    int payload = 7;
    b.setUserData(reinterpret_cast<std::uintptr_t>(&payload));
    JointDef j;
    j.type = JointType::Distance;
    j.bodyA = a;
    j.bodyB = b;
    j.anchorA = a.position();
    j.anchorB = b.position();
    j.userData = 42;
    Joint joint = world.createJoint(j);
    EXPECT_EQ(joint.userData(), 42u);
    EXPECT_EQ(joint.def().userData, 42u);
    joint.setUserData(43);
    for (int i = 0; i < 5; ++i) world.step();
    EXPECT_EQ(a.userData(), 0xFEEDFACECAFEBEEFull);
    EXPECT_EQ(*reinterpret_cast<int*>(b.userData()), 7);
    EXPECT_EQ(joint.userData(), 43u);
    world.destroyBody(b);  // takes the joint with it
    expectError([&] { (void)b.userData(); }, ErrorKind::StaleHandle, "");
    expectError([&] { joint.setUserData(1); }, ErrorKind::StaleHandle, "");
}

ANYPHYS_CONTRACT_SUITE(HardeningTest);
ANYPHYS_CONTRACT_SUITE(DivergenceTest);

}  // namespace
}  // namespace anyphys::test
