// Debug drawing draws the same scene the same way on every backend: what it draws comes from the
// layer (defs, body states, the last step's events, the joints' frames), checked here against what
// the world reports through its handles.
#include <algorithm>
#include <cmath>
#include <string>

#include "contact_helpers.hpp"
#include "contract_fixture.hpp"
#include "recording_drawer.hpp"

namespace anyphys::test {
namespace {

constexpr double kBoxHalf = 0.25;           // m
constexpr double kBallRadius = 0.2;         // m
const Vec3 kHingeAnchor(3.0, 2.0, 0.0);     // m: the ball hangs 1 m below it, at rest
constexpr double kHingeLimit = 0.5;         // rad, both sides

struct DrawnScene {
    Body ground;
    std::vector<Body> boxes;  // three, apart from each other, on the ground
    Body ball;                // hangs from the hinge, off the ground
    Joint hinge;              // null where the backend has no hinge
};

class DebugDrawTest : public ContractTest {
protected:
    // Nothing drawn needs a third dimension: a planar-only backend runs it in the XY plane.
    bool runsPlanarWithout3D() const override { return true; }
    std::string missing() const {
        return lacking(caps(), {ShapeType::Box, ShapeType::Sphere, ShapeType::Plane}, Effect::Contacts);
    }
    bool hasHinge() const { return caps().effects.has(Effect::Joints) && caps().jointTypes.contains("hinge"); }
    bool hasHingeLimits() const { return hasHinge() && caps().parameters.contains("joint.hinge.limits"); }

    /// Ground plane, three boxes dropped 1 cm onto it, and a ball hanging from a hinge to the world
    /// (about Z, so planar worlds have it too) with limits where the backend honours them.
    DrawnScene build(World& world, bool allowSleep) const {
        DrawnScene s;
        s.ground = world.createBody(groundDef());
        for (int k = 0; k < 3; ++k) {
            BodyDef d = boxDef("box" + std::to_string(k), Vec3::Constant(kBoxHalf), Vec3(-2.0 + k, kBoxHalf + 0.01, 0));
            d.allowSleep = allowSleep;
            s.boxes.push_back(world.createBody(d));
        }
        BodyDef ball = ballDef("ball", kBallRadius, kHingeAnchor - Vec3(0, 1, 0));
        ball.allowSleep = allowSleep;
        s.ball = world.createBody(ball);
        if (hasHinge()) {
            JointDef j;
            j.type = JointType::Hinge;
            j.bodyB = s.ball;
            j.anchor = kHingeAnchor;
            if (hasHingeLimits()) j.limits = JointLimits{-kHingeLimit, kHingeLimit};
            s.hinge = world.createJoint(j);
        }
        return s;
    }

