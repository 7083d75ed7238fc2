// Ray casts (closest and all hits) and shape overlap against the world. Geometry is exact, so
// positions and distances are checked to 1e-6 m (rounding only); membership exactly.
#include <algorithm>
#include <numbers>

#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

constexpr double kExact = 1e-6;  // m: closed-form ray / box intersections, only rounding remains

class QueriesTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
    // Ground y = 0 and three static unit boxes centred at x = 2, 4, 6 (y = 0.5); box "b2" is on
    // layer 2, the others on layer 1; a sensor box at x = 1 that queries must ignore.
    void build(World& world) {
        world.createBody(groundDef());
        for (int i = 0; i < 3; ++i) {
            BodyDef def = boxDef("b" + std::to_string(i + 1), Vec3(0.5, 0.5, 0.5), Vec3(2.0 * (i + 1), 0.5, 0));
            def.type = BodyType::Static;
            def.layer = i == 1 ? 2u : 1u;
            boxes.push_back(world.createBody(def));
        }
        BodyDef sensor = boxDef("sensor", Vec3(0.25, 0.25, 0.25), Vec3(1, 0.5, 0));
        sensor.type = BodyType::Static;
        sensor.isTrigger = true;
        world.createBody(sensor);
    }
    bool has(const char* query) const { return caps().queries.contains(query); }
    std::vector<Body> boxes;
};

TEST_P(QueriesTest, RaycastReturnsTheClosestHit) {
    ANYPHYS_REQUIRE(has("raycast") && caps().shapes.contains(ShapeType::Box), "query raycast on boxes");
    World world(settings());
    build(world);
    const auto hit = world.raycast(Vec3(0, 0.5, 0), Vec3(1, 0, 0), 10.0);
    ASSERT_TRUE(hit.has_value());
    EXPECT_TRUE(hit->body == boxes[0]) << "hit " << hit->body.name();  // the sensor at x = 1 is skipped
    EXPECT_NEAR(hit->distance, 1.5, kExact);
    EXPECT_NEAR((hit->point - Vec3(1.5, 0.5, 0)).norm(), 0, kExact);
    EXPECT_NEAR((hit->normal - Vec3(-1, 0, 0)).norm(), 0, kExact);

    // maxDistance stops short of the first box; a ray pointing away hits nothing.
    EXPECT_FALSE(world.raycast(Vec3(0, 0.5, 0), Vec3(1, 0, 0), 1.4).has_value());
    EXPECT_FALSE(world.raycast(Vec3(0, 0.5, 0), Vec3(-1, 0, 0), 10.0).has_value());

    // Straight down onto the ground plane; distance is in metres even for a non-unit direction.
    const auto down = world.raycast(Vec3(-3, 5, 0), Vec3(0, -2, 0), 10.0);
    ASSERT_TRUE(down.has_value());
    EXPECT_EQ(down->body.name(), "ground");
    EXPECT_NEAR(down->distance, 5.0, kExact);
    EXPECT_NEAR((down->normal - Vec3(0, 1, 0)).norm(), 0, kExact);
}

TEST_P(QueriesTest, RaycastAllReturnsEveryHitNearestFirst) {
    ANYPHYS_REQUIRE(has("raycast") && caps().shapes.contains(ShapeType::Box), "query raycast on boxes");
    World world(settings());
    build(world);
    const std::vector<RayHit> hits = world.raycastAll(Vec3(0, 0.5, 0), Vec3(1, 0, 0), 10.0);
    ASSERT_EQ(hits.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_TRUE(hits[i].body == boxes[i]) << "hit " << i << " is " << hits[i].body.name();
        EXPECT_NEAR(hits[i].distance, 1.5 + 2.0 * i, kExact);
    }
    // maxDistance 4 m includes the entry into the second box (3.5 m) only.
    EXPECT_EQ(world.raycastAll(Vec3(0, 0.5, 0), Vec3(1, 0, 0), 4.0).size(), 2u);
    // The layer mask skips b2 (layer 2).
    const std::vector<RayHit> layer1 = world.raycastAll(Vec3(0, 0.5, 0), Vec3(1, 0, 0), 10.0, 1u);
    ASSERT_EQ(layer1.size(), 2u);
    EXPECT_TRUE(layer1[0].body == boxes[0] && layer1[1].body == boxes[2]);
    const auto closestOnLayer2 = world.raycast(Vec3(0, 0.5, 0), Vec3(1, 0, 0), 10.0, 2u);
    ASSERT_TRUE(closestOnLayer2.has_value());
    EXPECT_TRUE(closestOnLayer2->body == boxes[1]);
    EXPECT_NEAR(closestOnLayer2->distance, 3.5, kExact);
}

