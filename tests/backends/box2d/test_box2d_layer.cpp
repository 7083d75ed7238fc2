// Box2D backend and the layer: capabilities, refusals, masses, filtering, triggers, queries, the
// escape hatch and lifetimes.
#include <gtest/gtest.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <memory>

#include "box2d_test_helpers.hpp"

namespace anyphys::box2d::test {
namespace {

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(Box2dLayer, DeclaresPlanarCapabilities) {
    const Capabilities caps = backendInfo("box2d").capabilities;
    EXPECT_EQ(caps.dimensions, 2);
    EXPECT_TRUE(caps.planar);
    EXPECT_EQ(caps.maxConvexVertices, 8);
    EXPECT_FALSE(caps.shapes.count(ShapeType::Mesh));
    EXPECT_EQ(caps.defaultIterations, 8);
    EXPECT_EQ(caps.defaultSubsteps, 1);
    EXPECT_EQ(caps.defaultSolver, Solver::ProjectedGaussSeidel);
    EXPECT_FALSE(caps.parameters.count("settings.linearSlop"));  // b2_linearSlop is compile-time
}

TEST(Box2dLayer, RefusesThreeDimensionalWorld) {
    WorldSettings s;
    s.backend = "box2d";  // planar left false
    const std::string message = errorOf([&] { World w(s); });
    EXPECT_NE(message.find("WorldSettings.planar"), std::string::npos) << message;
    EXPECT_NE(message.find("planar worlds only"), std::string::npos) << message;
}

TEST(Box2dLayer, RefusesBodyOutOfPlane) {
    World world(planarSettings());
    const std::string message = errorOf([&] { world.createBody(ball("b", 0.5, Vec3(0, 0, 1))); });
    EXPECT_NE(message.find("BodyDef.position"), std::string::npos) << message;
    EXPECT_EQ(world.bodyCount(), 0u);
}

// A prism over a regular polygon of n sides: 2n points, n vertices in the XY outline.
std::vector<Vec3> prism(int n) {
    std::vector<Vec3> points;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * (i + 0.5) / n;  // a flat side at the bottom
        for (double z : {-0.5, 0.5}) points.emplace_back(0.5 * std::cos(a), 0.5 * std::sin(a), z);
    }
    return points;
}

TEST(Box2dLayer, ConvexHullOfNineOutlineVerticesIsRefusedNamingTheLimit) {
    World world(planarSettings());
    BodyDef def;
    def.name = "nonagon";
    def.shape = ShapeDef::convex(prism(9));
    const std::string message = errorOf([&] { world.createBody(def); });
    EXPECT_NE(message.find("BodyDef.shape.points"), std::string::npos) << message;
    EXPECT_NE(message.find("at most 8"), std::string::npos) << message;
    EXPECT_NE(message.find("got 9"), std::string::npos) << message;
    EXPECT_NE(message.find("nonagon"), std::string::npos) << message;
    EXPECT_EQ(world.bodyCount(), 0u);  // nothing changed
    // Eight is accepted, and falls onto the ground like anything else.
    world.createBody(ground());
    def.shape = ShapeDef::convex(prism(8));
    def.position = Vec3(0, 1, 0);
    Body b = world.createBody(def);
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_NEAR(b.position().y(), 0.5 * std::cos(std::numbers::pi / 8), 2e-3);  // resting on a flat side
}

// The vertex count of the polygon a body's one fixture collides with.
int polygonVertexCount(Body& b) {
    const b2Fixture* fixture = b.native<b2Body>()->GetFixtureList();
    EXPECT_EQ(fixture->GetType(), b2Shape::e_polygon);
    return static_cast<const b2PolygonShape*>(fixture->GetShape())->m_count;
}

// Outline vertices a hair off the line of their neighbours (a scanned or rounded hull) are left
// out: Box2D clips against one edge, and a bottom split into facets rocked on one of them. A
// plank's corners stay, however thin it is short of Box2D's weld distance.
TEST(Box2dLayer, NearlyFlatOutlineVerticesAreDroppedButCornersKept) {
    World world(planarSettings());
    world.createBody(ground());
    // An octagon whose flat bottom carries four points 10 um below it: twelve outline vertices in
    // the points, eight in the polygon (before, refused as more than 8).
    std::vector<Vec3> points = prism(8);
    const double bottom = -0.5 * std::cos(std::numbers::pi / 8);
    for (const double x : {-0.1, -0.05, 0.05, 0.1}) points.emplace_back(x, bottom - 1e-5 * (1 - std::abs(x)), 0.0);
    BodyDef def;
    def.shape = ShapeDef::convex(points);
    def.position = Vec3(0, 1, 0);
    def.allowSleep = false;
    Body octagon = world.createBody(def);
    EXPECT_EQ(polygonVertexCount(octagon), 8);
    // A plank 1 m long and 3 mm thick (Box2D welds corners 2.5 mm apart) keeps its four corners.
    const double t = 1.5e-3;
    def.shape = ShapeDef::convex({{-0.5, -t, -0.5}, {0.5, -t, -0.5}, {0.5, t, -0.5}, {-0.5, t, -0.5},
                                  {-0.5, -t, 0.5}, {0.5, -t, 0.5}, {0.5, t, 0.5}, {-0.5, t, 0.5}});
    def.position = Vec3(3, 1, 0);
    Body plank = world.createBody(def);
    EXPECT_EQ(polygonVertexCount(plank), 4);
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_NEAR(octagon.position().y(), -bottom, 2e-3);  // resting on its flat side
    EXPECT_NEAR(plank.position().y(), t, 2e-3);          // lying flat
    EXPECT_LT(std::abs(octagon.angularVelocity().z()), 1e-3);  // not rocking
}

// A hull spanning 1e7 m with its other corners within a metre of each other: in double its XY
// outline has four vertices and area, but in Box2D's floats the far corner rounds the near ones
// onto one line, and b2PolygonShape::Set aborted the process (found by the API fuzzer). Refused
// with an error naming the points; the world goes on.
TEST(Box2dLayer, HullTooThinForFloatIsRefusedNotAborted) {
    World world(planarSettings());
    BodyDef def;
    def.name = "sliver";
    def.type = BodyType::Static;
    def.shape = ShapeDef::convex({{-0.5605, -0.5247, -0.5247}, {-0.5247, -0.5605, -0.5247}, {-0.9283, -1.0, -1.0},
                                  {-1.0, -1.0, -1.0}, {-1.0, -1.0, -0.5874}, {-0.5874, -0.5874, -0.7130},
                                  {-1.0, -1.0, 1e5}, {1e7, 1e7, 1e7}});
    def.position = Vec3(1e7, 1e7, 0);
    const std::string message = errorOf([&] { world.createBody(def); });
    EXPECT_NE(message.find("BodyDef.shape.points"), std::string::npos) << message;
    EXPECT_NE(message.find("float"), std::string::npos) << message;
    EXPECT_NE(message.find("sliver"), std::string::npos) << message;
    EXPECT_EQ(world.bodyCount(), 0u);
    // The same corners without the far one make an ordinary body.
    def.shape.points.resize(6);
    def.position = Vec3(0, 0, 0);
    Body b = world.createBody(def);
    for (int i = 0; i < 10; ++i) world.step();
    EXPECT_TRUE(b.position().allFinite());
}

// The layer's mass, not Box2D's area density: a 1 m cube at 1000 kg/m^3 weighs 1000 kg and turns
// about Z with Izz = m (1 + 1) / 12. Float storage: 1e-6 relative.
TEST(Box2dLayer, MassesAreTheLayers) {
    World world(planarSettings());
    Body b = world.createBody(box("cube", Vec3(0.5, 0.5, 0.5), Vec3::Zero()));
    const b2Body* native = b.native<b2Body>();
    ASSERT_NE(native, nullptr);
    EXPECT_NEAR(native->GetMass(), 1000.0, 1e-6 * 1000);
    EXPECT_NEAR(native->GetInertia(), 1000.0 * 2 / 12, 1e-6 * 1000);
    EXPECT_NEAR(b.massProperties().mass, 1000.0, 1e-6 * 1000);
    // A sphere: 4/3 pi r^3 rho, Izz = 2/5 m r^2.
    Body s = world.createBody(ball("s", 0.5, Vec3(3, 0, 0)));
    const double m = 4.0 / 3.0 * std::numbers::pi * 0.125 * 1000;
    EXPECT_NEAR(s.native<b2Body>()->GetMass(), m, 1e-6 * m);
    EXPECT_NEAR(s.native<b2Body>()->GetInertia(), 0.4 * m * 0.25, 1e-6 * m);
}

// A compound whose centre of mass is off the origin: the peer frame sits at the centre of mass,
// and the body's origin still round-trips through Box2D.
TEST(Box2dLayer, CompoundKeepsBodyOrigin) {
    WorldSettings s = planarSettings();
    s.gravity = Vec3::Zero();
    World world(s);
    BodyDef def;
    def.name = "dumbbell";
    def.shape = ShapeDef::compound({ShapeDef::sphere(0.2).placed(Vec3(1, 0, 0)),
                                    ShapeDef::box(Vec3(0.5, 0.1, 0.1)).placed(Vec3(0, 0, 0),
                                                                             Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())))});
    def.position = Vec3(2, 3, 0);
    def.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ()));
    Body b = world.createBody(def);
    EXPECT_TRUE(b.position().isApprox(def.position, 1e-6)) << b.position().transpose();
    EXPECT_TRUE(b.orientation().isApprox(def.orientation, 1e-6));
    b.setAngularVelocity(Vec3(0, 0, 1));
    for (int i = 0; i < 60; ++i) world.step();
    // Spinning about its centre of mass: that point stays put.
    const Vec3 com = b.centerOfMass();
    for (int i = 0; i < 60; ++i) world.step();
    EXPECT_TRUE(b.centerOfMass().isApprox(com, 1e-5)) << b.centerOfMass().transpose();
    EXPECT_NEAR(b.orientation().angularDistance(def.orientation), 2.0, 1e-4);
}

