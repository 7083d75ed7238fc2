// A compound's children may carry their own material, filter and sensor flag (ShapeDef.material,
// layer, mask, isTrigger; default the body's). Every backend must apply them per child: friction
// follows the child that touches, a sensor child reports triggers and never pushes while the
// solid children still collide, and a child's filter lets a body through that child only.
// Every scene lies in the XY plane, so a planar-only backend runs them in a planar world.
#include <cmath>
#include <numbers>
#include <sstream>

#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class CompoundSurfacesTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }

    /// Skips, visibly, a backend that does not declare the per-child field or the effects.
    void requireChildField(const char* field, Effects effects) {
        const std::string parameter = std::string("body.shape.shapes.") + field;
        if (!caps().parameters.contains(parameter)) GTEST_SKIP() << "backend " << backend() << " lacks " << parameter;
        const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Box, ShapeType::Compound}, effects);
        if (!missing.empty()) GTEST_SKIP() << "backend " << backend() << " lacks " << missing;
    }
};

/// Counts each kind of event of one body pair.
struct PairEvents : ContactListener {
    BodyId a, b;
    int collisionEnter = 0, collisionExit = 0, triggerEnter = 0, triggerExit = 0;

    bool mine(const ContactEvent& e) const { return (e.bodyA == a && e.bodyB == b) || (e.bodyA == b && e.bodyB == a); }
    void onCollisionEnter(const ContactEvent& e) override { collisionEnter += mine(e); }
    void onCollisionExit(const ContactEvent& e) override { collisionExit += mine(e); }
    void onTriggerEnter(const ContactEvent& e) override { triggerEnter += mine(e); }
    void onTriggerExit(const ContactEvent& e) override { triggerExit += mine(e); }
};

BodyDef staticCompound(const std::string& name, std::vector<ShapeDef> children) {
    BodyDef def;
    def.name = name;
    def.type = BodyType::Static;
    def.shape = ShapeDef::compound(std::move(children));
    return def;
}

BodyDef ball(const std::string& name, const Vec3& at, double radius) {
    BodyDef def = sphereDef(radius);
    def.name = name;
    def.position = at;
    def.allowSleep = false;  // measured over the whole run: a sleeping ball proves nothing
    return def;
}

// ---- material ---------------------------------------------------------------------------------

// A two-box compound (a foot and a top, stacked) resting on a slope of theta = 20 deg: friction
// is the mix of the slope's material and the material of the child that touches, the foot. The
// slope's material has mu = 1, "grip" 0.25 and "slick" 0.04, so with the default geometric mean
// the foot meets mu = 0.5 (grip) or 0.2 (slick); tan(theta) = 0.364 lies between: a grip foot
// sticks and a slick one slides at g (sin theta - mu cos theta), whatever the top child or the
// body's material is.
struct SlopeRun {
    double travel = 0.0;  // m, along the slope, downhill positive, after `seconds`
    double seconds = 0.0;
};