    static DebugDrawOptions everything() {
        DebugDrawOptions o;
        o.shapes = o.contacts = o.joints = o.jointLimits = o.bounds = true;
        return o;
    }
};

double angleBetween(const Quat& a, const Quat& b) { return a.angularDistance(b); }

/// The eight corners of a box shape at a pose.
std::vector<Vec3> corners(const Vec3& half, const Transform& pose) {
    std::vector<Vec3> out;
    for (int k = 0; k < 8; ++k) {
        const Vec3 local((k & 1 ? 1 : -1) * half.x(), (k & 2 ? 1 : -1) * half.y(), (k & 4 ? 1 : -1) * half.z());
        out.push_back(pose.position + pose.orientation * local);
    }
    return out;
}

// Every body is drawn once (one primitive each), at the pose its handle reports, in the colour
// of its type; contacts and bounds are off by default.
TEST_P(DebugDrawTest, ShapesAreDrawnAtTheBodiesPoses) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    const DrawnScene scene = build(world, false);
    for (int i = 0; i < 30; ++i) world.step();
    RecordingDrawer drawer;
    world.debugDraw(drawer);
    ASSERT_EQ(drawer.shapes.size(), world.bodyCount());
    EXPECT_TRUE(drawer.contacts.empty()) << "contacts are off by default";
    EXPECT_TRUE(drawer.bounds.empty()) << "bounds are off by default";
    const DebugPalette palette;
    for (const auto& drawn : drawer.shapes) {
        const Body body = world.body(drawn.body);
        EXPECT_EQ(drawn.shape.type, body.type() == BodyType::Static ? ShapeType::Plane
                                    : body == scene.ball          ? ShapeType::Sphere
                                                                  : ShapeType::Box);
        // The same numbers the handle reports: both are the layer's view of the peer's state.
        EXPECT_LT((drawn.pose.position - body.position()).norm(), 1e-12);
        EXPECT_LT(angleBetween(drawn.pose.orientation, body.orientation()), 1e-12);
        EXPECT_EQ(drawn.awake, body.type() != BodyType::Static && body.isAwake());
        EXPECT_EQ(drawn.color, body.type() == BodyType::Static ? palette.staticBody : palette.awakeBody);
    }
}

// A compound is drawn child by child, each at the body's pose composed with its placement.
TEST_P(DebugDrawTest, CompoundChildrenAreDrawnAtComposedPoses) {
    ANYPHYS_REQUIRE(lacking(caps(), {ShapeType::Compound, ShapeType::Sphere, ShapeType::Box}, {}).empty(),
                    lacking(caps(), {ShapeType::Compound, ShapeType::Sphere, ShapeType::Box}, {}));
    WorldSettings s = settings();
    s.gravity = Vec3::Zero();
    World world(s);
    BodyDef d;
    d.shape = ShapeDef::compound({ShapeDef::sphere(0.2).placed(Vec3(-0.5, 0, 0)),
                                  ShapeDef::box(Vec3(0.1, 0.2, 0.1)).placed(Vec3(0.5, 0, 0), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())))});
    d.position = Vec3(1, 2, 0);
    d.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ()));
    d.angularVelocity = Vec3(0, 0, 1);
    Body body = world.createBody(d);
    for (int i = 0; i < 10; ++i) world.step();
    RecordingDrawer drawer;
    world.debugDraw(drawer, [] { DebugDrawOptions o; o.bounds = true; return o; }());
    ASSERT_EQ(drawer.shapes.size(), 2u);
    ASSERT_EQ(drawer.bounds.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
        const ShapeDef& child = d.shape.shapes[k];
        const Vec3 expected = body.position() + body.orientation() * child.position;
        const Quat turn = body.orientation() * child.orientation;
        EXPECT_EQ(drawer.shapes[k].shape.type, child.type);
        EXPECT_LT((drawer.shapes[k].pose.position - expected).norm(), 1e-12);
        EXPECT_LT(angleBetween(drawer.shapes[k].pose.orientation, turn), 1e-12);
    }
}

// Boxes resting on the ground (sleeping off, so their contacts stay reported) touch it at y = 0
// with normals up, from the ground (created first: bodyA) to the box.
TEST_P(DebugDrawTest, RestingContactsLieOnTheGroundWithNormalsUp) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    const DrawnScene scene = build(world, false);
    while (world.time() < 1.5) world.step();  // a 1 cm drop is over within 0.1 s
    RecordingDrawer drawer;
    DebugDrawOptions o;
    o.shapes = o.joints = false;
    o.contacts = true;
    o.contactNormalLength = 0.3;
    world.debugDraw(drawer, o);
    // A point lies on one of the two surfaces, which overlap by no more than the solver lets them
    // (linearSlop, 5 mm) plus a skin some engines keep around shapes (Box2D's 2.5 mm): 2 slops.
    const double tolerance = 2.0 * world.settings().linearSlop;
    double highest = 0.0;
    for (const Body& box : scene.boxes) {
        int points = 0;
        double impulse = 0.0;
        bool impulses = false;
        for (const DebugContact& c : drawer.contacts) {
            if (!(c.bodyB == box.id())) continue;
            ++points;
            EXPECT_EQ(c.bodyA, scene.ground.id());
            highest = std::max(highest, std::abs(c.point.y()));
            EXPECT_LT(std::abs(c.point.y()), tolerance) << "contact point off the ground";
            // Unit and up, to float precision (Box2D's normals are floats).
            EXPECT_LT((c.normal - Vec3::UnitY()).norm(), 1e-5);
            EXPECT_LT((c.normalEnd - (c.point + 0.3 * c.normal)).norm(), 1e-12);
            EXPECT_LT(c.depth, tolerance);
            impulse += c.normalImpulse;
            impulses = c.hasImpulse;
        }
        EXPECT_GE(points, 1) << box.name() << " drew no contact with the ground";
        if (impulses) {
            // At rest the ground carries the box's weight: m g dt per step. 10 %: a resting box's
            // impulse varies by the solver's residual from step to step, far less than that.
            const double weight = box.massProperties().mass * kG * world.settings().timeStep;
            report(backend() + " " + box.name() + " contact impulse / (m g dt)", impulse / weight);
            EXPECT_NEAR(impulse, weight, 0.1 * weight);
        }
    }
    report(backend() + " highest resting contact point |y|", highest, "m");
    for (const DebugContact& c : drawer.contacts) EXPECT_FALSE(c.bodyA == scene.ball.id() || c.bodyB == scene.ball.id());
}