// A body whose principal frame is not a rotation about Z: a tall box (z half extent 3 m) turned
// 0.3 rad about Z as a compound child has off-diagonal xy inertia and its smallest moment about
// Z, so the layer's eigen decomposition puts the peer's x axis along world Z. The backend keeps
// that tilt as a constant offset: Box2D turns about Z with the layer's Izz, and the user still
// sees a body in the plane. 1e-6: float storage of positions and angles.
TEST(Box2dLayer, TiltedPrincipalFrameStaysPlanar) {
    World world(planarSettings());
    world.createBody(ground());
    BodyDef def;
    def.name = "tall";
    def.shape = ShapeDef::compound({ShapeDef::box(Vec3(1.0, 0.2, 3.0)).placed(Vec3::Zero(),
                                                                         Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())))});
    def.position = Vec3(0, 2, 0);
    Body b = world.createBody(def);
    const MassProperties m = b.massProperties();
    const double mass = 1000.0 * 2.0 * 0.4 * 6.0;
    EXPECT_NEAR(m.mass, mass, 1e-6 * mass);
    // Izz of the box is invariant under a turn about Z: m (2^2 + 0.4^2) / 12.
    EXPECT_NEAR(b.native<b2Body>()->GetInertia(), mass * (4.0 + 0.16) / 12.0, 1e-5 * mass);
    double worstZ = 0.0, worstTilt = 0.0;
    for (int i = 0; i < 180; ++i) {
        world.step();
        worstZ = std::max(worstZ, std::abs(b.position().z()));
        worstTilt = std::max({worstTilt, std::abs(b.orientation().x()), std::abs(b.orientation().y())});
    }
    EXPECT_LT(worstZ, 1e-6);
    EXPECT_LT(worstTilt, 1e-6);
    EXPECT_LT(b.position().y(), 1.0);  // it fell and landed (lowest corner on the ground)
    EXPECT_GT(b.position().y(), 0.1);
}