SlopeRun runOnSlope(const WorldSettings& settings, const std::string& bodyMaterial, const std::string& footMaterial,
                    const std::string& topMaterial) {
    MaterialLibrary materials;
    materials.add("slope", {1.0, 0.0, 1000.0});
    materials.add("grip", {0.25, 0.0, 1000.0});
    materials.add("slick", {0.04, 0.0, 1000.0});
    World world(settings, materials);
    const double theta = 20.0 * std::numbers::pi / 180.0;
    const Quat tilt(Eigen::AngleAxisd(theta, Vec3::UnitZ()));  // the slope falls towards -x
    const Vec3 down = tilt * Vec3(-1, 0, 0), up = tilt * Vec3::UnitY();

    BodyDef slope;
    slope.name = "slope";
    slope.type = BodyType::Static;
    slope.material = "slope";
    slope.shape = ShapeDef::box(Vec3(6, 0.5, 2));
    slope.orientation = tilt;
    slope.position = -0.5 * up;  // its top face passes through the origin
    world.createBody(slope);

    ShapeDef foot = ShapeDef::box(Vec3(0.4, 0.1, 0.4)).placed(Vec3(0, -0.2, 0));
    foot.material = footMaterial;
    ShapeDef top = ShapeDef::box(Vec3(0.4, 0.1, 0.4)).placed(Vec3(0, 0.2, 0));
    if (!topMaterial.empty()) top.material = topMaterial;
    BodyDef block;
    block.name = "block";
    block.material = bodyMaterial;
    block.shape = ShapeDef::compound({foot, top});
    block.orientation = tilt;
    const Vec3 start = -4.0 * down + 0.3 * up;  // the foot's lower face on the slope's
    block.position = start;
    block.allowSleep = false;
    Body body = world.createBody(block);

    SlopeRun run;
    run.seconds = 1.5;
    const int steps = static_cast<int>(std::lround(run.seconds / settings.timeStep));
    for (int i = 0; i < steps; ++i) world.step();
    run.travel = (body.state().position - start).dot(down);
    return run;
}

TEST_P(CompoundSurfacesTest, FrictionFollowsTheChildThatTouches) {
    requireChildField("material", Effect::Contacts | Effect::Friction);
    const WorldSettings s = settings();
    const double theta = 20.0 * std::numbers::pi / 180.0, g = 9.81;

    // Grip foot on a body of slick material (and a slick top): mu 0.5 > tan theta, it sticks.
    // Allowed creep 1 cm over 1.5 s: settling into the contact (the solver's slop, a few mm),
    // not sliding, which would cover 1.7 m.
    const SlopeRun stuck = runOnSlope(s, "slick", "grip", "slick");
    EXPECT_LT(std::abs(stuck.travel), 0.01) << "a grip foot (mu 0.5 > tan 20 deg = 0.364) must stick";

    // Slick foot on a body of grip material (and a grip top): mu 0.2 < tan theta, it slides at
    // a = g (sin theta - 0.2 cos theta) = 1.51 m/s^2, 1.70 m in 1.5 s. Tolerance 5 %: semi-implicit
    // Euler runs ahead of 0.5 a t^2 by 1/n (1.1 % at 90 steps), the first steps settle the contact,
    // and a float engine (Box2D) rounds the friction bound; a body taking the grip top's or the
    // body's mu (0.5) would not move at all.
    const SlopeRun slid = runOnSlope(s, "grip", "slick", "grip");
    const double a = g * (std::sin(theta) - 0.2 * std::cos(theta));
    const double expected = 0.5 * a * slid.seconds * slid.seconds;
    EXPECT_NEAR(slid.travel, expected, 0.05 * expected) << "a slick foot (mu 0.2) must slide at g (sin - mu cos)";
}

// ---- sensor -------------------------------------------------------------------------------------