// The hinge's frames: A's is the world frame at the anchor, B's follows the ball and stays on it
// as far as the joint holds; the limits come in A's frame.
TEST_P(DebugDrawTest, JointFramesMeetAtTheAnchor) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    ANYPHYS_REQUIRE(hasHinge(), "joint type hinge");
    World world(settings());
    DrawnScene scene = build(world, false);
    scene.ball.applyLinearImpulse(Vec3(5, 0, 0));  // 0.15 m/s: a swing of 0.05 rad, within the limits
    while (world.time() < 1.0) world.step();
    RecordingDrawer drawer;
    DebugDrawOptions o;
    o.shapes = false;
    world.debugDraw(drawer, o);
    ASSERT_EQ(drawer.joints.size(), 1u);
    const auto& drawn = drawer.joints[0];
    EXPECT_EQ(drawn.joint, scene.hinge.id());
    EXPECT_EQ(drawn.type, JointType::Hinge);
    EXPECT_LT((drawn.frameA.position - kHingeAnchor).norm(), 1e-12) << "A is the world: its frame stays put";
    EXPECT_LT((drawn.frameA.orientation * Vec3::UnitX() - Vec3::UnitZ()).norm(), 1e-12) << "X along the hinge axis";
    // The joint's gap: how far the engine lets B's anchor drift from A's under a swinging 33 kg
    // ball. A joint holds its anchor as contacts hold a resting box, to within linearSlop (5 mm);
    // measured 7e-8 m (box2d) to 2e-5 m (native). 1 mm is far below the 1 m arm: a frame placed
    // from the wrong pose (the centre of mass, or not turned with B) misses by decimetres.
    const double gap = (drawn.frameB.position - drawn.frameA.position).norm();
    report(backend() + " hinge frame gap", gap, "m");
    EXPECT_LT(gap, 1e-3);
    // B's frame turned about the hinge axis only: its X stays on A's, its Y turned by the angle.
    const Vec3 xB = drawn.frameB.orientation * Vec3::UnitX();
    EXPECT_LT((xB - Vec3::UnitZ()).norm(), 0.01);
    // B's Y turned from A's about the axis by the hinge angle the joint reports.
    const Vec3 xA = drawn.frameA.orientation * Vec3::UnitX();
    const Vec3 yA = drawn.frameA.orientation * Vec3::UnitY(), yB = drawn.frameB.orientation * Vec3::UnitY();
    const double angle = std::atan2(yA.cross(yB).dot(xA), yA.dot(yB));
    report(backend() + " hinge angle drawn - reported", angle - scene.hinge.position(), "rad");
    EXPECT_NEAR(angle, scene.hinge.position(), 0.01);
    if (hasHingeLimits()) {
        ASSERT_EQ(drawer.limits.size(), 1u);
        const DebugJointLimit& limit = drawer.limits[0].limit;
        EXPECT_EQ(drawer.limits[0].joint, scene.hinge.id());
        EXPECT_EQ(limit.kind, DebugJointLimit::Kind::Angle);
        EXPECT_EQ(limit.lower, -kHingeLimit);
        EXPECT_EQ(limit.upper, kHingeLimit);
        EXPECT_LT((limit.frame.position - drawn.frameA.position).norm(), 1e-12);
    } else {
        EXPECT_TRUE(drawer.limits.empty());
    }
}