// A convex hull uneven in z has its centre of mass off the plane (z != 0): the peer frame keeps
// that height, and the body origin stays at z = 0.
TEST(Box2dLayer, ConvexWithCentreOfMassOffThePlane) {
    World world(planarSettings());
    world.createBody(ground());
    BodyDef def;
    def.name = "wedge";
    def.shape = ShapeDef::convex({Vec3(-0.5, -0.5, 0), Vec3(0.5, -0.5, 0), Vec3(0.5, 0.5, 0), Vec3(-0.5, 0.5, 0),
                                  Vec3(0, 0, 1)});  // a pyramid standing on z = 0
    def.position = Vec3(0, 1, 0);
    Body b = world.createBody(def);
    EXPECT_GT(std::abs(b.centerOfMass().z()), 0.1);
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_LT(std::abs(b.position().z()), 1e-6);
    EXPECT_NEAR(b.position().y(), 0.5, 2e-3);  // resting on its square outline
}

// Filtering: a ball whose mask leaves out the ground's layer falls through it; the other lands.
TEST(Box2dLayer, LayersAndMasksFilterPairs) {
    World world(planarSettings());
    BodyDef g = ground();
    g.layer = 2;
    world.createBody(g);
    BodyDef a = ball("passes", 0.25, Vec3(0, 1, 0));
    a.mask = ~2u;
    BodyDef c = ball("lands", 0.25, Vec3(2, 1, 0));
    Body passes = world.createBody(a);
    Body lands = world.createBody(c);
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_LT(passes.position().y(), -1.0);
    EXPECT_NEAR(lands.position().y(), 0.25, 1e-3);
}