// A static compound: a solid slab (top face y = 0) and, 1.5 m above it, a sensor box child. A
// ball dropped through the sensor gets one trigger enter and one trigger exit, falls on through
// (no push: it keeps free fall's speed) and comes to rest on the slab with one collision enter.
TEST_P(CompoundSurfacesTest, BallFallsThroughSensorChildAndRestsOnSolidChild) {
    requireChildField("isTrigger", Effect::Contacts | Effect::Events);
    World world(settings());
    ShapeDef slab = ShapeDef::box(Vec3(3, 0.2, 3)).placed(Vec3(0, -0.2, 0));
    ShapeDef sensor = ShapeDef::box(Vec3(0.8, 0.5, 0.8)).placed(Vec3(0, 2.0, 0));
    sensor.isTrigger = true;
    Body station = world.createBody(staticCompound("station", {slab, sensor}));
    const double radius = 0.2, dropFrom = 4.0;
    Body b = world.createBody(ball("ball", Vec3(0, dropFrom, 0), radius));
    PairEvents events;
    events.a = station.id();
    events.b = b.id();
    world.addListener(&events);

    // Free fall from 4 m to the sensor's lower face at 1.5 m: the speed there, from energy.
    const double sensorBottom = 1.5, g = 9.81;
    double speedBelowSensor = -1.0;
    for (int i = 0; i < 180; ++i) {
        world.step();
        const BodyState st = b.state();
        if (speedBelowSensor < 0 && st.position.y() + radius < sensorBottom - 0.1) speedBelowSensor = -st.linearVelocity.y();
    }
    EXPECT_EQ(events.triggerEnter, 1);
    EXPECT_EQ(events.triggerExit, 1);
    EXPECT_EQ(events.collisionEnter, 1) << "the slab child must still collide";
    EXPECT_EQ(events.collisionExit, 0);
    // A sensor that pushed would have slowed the ball; 3 % covers the discrete step's energy
    // error of semi-implicit Euler over the fall (h g / v, under 1 % here) and float rounding.
    const double freeFall = std::sqrt(2 * g * (dropFrom - (sensorBottom - 0.1 - radius)));
    EXPECT_NEAR(speedBelowSensor, freeFall, 0.03 * freeFall) << "the sensor child must not push";
    // Resting on the slab: its centre one radius above y = 0, within 5 mm (the engines' contact
    // slop and skins are at most a few millimetres).
    EXPECT_NEAR(b.state().position.y(), radius, 0.005);
    EXPECT_LT(b.state().linearVelocity.norm(), 0.05);
}

// The sensor child encloses the slab's top, so the ball resting on the slab sits inside it: the
// body pair touches (collision) and overlaps the sensor (trigger) at once, two pairs with their
// own enters and no exits while it rests.
TEST_P(CompoundSurfacesTest, BallRestingInsideSensorChildHasBothCollisionAndTrigger) {
    requireChildField("isTrigger", Effect::Contacts | Effect::Events);
    World world(settings());
    ShapeDef slab = ShapeDef::box(Vec3(3, 0.2, 3)).placed(Vec3(0, -0.2, 0));
    ShapeDef sensor = ShapeDef::box(Vec3(1, 0.5, 1)).placed(Vec3(0, 0.3, 0));
    sensor.isTrigger = true;
    Body station = world.createBody(staticCompound("station", {slab, sensor}));
    const double radius = 0.2;
    Body b = world.createBody(ball("ball", Vec3(0, 2.0, 0), radius));
    PairEvents events;
    events.a = station.id();
    events.b = b.id();
    world.addListener(&events);
    for (int i = 0; i < 150; ++i) world.step();
    EXPECT_EQ(events.triggerEnter, 1);
    EXPECT_EQ(events.triggerExit, 0) << "resting inside the sensor child";
    EXPECT_EQ(events.collisionEnter, 1);
    EXPECT_EQ(events.collisionExit, 0);
    EXPECT_NEAR(b.state().position.y(), radius, 0.005) << "resting on the slab, not held by the sensor";
}

// A fast ball (40 m/s, 0.67 m per step, more than the slab's 0.1 m plus its 0.2 m diameter)
// shot down through a sensor child onto a thin solid child must be stopped by the solid child:
// the backend's continuous collision has to tell the children apart (a sweep that took the
// compound as one solid would stop the ball at the sensor; one that skipped it, not at all).
TEST_P(CompoundSurfacesTest, FastBallThroughSensorChildIsStoppedBySolidChild) {
    requireChildField("isTrigger", Effect::Contacts | Effect::ContinuousCollision | Effect::Events);
    World world(settings());
    ShapeDef slab = ShapeDef::box(Vec3(3, 0.05, 3)).placed(Vec3(0, -0.05, 0));
    ShapeDef sensor = ShapeDef::box(Vec3(1, 1, 1)).placed(Vec3(0, 1.2, 0));
    sensor.isTrigger = true;
    Body station = world.createBody(staticCompound("station", {slab, sensor}));
    const double radius = 0.1;
    BodyDef shot = ball("shot", Vec3(0, 4, 0), radius);
    shot.linearVelocity = Vec3(0, -40, 0);
    Body b = world.createBody(shot);
    PairEvents events;
    events.a = station.id();
    events.b = b.id();
    world.addListener(&events);
    double lowest = b.state().position.y();
    for (int i = 0; i < 60; ++i) {
        world.step();
        lowest = std::min(lowest, b.state().position.y());
    }
    EXPECT_EQ(events.triggerEnter, 1) << "the ball crossed the sensor child";
    // Stopped above the slab's lower face (y = -0.1): a ball that tunnelled falls on for a second.
    const bool stopped = lowest > -0.1 && b.state().position.y() > 0.0;
    std::ostringstream measured;
    measured << "lowest centre y " << lowest << " m, final " << b.state().position.y() << " m (slab top y = 0)";
    expectCriterion("compound.fast_body_stopped_by_solid_child", stopped, measured.str());
}