// "At most one hit per shape": a ray down onto the ground plane hits it once, wherever it falls
// (near the origin, 2 km out where Box2D's run of edges joins two, 3 000 km out), straight down
// or slanted. Bullet's plane is two triangles meeting under the ray, and both answered: 2 hits.
TEST_P(QueriesTest, RaycastAllHitsAPlaneOnce) {
    ANYPHYS_REQUIRE(has("raycast") && caps().shapes.contains(ShapeType::Plane), "query raycast on planes");
    World world(settings());
    world.createBody(groundDef());
    const double zs[] = {0.0, 0.7};
    for (const double x : {0.0, 3.3, 2000.0, -3e6})
        for (const double z : zs) {
            const Vec3 from(x, 10, planarWorld() ? 0.0 : z);
            for (const Vec3& dir : {Vec3(0, -1, 0), Vec3(0.6, -0.8, 0)}) {
                const std::vector<RayHit> hits = world.raycastAll(from, dir, 20.0);
                ASSERT_EQ(hits.size(), 1u) << "ray from " << from.transpose() << " along " << dir.transpose();
                // 10 m straight down, 12.5 m along the slant; a float engine rounds 3e6 m to 0.25 m
                // along the plane, which moves neither distance.
                EXPECT_NEAR(hits[0].distance, 10.0 / -dir.y(), 1e-4) << "ray from " << from.transpose();
            }
        }
}

std::vector<std::string> names(const std::vector<Body>& bodies) {
    std::vector<std::string> out;
    for (const Body& b : bodies) out.push_back(b.name());
    std::sort(out.begin(), out.end());
    return out;
}

TEST_P(QueriesTest, OverlapFindsTheBodiesAShapeTouches) {
    ANYPHYS_REQUIRE(has("overlap") && caps().shapes.contains(ShapeType::Box), "query overlap on boxes");
    World world(settings());
    build(world);
    using Names = std::vector<std::string>;
    // A sphere beside b1 (above it in a planar world) reaching 0.1 m into it, clear of the ground.
    const Vec3 beside = planarWorld() ? Vec3(2, 1.5, 0) : Vec3(2, 1.0, 1.0);
    EXPECT_EQ(names(world.overlap(ShapeDef::sphere(0.6), Transform{beside, Quat::Identity()})), Names{"b1"});
    // A sphere 0.1 m short of b1 touches nothing.
    EXPECT_TRUE(world.overlap(ShapeDef::sphere(0.4), Transform{beside, Quat::Identity()}).empty());
    // A long box along the row covers b1..b3 and dips into the ground; the sensor is skipped.
    EXPECT_EQ(names(world.overlap(ShapeDef::box(Vec3(4, 0.5, 0.5)), Transform{Vec3(4, 0.4, 0), Quat::Identity()})),
              (Names{"b1", "b2", "b3", "ground"}));
    // The same box filtered to layer 2 finds b2 only.
    EXPECT_EQ(names(world.overlap(ShapeDef::box(Vec3(4, 0.5, 0.5)), Transform{Vec3(4, 0.6, 0), Quat::Identity()}, 2u)),
              Names{"b2"});
    // The pose's rotation counts: a box centred at x = 0.85 reaches x = 1.35, short of b1's face at
    // 1.5; turned 45 deg about y its corner reaches 0.85 + 0.5 sqrt(2) = 1.557, 5.7 cm into b1. In
    // a planar world the turn is about z, so the box is a cube held at y = 0.75, whose turned
    // corners (0.71 from its centre) stay clear of the ground.
    const bool planar = planarWorld();
    const ShapeDef plate = ShapeDef::box(planar ? Vec3(0.5, 0.5, 0.5) : Vec3(0.5, 0.2, 0.5));
    const Quat turn(Eigen::AngleAxisd(std::numbers::pi / 4, planar ? Vec3::UnitZ() : Vec3::UnitY()));
    const Vec3 at(0.85, planar ? 0.75 : 0.5, 0);
    EXPECT_TRUE(world.overlap(plate, Transform{at, Quat::Identity()}).empty());
    EXPECT_EQ(names(world.overlap(plate, Transform{at, turn})), Names{"b1"});
    // The ground is solid below its surface: a shape wholly under it overlaps it, however deep.
    // (Box2D's overlap found a plane only through its edges' bounding boxes, a box 5 m down none.)
    for (const double depth : {0.5, 5.0, 500.0}) {
        SCOPED_TRACE("box centred " + std::to_string(depth) + " m under the ground");
        EXPECT_EQ(names(world.overlap(ShapeDef::box(Vec3(0.1, 0.1, 0.1)), Transform{Vec3(-3, -depth, 0), Quat::Identity()})),
                  Names{"ground"});
    }
}