struct Recorder : ContactListener {
    int triggerEnter = 0, triggerExit = 0, collisionEnter = 0;
    void onTriggerEnter(const ContactEvent& e) override { triggerEnter += e.trigger; }
    void onTriggerExit(const ContactEvent& e) override { triggerExit += e.trigger; }
    void onCollisionEnter(const ContactEvent&) override { ++collisionEnter; }
};

// A ball falls through a sensor box onto the ground: one trigger enter, one trigger exit, and the
// sensor never stops it.
TEST(Box2dLayer, TriggersReportEnterAndExit) {
    World world(planarSettings());
    Recorder recorder;
    world.addListener(&recorder);
    world.createBody(ground());
    BodyDef sensor = box("sensor", Vec3(1, 0.25, 0.5), Vec3(0, 2, 0));
    sensor.type = BodyType::Static;
    sensor.isTrigger = true;
    world.createBody(sensor);
    Body b = world.createBody(ball("ball", 0.2, Vec3(0, 4, 0)));
    for (int i = 0; i < 180; ++i) world.step();
    EXPECT_EQ(recorder.triggerEnter, 1);
    EXPECT_EQ(recorder.triggerExit, 1);
    EXPECT_EQ(recorder.collisionEnter, 1);  // the ground
    EXPECT_NEAR(b.position().y(), 0.2, 1e-3);
}

// Contact events: lower id first, normal from A to B, depths against the true surfaces. The
// ground (created first) is A, so the normal is +Y whichever fixture Box2D made A; a resting
// ball's depth is about 0 (within b2_linearSlop / 2: the skin absorbs Box2D's slop).
TEST(Box2dLayer, ContactNormalPointsFromAToB) {
    World world(planarSettings());
    Body g = world.createBody(ground());
    Body b = world.createBody(ball("ball", 0.5, Vec3(0, 0.5, 0)));
    world.step();  // the enter event (it would sleep, eventless, after 0.5 s at rest)
    ASSERT_EQ(world.lastEvents().size(), 1u);
    const ContactEvent& e = world.lastEvents().front();
    EXPECT_EQ(e.bodyA, g.id());
    EXPECT_EQ(e.bodyB, b.id());
    EXPECT_TRUE(e.normal.isApprox(Vec3(0, 1, 0), 1e-6)) << e.normal.transpose();
    ASSERT_FALSE(e.points.empty());
    EXPECT_NEAR(e.points[0].depth, 0.0, 0.0025);
    EXPECT_NEAR(e.points[0].position.y(), 0.0, 0.0025);
}