// The same with a filter: the upper child's mask leaves out the ball's layer, so the fast ball
// passes it and must be stopped by the thin slab child below.
TEST_P(CompoundSurfacesTest, FastBallThroughFilteredChildIsStoppedByTheOtherChild) {
    requireChildField("mask", Effect::Contacts | Effect::ContinuousCollision);
    World world(settings());
    ShapeDef slab = ShapeDef::box(Vec3(3, 0.05, 3)).placed(Vec3(0, -0.05, 0));
    ShapeDef roof = ShapeDef::box(Vec3(3, 0.05, 3)).placed(Vec3(0, 1.5, 0));
    roof.mask = ~std::uint32_t(2);
    world.createBody(staticCompound("shelter", {slab, roof}));
    BodyDef shot = ball("shot", Vec3(0, 4, 0), 0.1);
    shot.layer = 2;
    shot.linearVelocity = Vec3(0, -40, 0);
    Body b = world.createBody(shot);
    double lowest = b.state().position.y(), afterRoof = 0.0;
    const int roofPassed = 5;  // steps: past the roof (y 1.55), not yet at the slab (free flight 0.63 m)
    for (int i = 1; i <= 60; ++i) {
        world.step();
        lowest = std::min(lowest, b.state().position.y());
        if (i == roofPassed) afterRoof = b.state().position.y();
    }
    const bool stopped = lowest > -0.1 && b.state().position.y() > 0.0;
    std::ostringstream measured;
    measured << "lowest centre y " << lowest << " m, final " << b.state().position.y() << " m (slab top y = 0)";
    expectCriterion("compound.fast_body_stopped_by_unfiltered_child", stopped, measured.str());
    // Not held at the roof it passes: at step 5 free flight puts it at 4 - 40 t - g t^2 / 2. 2 cm
    // covers the integrators' difference from that (g h t / 2 = 7 mm for semi-implicit Euler);
    // a step's hold at the roof would leave it 0.67 m behind.
    const double t = roofPassed * settings().timeStep, freeFlight = 4 - 40 * t - 0.5 * 9.81 * t * t;
    std::ostringstream late;
    late << "centre y " << afterRoof << " m at step " << roofPassed << ", free flight " << freeFlight << " m";
    expectCriterion("compound.fast_body_passes_filtered_child", std::abs(afterRoof - freeFlight) < 0.02, late.str(),
                    std::abs(afterRoof - freeFlight));
}

// ---- filter -------------------------------------------------------------------------------------