// A ray does not hit a shape whose solid holds its origin (below a plane included), on every
// backend, as Box2D's and Unity's rays do; it goes on to hit what lies beyond. ODE reported where
// the ray left a box, sphere, capsule or hull, and ODE, Bullet and Box2D hit a plane from below.
// (A ray starting exactly on a surface: the next case.) The counts also
// hold Box2D's capsule, three fixtures, to one hit: it gave one per piece the ray crossed.
TEST_P(QueriesTest, RaycastIgnoresAShapeItStartsInside) {
    ANYPHYS_REQUIRE(has("raycast"), "query raycast");
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Sphere, ShapeType::Capsule, ShapeType::Plane}, Effects{});
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const bool hulls = caps().shapes.contains(ShapeType::Convex);
    World world(settings());
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::plane(Vec3(0, 1, 0), 0.0);
    world.createBody(ground);
    // A row along +X at y = 5, each 2 m across, centres 10 m apart.
    std::vector<ShapeDef> shapes{ShapeDef::box(Vec3(1, 1, 1)), ShapeDef::sphere(1.0), ShapeDef::capsule(1.0, 0.5)};
    if (hulls) {
        std::vector<Vec3> corners;
        for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        shapes.push_back(ShapeDef::convex(corners));
    }
    std::vector<Body> row;
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        BodyDef def;
        def.type = BodyType::Static;
        def.shape = shapes[i];
        def.position = Vec3(10.0 * static_cast<double>(i + 1), 5, 0);
        def.name = "shape" + std::to_string(i);
        row.push_back(world.createBody(def));
    }
    for (std::size_t i = 0; i < row.size(); ++i) {
        SCOPED_TRACE("from inside " + row[i].name());
        // From a point inside, off the centre, along +X: the next shapes, 10 m apart, not this one.
        const Vec3 origin = row[i].position() + Vec3(0.3, 0.2, 0);
        const std::vector<RayHit> hits = world.raycastAll(origin, Vec3(1, 0, 0), 100.0);
        ASSERT_EQ(hits.size(), row.size() - 1 - i);
        for (std::size_t k = 0; k < hits.size(); ++k) {
            EXPECT_TRUE(hits[k].body == row[i + 1 + k]) << "hit " << hits[k].body.name();
            EXPECT_GT(hits[k].distance, 8.0);  // at least the next shape's near side
        }
        const auto closest = world.raycast(origin, Vec3(1, 0, 0), 100.0);
        EXPECT_EQ(closest.has_value(), i + 1 < row.size());
        if (closest) {
            EXPECT_TRUE(closest->body == row[i + 1]) << "hit " << closest->body.name();
        }
        // Backwards, out through the near side: the shapes before it, nearest first.
        EXPECT_EQ(world.raycastAll(origin, Vec3(-1, 0, 0), 100.0).size(), i);
    }
    // Under the ground, up or down: nothing (the sky above x = -3 is empty).
    for (const Vec3& direction : {Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0.6, 0.8, 0)}) {
        SCOPED_TRACE("from under the ground along " + ::testing::PrintToString(direction.transpose()));
        EXPECT_TRUE(world.raycastAll(Vec3(-3, -1, 0), direction, 100.0).empty());
    }
}