// Ray casts hit the true surfaces (not Box2D's skin): exact face distances within float
// precision (1e-5 m at these magnitudes). Sensors are skipped, masks apply.
TEST(Box2dLayer, RaycastClosestAndAll) {
    WorldSettings s = planarSettings();
    s.gravity = Vec3::Zero();
    World world(s);
    std::vector<Body> boxes;
    for (int i = 0; i < 3; ++i) {
        BodyDef def = box("b" + std::to_string(i), Vec3(0.25, 0.25, 0.25), Vec3(2.0 + 2 * i, 0, 0));
        def.layer = i == 2 ? 2u : 1u;
        boxes.push_back(world.createBody(def));
    }
    BodyDef sensor = ball("sensor", 0.3, Vec3(1, 0, 0));
    sensor.isTrigger = true;
    world.createBody(sensor);
    BodyDef disc = ball("disc", 0.5, Vec3(10, 0, 0));
    Body discBody = world.createBody(disc);

    const auto closest = world.raycast(Vec3::Zero(), Vec3(1, 0, 0), 100.0);
    ASSERT_TRUE(closest.has_value());
    EXPECT_TRUE(closest->body == boxes[0]);
    EXPECT_NEAR(closest->distance, 1.75, 1e-5);
    EXPECT_TRUE(closest->normal.isApprox(Vec3(-1, 0, 0), 1e-6));

    const auto all = world.raycastAll(Vec3::Zero(), Vec3(1, 0, 0), 100.0);
    ASSERT_EQ(all.size(), 4u);
    EXPECT_NEAR(all[0].distance, 1.75, 1e-5);
    EXPECT_NEAR(all[1].distance, 3.75, 1e-5);
    EXPECT_NEAR(all[2].distance, 5.75, 1e-5);
    EXPECT_NEAR(all[3].distance, 9.5, 1e-5);  // the disc: its true radius
    EXPECT_TRUE(all[3].body == discBody);

    const auto masked = world.raycastAll(Vec3::Zero(), Vec3(1, 0, 0), 100.0, 2u);
    ASSERT_EQ(masked.size(), 1u);
    EXPECT_TRUE(masked[0].body == boxes[2]);
    EXPECT_TRUE(world.raycastAll(Vec3::Zero(), Vec3(1, 0, 0), 1.5).empty());

    // A ray leaving the plane has no planar answer: refused, naming the field.
    const std::string message = errorOf([&] { world.raycast(Vec3::Zero(), Vec3(1, 0, 1), 10.0); });
    EXPECT_NE(message.find("World.raycast.direction"), std::string::npos) << message;
}

// A plane is a run of Box2D edges (box2d_shapes.cpp: from 1 km either side of the origin, each
// twice the last). A ray down through the point where two of them meet, or far out along the
// plane, hits the one plane once, at its surface.
TEST(Box2dLayer, RayHitsAPlaneOnceAnywhereAlongIt) {
    WorldSettings s = planarSettings();
    s.gravity = Vec3::Zero();
    World world(s);
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::plane(Vec3(0, 1, 0), 0.0);
    world.createBody(ground);
    for (const double x : {0.0, 1000.0, -2000.0, 3000.0, 1e5, -5e6}) {
        const auto all = world.raycastAll(Vec3(x, 10, 0), Vec3(0, -1, 0), 20.0);
        ASSERT_EQ(all.size(), 1u) << "ray down at x = " << x;
        EXPECT_NEAR(all[0].distance, 10.0, 1e-5) << "ray down at x = " << x;  // float rounding of 10 m
    }
}

// Overlap against true shapes; a plane is a half-plane (anything reaching below it overlaps).
TEST(Box2dLayer, OverlapQueries) {
    WorldSettings s = planarSettings();
    s.gravity = Vec3::Zero();
    World world(s);
    Body g = world.createBody(ground());
    Body a = world.createBody(box("a", Vec3(0.5, 0.5, 0.5), Vec3(0, 2, 0)));
    Body c = world.createBody(ball("c", 0.5, Vec3(3, 2, 0)));
    const auto hits = [&](const ShapeDef& shape, const Vec3& at) { return world.overlap(shape, {at, Quat::Identity()}); };
    EXPECT_EQ(hits(ShapeDef::sphere(0.2), Vec3(0.6, 2, 0)).size(), 1u);   // reaches 0.1 into box a
    EXPECT_TRUE(hits(ShapeDef::sphere(0.2), Vec3(0.75, 2, 0)).empty());   // 5 cm clear of it
    EXPECT_TRUE(hits(ShapeDef::sphere(0.2), Vec3(1.5, 0.25, 0)).empty()); // 5 cm above the ground
    const auto low = hits(ShapeDef::sphere(0.2), Vec3(1.5, 0.15, 0));
    ASSERT_EQ(low.size(), 1u);
    EXPECT_TRUE(low[0] == g);
    const auto both = hits(ShapeDef::box(Vec3(2, 0.2, 0.2)), Vec3(1.5, 2, 0));
    EXPECT_EQ(both.size(), 2u);
    (void)a;
    (void)c;
}