// Two shelves of one static compound: the lower (top face y = 0) with the body's filter, the
// upper (top face y = 2) with a mask that leaves out layer 2. A ball on layer 2 falls through
// the upper shelf and rests on the lower; a ball on layer 1 rests on the upper.
TEST_P(CompoundSurfacesTest, ChildMaskLetsOneLayerThroughThatChildOnly) {
    requireChildField("mask", Effect::Contacts);
    World world(settings());
    ShapeDef lower = ShapeDef::box(Vec3(3, 0.2, 3)).placed(Vec3(0, -0.2, 0));
    ShapeDef upper = ShapeDef::box(Vec3(3, 0.2, 3)).placed(Vec3(0, 1.8, 0));
    upper.mask = ~std::uint32_t(2);
    world.createBody(staticCompound("shelves", {lower, upper}));
    const double radius = 0.2;
    BodyDef passer = ball("passer", Vec3(-1, 3, 0), radius);
    passer.layer = 2;
    BodyDef stopped = ball("stopped", Vec3(1, 3, 0), radius);
    Body p = world.createBody(passer), q = world.createBody(stopped);
    for (int i = 0; i < 180; ++i) world.step();
    // Resting heights within 5 mm (contact slop and skins), against 2 m between the shelves.
    EXPECT_NEAR(p.state().position.y(), radius, 0.005) << "layer 2 passes the upper shelf, rests on the lower";
    EXPECT_NEAR(q.state().position.y(), 2.0 + radius, 0.005) << "layer 1 rests on the upper shelf";
}

// A child's layer is what others' masks see: the ball's mask leaves out layer 4, the upper
// shelf's layer, so it passes that shelf; the lower shelf keeps the body's layer 1.
TEST_P(CompoundSurfacesTest, ChildLayerIsWhatOtherMasksSee) {
    requireChildField("layer", Effect::Contacts);
    World world(settings());
    ShapeDef lower = ShapeDef::box(Vec3(3, 0.2, 3)).placed(Vec3(0, -0.2, 0));
    ShapeDef upper = ShapeDef::box(Vec3(3, 0.2, 3)).placed(Vec3(0, 1.8, 0));
    upper.layer = 4;
    world.createBody(staticCompound("shelves", {lower, upper}));
    const double radius = 0.2;
    BodyDef passer = ball("passer", Vec3(0, 3, 0), radius);
    passer.mask = ~std::uint32_t(4);
    Body p = world.createBody(passer);
    for (int i = 0; i < 180; ++i) world.step();
    EXPECT_NEAR(p.state().position.y(), radius, 0.005);
}

// ---- queries ------------------------------------------------------------------------------------

// Queries skip sensors and bodies off their mask; for a compound that is per child. A ray down
// through the station meets the sensor child first (top y = 2.5) and must report the slab
// (top y = 0); an overlap probe inside the sensor child finds nothing, one on the slab finds it;
// a ray whose mask leaves out the upper shelf's layer hits the lower shelf.
TEST_P(CompoundSurfacesTest, QueriesSkipSensorChildrenAndChildrenOffTheirMask) {
    requireChildField("isTrigger", Effects{});
    ANYPHYS_REQUIRE(caps().queries.contains("raycast") && caps().queries.contains("overlap"), "raycast and overlap queries");
    World world(settings());
    ShapeDef slab = ShapeDef::box(Vec3(3, 0.2, 3)).placed(Vec3(0, -0.2, 0));
    ShapeDef sensor = ShapeDef::box(Vec3(0.8, 0.5, 0.8)).placed(Vec3(0, 2.0, 0));
    sensor.isTrigger = true;
    ShapeDef shelf = ShapeDef::box(Vec3(1, 0.1, 1)).placed(Vec3(2, 1.0, 0));
    shelf.layer = 4;
    Body station = world.createBody(staticCompound("station", {slab, sensor, shelf}));

    const auto hit = world.raycast(Vec3(0, 5, 0), Vec3(0, -1, 0), 10);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->body.id(), station.id());
    // Exact up to the engine's rounding of a 5 m distance (float engines: a few 1e-7 m).
    EXPECT_NEAR(hit->distance, 5.0, 1e-5 + rounding(5.0, 8)) << "the ray passes the sensor child";

    EXPECT_TRUE(world.overlap(ShapeDef::sphere(0.1), Transform{Vec3(0, 2.0, 0), Quat::Identity()}).empty())
        << "inside the sensor child only";
    EXPECT_EQ(world.overlap(ShapeDef::sphere(0.1), Transform{Vec3(0, -0.05, 0), Quat::Identity()}).size(), 1u);

    const auto onShelf = world.raycast(Vec3(2, 5, 0), Vec3(0, -1, 0), 10);
    ASSERT_TRUE(onShelf.has_value());
    EXPECT_NEAR(onShelf->distance, 3.9, 1e-5 + rounding(5.0, 8)) << "layer 4 is in the default mask";
    const auto pastShelf = world.raycast(Vec3(2, 5, 0), Vec3(0, -1, 0), 10, ~std::uint32_t(4));
    ASSERT_TRUE(pastShelf.has_value());
    EXPECT_NEAR(pastShelf->distance, 5.0, 1e-5 + rounding(5.0, 8)) << "a mask without layer 4 passes the shelf child";
}