// A ray that starts exactly on a surface meets it at distance 0 heading in, and does not meet it
// heading out (the solid then holds the ray's start, as in the case above), on every backend and
// every shape. Before, each engine had its own answer: ODE and Box2D hit both ways (Box2D at
// -0.000 m), Bullet neither, native only heading in; the layer now starts each ray a hair behind
// its origin (World::raycast). Points on the surfaces are exact in float and double; the distance
// and point are checked to 1e-5 m, four float roundings of coordinates up to 41 m (Box2D solves
// in float).
TEST_P(QueriesTest, RayStartingOnASurfaceMeetsItOnlyHeadingIn) {
    ANYPHYS_REQUIRE(has("raycast"), "query raycast");
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Sphere, ShapeType::Capsule, ShapeType::Plane}, Effects{});
    ANYPHYS_REQUIRE(missing.empty(), missing);
    World world(settings());
    BodyDef groundDef;
    groundDef.type = BodyType::Static;
    groundDef.shape = ShapeDef::plane(Vec3(0, 1, 0), 0.0);
    groundDef.name = "ground";
    const Body ground = world.createBody(groundDef);
    struct OnSurface {
        Body body;
        Vec3 point, outward;  // on the surface; its outward normal there
    };
    std::vector<OnSurface> cases{{ground, Vec3(-3, 0, 0), Vec3(0, 1, 0)}};
    const auto add = [&](const char* name, const ShapeDef& shape, const Vec3& centre, std::vector<std::pair<Vec3, Vec3>> points) {
        BodyDef def;
        def.type = BodyType::Static;
        def.shape = shape;
        def.position = centre;
        def.name = name;
        const Body body = world.createBody(def);
        for (const auto& [offset, outward] : points) cases.push_back({body, centre + offset, outward});
    };
    // Centres 10 m apart along +X at y = 5, each 2 m across: a ray along X from one meets the next.
    add("box", ShapeDef::box(Vec3(1, 1, 1)), Vec3(10, 5, 0), {{Vec3(-1, 0.25, 0), Vec3(-1, 0, 0)}, {Vec3(0.5, 1, 0), Vec3(0, 1, 0)}});
    add("sphere", ShapeDef::sphere(1.0), Vec3(20, 5, 0), {{Vec3(-1, 0, 0), Vec3(-1, 0, 0)}, {Vec3(0, 1, 0), Vec3(0, 1, 0)}});
    add("capsule", ShapeDef::capsule(1.0, 0.5), Vec3(30, 5, 0), {{Vec3(-1, 0.25, 0), Vec3(-1, 0, 0)}, {Vec3(0, 1.5, 0), Vec3(0, 1, 0)}});
    if (caps().shapes.contains(ShapeType::Convex)) {
        std::vector<Vec3> corners;
        for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        add("hull", ShapeDef::convex(corners), Vec3(40, 5, 0), {{Vec3(-1, 0.25, 0), Vec3(-1, 0, 0)}, {Vec3(0.5, 1, 0), Vec3(0, 1, 0)}});
    }
    for (const OnSurface& c : cases) {
        SCOPED_TRACE(c.body.name() + " at " + ::testing::PrintToString(c.point.transpose()));
        // Heading in, straight or slanted (in the XY plane, for planar worlds): the surface itself, at distance 0.
        const Vec3 along(-c.outward.y(), c.outward.x(), 0.0);
        for (const Vec3& in : {Vec3(-c.outward), Vec3(-c.outward + 0.3 * along)}) {
            const auto hit = world.raycast(c.point, in, 100.0);
            ASSERT_TRUE(hit.has_value()) << "heading " << in.transpose();
            EXPECT_TRUE(hit->body == c.body) << "heading " << in.transpose() << ": hit " << hit->body.name();
            EXPECT_LE(hit->distance, 1e-5) << "heading " << in.transpose();
            EXPECT_GE(hit->distance, 0.0) << "heading " << in.transpose();
            EXPECT_LT((hit->point - c.point).norm(), 1e-5) << "heading " << in.transpose();
            EXPECT_GT(hit->normal.dot(c.outward), 0.99) << "heading " << in.transpose();
        }
        // Heading out: not this shape (another may lie ahead, metres away).
        for (const RayHit& hit : world.raycastAll(c.point, c.outward, 100.0)) {
            EXPECT_FALSE(hit.body == c.body) << "heading out, hit at " << hit.distance << " m";
            EXPECT_GT(hit.distance, 1.0);
        }
    }
    // A mesh is a sheet with no solid, met from either side: from on it, either way at distance 0,
    // its normal facing the ray. In a world of its own (ODE collides no hull with a mesh).
    if (!caps().shapes.contains(ShapeType::Mesh)) return;
    World sheetWorld(settings());
    BodyDef sheet;
    sheet.type = BodyType::Static;
    sheet.name = "sheet";
    const double depth = planarWorld() ? 1.0 : 5.0;  // a planar world's bodies span z = 0
    sheet.shape = ShapeDef::mesh({Vec3(-5, 0, -depth), Vec3(5, 0, -depth), Vec3(5, 0, depth), Vec3(-5, 0, depth)}, {0, 2, 1, 0, 3, 2});
    sheet.position = Vec3(60, 5, 0);
    const Body mesh = sheetWorld.createBody(sheet);
    for (const double up : {1.0, -1.0}) {
        SCOPED_TRACE("from on the sheet, heading " + std::string(up > 0 ? "up" : "down"));
        const auto hit = sheetWorld.raycast(Vec3(60.5, 5, 0), Vec3(0, up, 0), 100.0);
        ASSERT_TRUE(hit.has_value());
        EXPECT_TRUE(hit->body == mesh) << "hit " << hit->body.name();
        EXPECT_LE(hit->distance, 1e-5);
        EXPECT_LT(hit->normal.y() * up, -0.99);
    }
}