// Escape hatch: the b2World and b2Body behind the handles; other types give nullptr.
TEST(Box2dLayer, EscapeHatchGivesBox2dObjects) {
    World world(planarSettings());
    Body b = world.createBody(ball("b", 0.5, Vec3(0, 1, 0)));
    b2World* native = world.native<b2World>();
    ASSERT_NE(native, nullptr);
    b2Body* body = b.native<b2Body>();
    ASSERT_NE(body, nullptr);
    EXPECT_EQ(body->GetWorld(), native);
    EXPECT_EQ(native->GetBodyCount(), 1);
    EXPECT_EQ(world.native<int>(), nullptr);
    EXPECT_EQ(b.native<b2World>(), nullptr);
}

// Destroying a body wakes what rested on it, so it falls.
TEST(Box2dLayer, DestroyingSupportWakesBodyAbove) {
    World world(planarSettings());
    world.createBody(ground());
    Body lower = world.createBody(box("lower", Vec3(0.5, 0.5, 0.5), Vec3(0, 0.5, 0)));
    Body upper = world.createBody(box("upper", Vec3(0.5, 0.5, 0.5), Vec3(0, 1.5, 0)));
    for (int i = 0; i < 180; ++i) world.step();
    ASSERT_FALSE(upper.isAwake());
    world.destroyBody(lower);
    EXPECT_TRUE(upper.isAwake());
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_NEAR(upper.position().y(), 0.5, 2e-3);
}

// Lifetimes: worlds with live bodies go away cleanly (LeakSanitizer checks the sanitizer build),
// bodies and worlds in any order, and a Box2D world coexists with a native one.
TEST(Box2dLayer, WorldsAndBodiesInAnyOrderAlongsideNative) {
    {
        World world(planarSettings());
        world.createBody(ground());
        for (int i = 0; i < 20; ++i) world.createBody(ball("b" + std::to_string(i), 0.2, Vec3(0.1 * i, 1 + 0.5 * i, 0)));
        for (int i = 0; i < 30; ++i) world.step();
    }  // destroyed with its bodies
    auto box2dWorld = std::make_unique<World>(planarSettings());
    World native;  // default: the native backend, 3D
    std::vector<Body> bodies;
    for (int i = 0; i < 5; ++i) bodies.push_back(box2dWorld->createBody(ball("b" + std::to_string(i), 0.2, Vec3(i, 1, 0))));
    Body n = native.createBody(ball("n", 0.2, Vec3(0, 1, 0)));
    box2dWorld->destroyBody(bodies[2]);
    EXPECT_THROW(bodies[2].position(), Error);
    for (int i = 0; i < 10; ++i) {
        box2dWorld->step();
        native.step();
    }
    EXPECT_NEAR(bodies[0].position().y(), n.position().y(), 1e-4);  // both fell freely for 10 steps
    box2dWorld.reset();
    native.step();
}

// Effects declared off are off: without gravity nothing falls, without contacts nothing collides.
TEST(Box2dLayer, DeclaredEffectsAreHonoured) {
    WorldSettings s = planarSettings();
    s.effects = Effects(Effect::Gravity);  // no contacts
    World world(s);
    world.createBody(ground());
    Body b = world.createBody(ball("b", 0.25, Vec3(0, 1, 0)));
    for (int i = 0; i < 60; ++i) world.step();
    EXPECT_LT(b.position().y(), -2.0);  // fell through the ground
    WorldSettings still = planarSettings();
    still.effects = Effects(Effect::Contacts);
    World world2(still);
    Body c = world2.createBody(ball("c", 0.25, Vec3(0, 1, 0)));
    for (int i = 0; i < 60; ++i) world2.step();
    EXPECT_EQ(c.position().y(), 1.0);
}

}  // namespace
}  // namespace anyphys::box2d::test