// Each shape's bounds hold it and are tight: a box's corners reach every face, a sphere is its
// centre plus or minus the radius. The plane has none.
TEST_P(DebugDrawTest, BoundsHoldEachShape) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    DrawnScene scene = build(world, false);
    scene.boxes[0].setAngularVelocity(Vec3(0, 0, 3));  // a turned box: bounds larger than its sizes
    for (int i = 0; i < 20; ++i) world.step();
    RecordingDrawer drawer;
    DebugDrawOptions o;
    o.bounds = true;
    world.debugDraw(drawer, o);
    ASSERT_EQ(drawer.bounds.size(), drawer.shapes.size() - 1) << "every shape but the plane";
    std::size_t k = 0;
    for (const auto& shape : drawer.shapes) {
        if (shape.shape.type == ShapeType::Plane) continue;
        const auto& box = drawer.bounds[k++];
        EXPECT_EQ(box.body, shape.body);
        if (shape.shape.type == ShapeType::Sphere) {
            EXPECT_LT((box.min - (shape.pose.position - Vec3::Constant(kBallRadius))).norm(), 1e-12);
            EXPECT_LT((box.max - (shape.pose.position + Vec3::Constant(kBallRadius))).norm(), 1e-12);
            continue;
        }
        Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
        for (const Vec3& c : corners(shape.shape.halfExtents, shape.pose)) {
            lo = lo.cwiseMin(c);
            hi = hi.cwiseMax(c);
        }
        EXPECT_LT((box.min - lo).norm(), 1e-12);
        EXPECT_LT((box.max - hi).norm(), 1e-12);
    }
}

// Bodies at rest fall asleep (sleeping on) and are drawn asleep, in the sleeping colour.
TEST_P(DebugDrawTest, SleepingBodiesAreDrawnAsleep) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    ANYPHYS_REQUIRE(caps().effects.has(Effect::Sleeping), "effect sleeping");
    World world(settings());
    const DrawnScene scene = build(world, true);
    const auto boxesAsleep = [&scene] {
        return std::none_of(scene.boxes.begin(), scene.boxes.end(), [](const Body& b) { return b.isAwake(); });
    };
    // The drop settles in 0.1 s, then timeToSleep (0.5 s): 5 s is eight times that.
    while (world.time() < 5.0 && !boxesAsleep()) world.step();
    ASSERT_TRUE(boxesAsleep()) << "precondition: resting boxes sleep within 5 s";
    RecordingDrawer drawer;
    world.debugDraw(drawer);
    const DebugPalette palette;
    int asleep = 0;
    for (const auto& drawn : drawer.shapes) {
        const Body body = world.body(drawn.body);
        EXPECT_EQ(drawn.awake, body.type() != BodyType::Static && body.isAwake());
        if (body.type() == BodyType::Dynamic && !drawn.awake) {
            ++asleep;
            EXPECT_EQ(drawn.color, palette.sleepingBody);
        }
    }
    EXPECT_GE(asleep, 3);
}

// Each kind switched off draws nothing of its kind, and only that kind goes.
TEST_P(DebugDrawTest, EachOptionOffDrawsNothingOfItsKind) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    build(world, false);
    while (world.time() < 0.5) world.step();
    RecordingDrawer all;
    world.debugDraw(all, everything());
    EXPECT_GT(all.shapes.size(), 0u);
    EXPECT_GT(all.contacts.size(), 0u);
    EXPECT_GT(all.bounds.size(), 0u);
    if (hasHinge()) {
        EXPECT_EQ(all.joints.size(), 1u);
    }
    if (hasHingeLimits()) {
        EXPECT_EQ(all.limits.size(), 1u);
    }

    const auto without = [&](bool DebugDrawOptions::*kind) {
        DebugDrawOptions o = everything();
        o.*kind = false;
        RecordingDrawer d;
        world.debugDraw(d, o);
        return d;
    };
    const RecordingDrawer noShapes = without(&DebugDrawOptions::shapes);
    EXPECT_EQ(noShapes.shapes.size(), 0u);
    EXPECT_EQ(noShapes.bounds.size(), all.bounds.size()) << "bounds do not need shapes";
    const RecordingDrawer noContacts = without(&DebugDrawOptions::contacts);
    EXPECT_EQ(noContacts.contacts.size(), 0u);
    EXPECT_EQ(noContacts.shapes.size(), all.shapes.size());
    const RecordingDrawer noJoints = without(&DebugDrawOptions::joints);
    EXPECT_EQ(noJoints.joints.size(), 0u);
    EXPECT_EQ(noJoints.limits.size(), 0u) << "limits belong to the joints drawn";
    const RecordingDrawer noLimits = without(&DebugDrawOptions::jointLimits);
    EXPECT_EQ(noLimits.limits.size(), 0u);
    EXPECT_EQ(noLimits.joints.size(), all.joints.size());
    const RecordingDrawer noBounds = without(&DebugDrawOptions::bounds);
    EXPECT_EQ(noBounds.bounds.size(), 0u);
    EXPECT_EQ(noBounds.contacts.size(), all.contacts.size());
}