// A ray meets a sphere and a capsule (side and end cap) where the closed form says, at radii from
// 1 cm to 10 m: to rounding, on every backend. Bullet's convex cast hit capsules up to 7.8 mm late
// (3.7 mm on a 1 cm one) and turned a sphere's normal by up to 3.5e-4; its sphere and capsule hits
// are now solved in closed form.
TEST_P(QueriesTest, RaycastHitsRoundShapesWhereTheyAre) {
    ANYPHYS_REQUIRE(has("raycast"), "query raycast");
    const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Capsule}, Effects{});
    ANYPHYS_REQUIRE(missing.empty(), missing);
    for (const double r : {0.01, 1.0, 10.0}) {
        SCOPED_TRACE("radius " + std::to_string(r) + " m");
        World world(settings());
        BodyDef sphere;
        sphere.type = BodyType::Static;
        sphere.shape = ShapeDef::sphere(r);
        sphere.name = "sphere";
        world.createBody(sphere);
        BodyDef capsule = sphere;
        capsule.shape = ShapeDef::capsule(r, r);  // along Y, end caps centred r above and below
        capsule.position = Vec3(0, 50 * r, 0);
        capsule.name = "capsule";
        world.createBody(capsule);
        struct Case {
            const char* what;
            double height;   // of the ray, along +X from x = -20 r
            double distance; // closed form
            Vec3 normal;
        };
        const double capY = 0.5 * r, capX = std::sqrt(r * r - capY * capY);
        const Case cases[] = {
            {"sphere", 0.3 * r, 20 * r - std::sqrt(0.91) * r, Vec3(-std::sqrt(0.91), 0.3, 0)},
            {"capsule", 50 * r + 0.3 * r, 19 * r, Vec3(-1, 0, 0)},                       // its side
            {"capsule", 50 * r + r + capY, 20 * r - capX, Vec3(-capX / r, capY / r, 0)},  // its top cap
        };
        for (const Case& c : cases) {
            const auto hit = world.raycast(Vec3(-20 * r, c.height, 0), Vec3(1, 0, 0), 100 * r);
            ASSERT_TRUE(hit.has_value()) << c.what << " at height " << c.height;
            EXPECT_EQ(hit->body.name(), c.what);
            // Closed form, so only rounding: of coordinates of 20 r (floats on Box2D), a few dozen roundings.
            const double tolerance = 1e-9 + rounding(20 * r, 32);
            EXPECT_NEAR(hit->distance, c.distance, tolerance) << c.what << " at height " << c.height;
            // The normal from a hit point of coordinates near 20 r, over r: rounding of 20.
            EXPECT_NEAR((hit->normal - c.normal).norm(), 0.0, 1e-9 + rounding(20.0, 32)) << c.what << " normal";
        }
    }
}

