// Bad input is refused with an anyphys::Error naming the field, the value and the rule, and
// the world is left exactly as it was.
#include <gmock/gmock.h>

#include <cmath>
#include <limits>

#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

class BadInputTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
};

// Runs `call`, expects an Error whose message contains every fragment.
template <class F>
void expectError(F&& call, std::initializer_list<const char*> fragments) {
    try {
        call();
        ADD_FAILURE() << "expected anyphys::Error";
    } catch (const Error& e) {
        for (const char* f : fragments) EXPECT_THAT(e.what(), HasSubstr(f));
    }
}

TEST_P(BadInputTest, RejectedBodyLeavesWorldUnchanged) {
    World world(settings());
    World reference(settings());
    BodyDef good;
    good.position = Vec3(0, 5, 0);
    good.shape = ShapeDef::sphere(0.5);
    Body a = world.createBody(good);
    Body r = reference.createBody(good);

    BodyDef bad = good;
    bad.shape = ShapeDef::sphere(-1);
    expectError([&] { world.createBody(bad); }, {"BodyDef.shape.radius", "must be > 0", "got -1"});
    bad = good;
    bad.position.y() = std::numeric_limits<double>::quiet_NaN();
    expectError([&] { world.createBody(bad); }, {"BodyDef.position", "must be finite", "nan"});
    bad = good;
    bad.mass = 0.0;
    expectError([&] { world.createBody(bad); }, {"BodyDef.mass", "must be > 0", "got 0"});
    bad = good;
    bad.orientation = Quat(2, 0, 0, 0);
    expectError([&] { world.createBody(bad); }, {"BodyDef.orientation", "unit quaternion", "[2, 0, 0, 0]"});
    bad = good;
    bad.type = BodyType::Dynamic;
    bad.shape = ShapeDef::plane(Vec3(0, 1, 0), 0);
    expectError([&] { world.createBody(bad); }, {"BodyDef.shape.type", "static"});
    bad = good;
    bad.material = "unobtainium";
    expectError([&] { world.createBody(bad); }, {"BodyDef.material", "unobtainium"});
    bad = good;
    bad.linearDamping = -0.5;
    expectError([&] { world.createBody(bad); }, {"BodyDef.linearDamping", "must be >= 0", "-0.5"});
    bad = good;
    bad.shape = ShapeDef::convex({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)});
    expectError([&] { world.createBody(bad); }, {"BodyDef.shape.points", "not all in one plane"});
    bad = good;
    bad.type = BodyType::Static;
    bad.shape = ShapeDef::mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)}, {0, 1, 7});
    expectError([&] { world.createBody(bad); }, {"BodyDef.shape.indices[2]", "got 7", "< the number of vertices"});
    bad = good;
    bad.shape = ShapeDef::compound({ShapeDef::sphere(0.5), ShapeDef::sphere(-2).placed(Vec3(1, 0, 0))});
    expectError([&] { world.createBody(bad); }, {"BodyDef.shape.shapes[1].radius", "must be > 0", "got -2"});
    expectError([&] { a.applyForce(Vec3(std::numeric_limits<double>::infinity(), 0, 0)); },
                {"Body.applyForce.force", "must be finite"});
    expectError([&] { world.step(0.0); }, {"World.step.dt", "must be > 0"});
    expectError([&] { world.step(-1.0 / 60); }, {"World.step.dt", "must be > 0"});
    // Positive but absurdly short: split into substeps it rounds to 0 (ODE aborted: API fuzzer).
    expectError([&] { world.step(5e-324); }, {"World.step.dt", "must be >= 1e-09 s", "kMinTimeStep"});

    // Nothing changed: same body count, and the world steps exactly like one that never saw
    // the bad calls.
    EXPECT_EQ(world.bodyCount(), 1u);
    for (int i = 0; i < 30; ++i) {
        world.step();
        reference.step();
    }
    EXPECT_EQ(a.position(), r.position());
    EXPECT_EQ(a.linearVelocity(), r.linearVelocity());
    EXPECT_EQ(world.time(), reference.time());
}

TEST_P(BadInputTest, InvalidSettingsAreRefused) {
    WorldSettings s = settings();
    s.timeStep = 0;
    expectError([&] { World w(s); }, {"WorldSettings.timeStep", "must be > 0", "got 0"});
    s = settings();
    s.substeps = 0;
    expectError([&] { World w(s); }, {"WorldSettings.substeps", "must be in [1, 1000]", "got 0"});
    // A count a typo makes absurd (2e9 substeps) would hang the step: refused up front.
    s.substeps = 2000000000;
    expectError([&] { World w(s); }, {"WorldSettings.substeps", "kMaxSubsteps", "got 2000000000"});
    s = settings();
    s.iterations = 100001;
    expectError([&] { World w(s); }, {"WorldSettings.iterations", "kMaxIterations"});
    s = settings();
    s.maxStepsPerUpdate = 1001;
    expectError([&] { World w(s); }, {"WorldSettings.maxStepsPerUpdate", "kMaxStepsPerUpdate"});
    s = settings();
    s.gravity = Vec3(0, std::numeric_limits<double>::infinity(), 0);
    expectError([&] { World w(s); }, {"WorldSettings.gravity", "must be finite"});
}