// A destroyed body is not drawn, nor its joint, nor the last step's contacts it had.
TEST_P(DebugDrawTest, DestroyedBodiesAreNotDrawn) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    const DrawnScene scene = build(world, false);
    while (world.time() < 0.5) world.step();
    const BodyId box = scene.boxes[1].id(), ball = scene.ball.id();
    world.destroyBody(scene.boxes[1]);
    world.destroyBody(scene.ball);  // and its hinge with it
    RecordingDrawer drawer;
    world.debugDraw(drawer, everything());
    EXPECT_EQ(drawer.shapes.size(), world.bodyCount());
    for (const auto& s : drawer.shapes) EXPECT_FALSE(s.body == box || s.body == ball);
    for (const auto& b : drawer.bounds) EXPECT_FALSE(b.body == box || b.body == ball);
    for (const DebugContact& c : drawer.contacts) EXPECT_FALSE(c.bodyA == box || c.bodyB == box);
    EXPECT_GT(drawer.contacts.size(), 0u) << "the other boxes' contacts are still drawn";
    EXPECT_TRUE(drawer.joints.empty());
    EXPECT_TRUE(drawer.limits.empty());
}

// Bad options are refused naming the field, the value and the rule; nothing is drawn.
TEST_P(DebugDrawTest, BadOptionsAreRefused) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    build(world, false);
    const auto refused = [&](const DebugDrawOptions& o, const std::string& field) {
        RecordingDrawer drawer;
        try {
            world.debugDraw(drawer, o);
            ADD_FAILURE() << field << ": accepted";
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(field), std::string::npos) << message;
            EXPECT_NE(message.find("got"), std::string::npos) << message;
        }
        EXPECT_EQ(drawer.total(), 0u);
    };
    DebugDrawOptions o;
    o.contactNormalLength = -1.0;
    refused(o, "DebugDrawOptions.contactNormalLength: must be >= 0 and finite (m), got -1");
    o.contactNormalLength = std::nan("");
    refused(o, "DebugDrawOptions.contactNormalLength");
    o = {};
    o.palette.sleepingBody.g = 1.5f;
    refused(o, "DebugDrawOptions.palette.sleepingBody.g: must be in [0, 1], got 1.5");
}

// A drawer may read the world but not change it: a body created from a callback is refused, the
// world keeps its bodies, and the next draw works.
TEST_P(DebugDrawTest, DrawerMayNotChangeTheWorld) {
    ANYPHYS_REQUIRE(missing().empty(), missing());
    World world(settings());
    build(world, false);
    struct Meddler : RecordingDrawer {
        World* world = nullptr;
        void drawShape(BodyId body, const ShapeDef& shape, const Transform& pose, DebugColor color, bool awake) override {
            RecordingDrawer::drawShape(body, shape, pose, color, awake);
            world->step();
        }
    } meddler;
    meddler.world = &world;
    const std::size_t before = world.bodyCount();
    try {
        world.debugDraw(meddler);
        ADD_FAILURE() << "a step from inside debugDraw was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("World.step: not allowed inside World::debugDraw"), std::string::npos) << e.what();
    }
    EXPECT_EQ(world.bodyCount(), before);
    EXPECT_EQ(world.stepCount(), 0u);
    RecordingDrawer drawer;
    world.debugDraw(drawer);
    EXPECT_EQ(drawer.shapes.size(), before);
}

ANYPHYS_CONTRACT_SUITE(DebugDrawTest);

}  // namespace
}  // namespace anyphys::test