// raycastAll answers once per shape, and a compound's children are shapes: a ray along a
// compound of a box, a sphere and a capsule hits each child, and from inside one the others.
// (ODE answered once per body: its nearest child alone.)
TEST_P(QueriesTest, RaycastAllHitsEachOfACompoundsShapes) {
    ANYPHYS_REQUIRE(has("raycast"), "query raycast");
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Sphere, ShapeType::Capsule, ShapeType::Compound}, Effects{});
    ANYPHYS_REQUIRE(missing.empty(), missing);
    World world(settings());
    ShapeDef box = ShapeDef::box(Vec3(0.5, 0.5, 0.5)), ball = ShapeDef::sphere(0.5), capsule = ShapeDef::capsule(0.25, 0.5);
    box.position = Vec3(-1, 0, 0);     // x from 8.5 to 9.5 in the world
    ball.position = Vec3(1, 0, 0);     // centre at x = 11
    capsule.position = Vec3(3, 0, 0);  // along Y, x from 12.75 to 13.25
    BodyDef def;
    def.type = BodyType::Static;
    def.shape = ShapeDef::compound({box, ball, capsule});
    def.position = Vec3(10, 0, 0);
    const Body body = world.createBody(def);
    const double ballEntry = 11.0 - std::sqrt(0.25 - 0.01);  // the ray runs 0.1 m off the ball's centre
    const struct {
        double from;
        std::vector<double> distances;
    } cases[] = {{0.0, {8.5, ballEntry, 12.75}}, {9.0, {ballEntry - 9.0, 12.75 - 9.0}}, {11.0, {12.75 - 11.0}}};
    for (const auto& c : cases) {
        SCOPED_TRACE("from x = " + std::to_string(c.from));
        const std::vector<RayHit> hits = world.raycastAll(Vec3(c.from, 0.1, 0), Vec3(1, 0, 0), 100.0);
        ASSERT_EQ(hits.size(), c.distances.size());
        for (std::size_t k = 0; k < hits.size(); ++k) {
            EXPECT_TRUE(hits[k].body == body);
            EXPECT_NEAR(hits[k].distance, c.distances[k], kExact + rounding(13.0, 32));
        }
    }
}

// A cube balanced on a corner over a box's top face: the shallowest depth of the corner in the face
// at which World::overlap reports the box (bisection to 0.1 um). The exact answer is 0.
double cornerOverlapDepth(World& world, bool planar) {
    // In a planar world the corner turns down about Z; in 3D the cube's diagonal points down.
    const Quat turn = planar ? Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()))
                             : Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3(0, -1, 0));
    const double reach = 0.5 * (planar ? std::sqrt(2.0) : std::sqrt(3.0));  // centre to corner
    double seen = 0.1, missed = -1e-3;  // m into the face
    EXPECT_TRUE(world.overlap(ShapeDef::box(Vec3(0.5, 0.5, 0.5)), Transform{Vec3(0, reach - missed, 0), turn}).empty())
        << "a corner 1 mm above the face";
    while (seen - missed > 1e-7) {
        const double depth = 0.5 * (seen + missed);
        const bool found = !world.overlap(ShapeDef::box(Vec3(0.5, 0.5, 0.5)), Transform{Vec3(0, reach - depth, 0), turn}).empty();
        (found ? seen : missed) = depth;
    }
    return seen;
}