// ---- a moving compound ----------------------------------------------------------------------------

// A dynamic compound (a box and, below it, a sensor child reaching into the ground) lands on the
// box: the sensor child reports a trigger with the ground and never holds the body up.
TEST_P(CompoundSurfacesTest, DynamicCompoundRestsOnItsSolidChildWithItsSensorInTheGround) {
    requireChildField("isTrigger", Effect::Contacts | Effect::Events);
    World world(settings());
    BodyDef groundBody;
    groundBody.name = "ground";
    groundBody.type = BodyType::Static;
    groundBody.shape = ShapeDef::box(Vec3(5, 0.5, 5));
    groundBody.position = Vec3(0, -0.5, 0);
    Body ground = world.createBody(groundBody);
    ShapeDef hull = ShapeDef::box(Vec3(0.5, 0.25, 0.5));
    ShapeDef probe = ShapeDef::box(Vec3(0.2, 0.3, 0.2)).placed(Vec3(0, -0.5, 0));  // reaches 0.55 below the hull
    probe.isTrigger = true;
    BodyDef vehicle;
    vehicle.name = "vehicle";
    vehicle.shape = ShapeDef::compound({hull, probe});
    vehicle.position = Vec3(0, 1.0, 0);
    vehicle.allowSleep = false;
    Body v = world.createBody(vehicle);
    PairEvents events;
    events.a = ground.id();
    events.b = v.id();
    world.addListener(&events);
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_EQ(events.triggerEnter, 1);
    EXPECT_EQ(events.triggerExit, 0);
    EXPECT_EQ(events.collisionEnter, 1);
    // The hull's lower face on the ground (origin 0.25 up), within 5 mm (contact slop, skins);
    // held by the sensor child it would stand 0.55 m higher.
    EXPECT_NEAR(v.state().position.y(), 0.25, 0.005);
}

// ---- input --------------------------------------------------------------------------------------

TEST_P(CompoundSurfacesTest, OverridesAreRefusedOutsideCompoundsAndUnknownMaterialsNamed) {
    World world(settings());
    BodyDef lone = sphereDef(0.5);
    lone.shape.material = "ice";
    try {
        world.createBody(lone);
        ADD_FAILURE() << "a surface override on a lone shape must be refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "BodyDef.shape.material") << e.what();
    }
    ShapeDef child = ShapeDef::sphere(0.5);
    child.material = "no-such-material";
    BodyDef compound;
    compound.shape = ShapeDef::compound({ShapeDef::sphere(0.5), child});
    try {
        world.createBody(compound);
        ADD_FAILURE() << "an unknown child material must be refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "BodyDef.shape.shapes[1].material") << e.what();
        EXPECT_NE(std::string(e.what()).find("must name a material"), std::string::npos) << e.what();
    }
    EXPECT_EQ(world.bodyCount(), 0u) << "a rejected call changes nothing";
}

ANYPHYS_CONTRACT_SUITE(CompoundSurfacesTest);

}  // namespace
}  // namespace anyphys::test