TEST_P(BadInputTest, UnknownBackendListsKnownOnes) {
    WorldSettings s = settings();
    s.backend = "havok";
    expectError([&] { World w(s); }, {"backend", "\"havok\"", backend().c_str()});
}

TEST_P(BadInputTest, StaleHandlesThrowEvenAfterSlotReuse) {
    World world(settings());
    Body first = world.createBody(sphereDef(0.5));
    world.destroyBody(first);
    Body second = world.createBody(sphereDef(0.5));  // may reuse the slot
    EXPECT_FALSE(first.isValid());
    EXPECT_TRUE(second.isValid());
    expectError([&] { first.position(); }, {"Body.position", "stale body handle"});
    expectError([&] { world.destroyBody(first); }, {"World.destroyBody", "stale"});
    expectError([&] { Body().position(); }, {"null body handle"});
    EXPECT_EQ(world.bodyCount(), 1u);
}

TEST_P(BadInputTest, StructuralChangesInsideForceCallbackAreRefused) {
    World world(settings());
    Body b = world.createBody(sphereDef(0.5));
    bool refused = false;
    world.setForceCallback([&](ForceContext&) {
        try {
            world.createBody(sphereDef(0.5));
        } catch (const Error&) {
            refused = true;
        }
    });
    world.step();
    EXPECT_TRUE(refused);
    EXPECT_EQ(world.bodyCount(), 1u);
    EXPECT_TRUE(b.isValid());
}

// Every option the backend lists refuses a value outside its range, and a fraction where it
// counts: a value below the minimum, above a finite maximum, and 0.5 past an integer's minimum.
// The ends of the range are taken. The layer checks them all (BackendOption), whatever the policy:
// a bad value is a mistake, not a missing feature.
TEST_P(BadInputTest, BackendOptionsOutsideTheirRangeAreRefused) {
    for (const BackendOption& option : caps().options) {
        SCOPED_TRACE(option.name);
        const std::string field = "WorldSettings.backendOptions." + option.name;
        const auto with = [&](double value, CapabilityPolicy policy = CapabilityPolicy::Strict) {
            WorldSettings s = settings();
            s.capabilityPolicy = policy;
            s.backendOptions[option.name] = value;
            return s;
        };
        const std::string rule = "must be " + option.allowed();
        expectError([&] { World w(with(option.min - 1.0)); }, {field.c_str(), rule.c_str()});
        expectError([&] { World w(with(option.min - 1.0, CapabilityPolicy::Lenient)); }, {field.c_str()});
        if (std::isfinite(option.max)) {
            expectError([&] { World w(with(option.max + 1.0)); }, {field.c_str(), rule.c_str()});
            EXPECT_NO_THROW(World w(with(option.max)));
        }
        if (option.integer) expectError([&] { World w(with(option.min + 0.5)); }, {field.c_str(), "an integer"});
        EXPECT_NO_THROW(World w(with(option.min)));
    }
}

TEST_P(BadInputTest, StrictPolicyRefusesWhatTheBackendLacks) {
    // A setting no backend honours: an unknown backend option.
    WorldSettings s = settings();
    s.backendOptions["no_such_option"] = 1.0;
    expectError([&] { World w(s); }, {"does not support", "backend option no_such_option"});
    // The lenient policy runs anyway and warns once, naming what it runs without.
    s.capabilityPolicy = CapabilityPolicy::Lenient;
    ::testing::internal::CaptureStderr();
    World w(s);
    const std::string warned = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warned.find("no_such_option"), std::string::npos) << warned;
    EXPECT_EQ(warned.find("no_such_option"), warned.rfind("no_such_option")) << "warned more than once: " << warned;
    // And it really simulates: a dropped body falls g t^2 / 2 (1/2 step of semi-implicit slack).
    BodyDef def;
    def.shape = ShapeDef::sphere(0.1);
    def.position = Vec3(0, 10, 0);
    Body b = w.createBody(def);
    for (int i = 0; i < 60; ++i) w.step();
    const double t = w.time(), dt = w.settings().timeStep;
    EXPECT_NEAR(b.position().y(), 10.0 - 0.5 * 9.81 * t * t, 9.81 * t * dt);
}

ANYPHYS_CONTRACT_SUITE(BadInputTest);

}  // namespace
}  // namespace anyphys::test