// A shape overlaps a body as soon as it reaches into it: a cube's corner 0.1 mm into a box's face is
// found (criterion queries.overlap_corner, within 1 mm), and 1 mm above it is not.
TEST_P(QueriesTest, OverlapFindsACornerJustInsideAFace) {
    ANYPHYS_REQUIRE(has("overlap") && caps().shapes.contains(ShapeType::Box), "query overlap on boxes");
    World world(settings());
    BodyDef box;
    box.type = BodyType::Static;
    box.shape = ShapeDef::box(Vec3(2, 1, 2));
    box.position = Vec3(0, -1, 0);  // top face at y = 0
    world.createBody(box);
    const double depth = cornerOverlapDepth(world, planarWorld());
    report(backend() + " cube corner into a box's face: overlap seen from", depth, "m");
    expectCriterion(planarWorld() ? "planar.queries.overlap_corner" : "queries.overlap_corner", depth < 1e-3,
                    "overlap seen from " + std::to_string(depth) + " m into the face (bound 0.001)", depth);
}

// Where a ray along +X from x = -5 at `height` enters a cube of half extent 1 at the origin turned
// by `angle` about Z (slabs in the cube's frame); its outward normal there. Misses: distance < 0.
std::pair<double, Vec3> rayIntoTurnedCube(double angle, double height) {
    const Mat3 r = Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
    const Vec3 o = r.transpose() * Vec3(-5, height, 0), d = r.transpose() * Vec3(1, 0, 0);
    double enter = -1e300, leave = 1e300;
    Vec3 normal = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0.0) {
            if (std::abs(o[k]) > 1.0) return {-1.0, Vec3::Zero()};
            continue;
        }
        const double t1 = (-1.0 - o[k]) / d[k], t2 = (1.0 - o[k]) / d[k];
        if (std::min(t1, t2) > enter) {
            enter = std::min(t1, t2);
            normal = Vec3::Zero();
            normal[k] = d[k] > 0 ? -1.0 : 1.0;
        }
        leave = std::min(leave, std::max(t1, t2));
    }
    if (enter > leave || enter < 0.0) return {-1.0, Vec3::Zero()};
    return {enter, r * normal};
}

// A hull of a cube's corners is hit where the same cube is, turned or not: to rounding, on every
// backend. ODE's own ray test against a hull ignored part of its turn: 17 cm early at 0.3 rad,
// 60 cm at 1 rad, and a miss 0.7 m off the centre.
TEST_P(QueriesTest, RaycastHitsATurnedHullWhereItIs) {
    ANYPHYS_REQUIRE(has("raycast"), "query raycast");
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Convex}, Effects{});
    ANYPHYS_REQUIRE(missing.empty(), missing);
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    for (const double angle : {0.0, 0.3, 1.0, 2.5})
        for (const ShapeDef& shape : {ShapeDef::convex(corners), ShapeDef::box(Vec3(1, 1, 1))}) {
            World world(settings());
            BodyDef def;
            def.type = BodyType::Static;
            def.shape = shape;
            def.orientation = Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
            world.createBody(def);
            for (const double height : {0.0, 0.2, 0.7, 1.3}) {
                SCOPED_TRACE(std::string(toString(shape.type)) + " turned " + std::to_string(angle) + " rad, ray at height " +
                             std::to_string(height));
                const auto [distance, normal] = rayIntoTurnedCube(angle, height);
                const auto hit = world.raycast(Vec3(-5, height, 0), Vec3(1, 0, 0), 10.0);
                ASSERT_EQ(hit.has_value(), distance >= 0.0);
                if (!hit) continue;
                // kExact, as for the other ray tests (Bullet's iterative cast lands within 1e-8 m on a
                // hull), plus rounding of coordinates of 5 m (floats on Box2D).
                EXPECT_NEAR(hit->distance, distance, kExact + rounding(5.0, 32));
                EXPECT_NEAR((hit->normal - normal).norm(), 0.0, kExact + rounding(5.0, 32));
            }
        }
}

ANYPHYS_CONTRACT_SUITE(QueriesTest);

// The same queries in a planar world, on every backend that has one: a query leaving the XY plane
// is refused by the layer in one wording (a 3D engine would see the bodies' depth, a planar one
// nothing), and the world still answers in-plane queries afterwards.
class PlanarQueriesTest : public QueriesTest {
protected:
    bool planarTest() const override { return true; }
};

template <class F>
void expectQueryRefused(F&& query, const std::string& field, const std::string& rule) {
    try {
        query();
        ADD_FAILURE() << "query accepted; expected a refusal of " << field;
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument) << e.what();
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(std::string(e.what()).find(rule), std::string::npos) << e.what();
    }
}

TEST_P(PlanarQueriesTest, QueriesLeavingThePlaneAreRefusedOnEveryBackend) {
    ANYPHYS_REQUIRE(has("raycast") && has("overlap") && caps().shapes.contains(ShapeType::Box), "queries raycast and overlap on boxes");
    World world(settings());
    build(world);
    const std::string inPlane = "must lie in the XY plane (z = 0) in a planar world";
    expectQueryRefused([&] { world.raycast(Vec3(0, 0.5, 0.25), Vec3(1, 0, 0), 10.0); }, "World.raycast.origin", inPlane);
    expectQueryRefused([&] { world.raycast(Vec3(0, 0.5, 0), Vec3(1, 0, 0.1), 10.0); }, "World.raycast.direction", inPlane);
    expectQueryRefused([&] { world.raycastAll(Vec3(0, 0.5, 0), Vec3(0, 0, 1), 10.0); }, "World.raycastAll.direction", inPlane);

    const ShapeDef cube = ShapeDef::box(Vec3(0.5, 0.5, 0.5));
    expectQueryRefused([&] { world.overlap(cube, Transform{Vec3(2, 0.5, 0.3), Quat::Identity()}); },
                       "World.overlap.pose.position", "must have z = 0 in a planar world");
    const Quat aboutY(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
    expectQueryRefused([&] { world.overlap(cube, Transform{Vec3(2, 0.5, 0), aboutY}); }, "World.overlap.pose.orientation",
                       "must be a rotation about Z (x = y = 0) in a planar world");
    ANYPHYS_REQUIRE(caps().shapes.contains(ShapeType::Compound), "compound shapes");
    const ShapeDef offPlane = ShapeDef::compound({ShapeDef::box(Vec3(0.5, 0.5, 0.5)).placed(Vec3(0, 0, 0.2))});
    expectQueryRefused([&] { world.overlap(offPlane, Transform{Vec3(2, 0.5, 0), Quat::Identity()}); },
                       "World.overlap.shape.shapes[0].position", "must have z = 0 in a planar world");

    // Nothing was lost: in-plane queries answer as in QueriesTest, and the world steps.
    const auto hit = world.raycast(Vec3(0, 0.5, 0), Vec3(1, 0, 0), 10.0);
    ASSERT_TRUE(hit.has_value());
    EXPECT_TRUE(hit->body == boxes[0]) << "hit " << hit->body.name();
    EXPECT_NEAR(hit->distance, 1.5, kExact);
    // A small cube inside b2's top half, well clear of the ground (y from 0.75 to 0.95).
    const auto inB2 = world.overlap(ShapeDef::box(Vec3(0.1, 0.1, 0.1)), Transform{Vec3(4, 0.85, 0), Quat::Identity()});
    ASSERT_EQ(inB2.size(), 1u);
    EXPECT_TRUE(inB2.front() == boxes[1]) << "found " << inB2.front().name();
    world.step();
}

ANYPHYS_CONTRACT_SUITE(PlanarQueriesTest);

}  // namespace
}  // namespace anyphys::test
