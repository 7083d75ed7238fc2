// The ODE backend's own hull-against-capsule collider (ode_convex_capsule.hpp), which replaces
// libccd's MPR (and, over a box's corners, ODE's box-capsule): the contacts it lists in the step they are made (a capsule lying on a face, on
// one end, sunk into a face, across an edge, beside an edge and at a corner), exact touching
// in every region both ways round, a capsule resting still on a hull, and a hull reaching 1e7 m
// that no longer hangs the step.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"
#include "ode_test_helpers.hpp"

namespace anyphys {
namespace {

/// A capsule of `radius` whose core runs from a to b, as a body definition.
BodyDef capsuleBetween(const Vec3& a, const Vec3& b, double radius) {
    BodyDef def;
    def.shape = ShapeDef::capsule(radius, 0.5 * (b - a).norm());
    def.position = 0.5 * (a + b);
    def.orientation = Quat::FromTwoVectors(Vec3::UnitY(), (b - a).normalized());  // a capsule's core lies along its y
    def.allowSleep = false;
    return def;
}

struct Expected {
    const char* name;
    Vec3 a, b;            // the capsule's core, radius 0.1
    Vec3 outward;         // out of the cube towards the capsule
    std::vector<Vec3> at;  // the contact points
    double depth;
};

// The contacts of a 0.1 m capsule against a static unit cube hull at the origin, listed by the
// first step's events: the collider's own output, before any solve moved the bodies. Each
// figure is worked out from the geometry in the case's comment.
TEST(OdeConvexCapsule, ContactsAreTheGeometrysInEveryRegion) {
    const double r = 0.1, s2 = std::sqrt(0.5), s3 = std::sqrt(1.0 / 3.0);
    const std::vector<Expected> cases{
        // Lying on the top face, its lowest line 1 cm into it: a contact under each end, at the
        // capsule's bottom (y = 0.49; the face is at y = 0.5).
        {"lying on a face", Vec3(-0.3, 0.59, 0.2), Vec3(0.3, 0.59, 0.2), Vec3::UnitY(),
         {Vec3(-0.3, 0.49, 0.2), Vec3(0.3, 0.49, 0.2)}, 0.01},
        // Past the face's edge at x = 0.5: the second contact where the core leaves the face.
        {"lying over a face's edge", Vec3(0.2, 0.59, 0), Vec3(0.8, 0.59, 0), Vec3::UnitY(),
         {Vec3(0.2, 0.49, 0), Vec3(0.5, 0.49, 0)}, 0.01},
        // Standing on one end (the other 0.3 m above): the lower end only.
        {"on one end", Vec3(0.1, 0.58, -0.1), Vec3(0.1, 0.88, -0.1), Vec3::UnitY(), {Vec3(0.1, 0.48, -0.1)}, 0.02},
        // Sunk: the core 5 cm below the top face, the shortest way out is up by 15 cm.
        {"sunk into a face", Vec3(-0.2, 0.45, 0), Vec3(0.2, 0.45, 0), Vec3::UnitY(),
         {Vec3(-0.2, 0.35, 0), Vec3(0.2, 0.35, 0)}, 0.15},
        // Across the edge x = y = 0.5, sunk: the core from (0.6, 0.3) to (0.3, 0.6) passes
        // 0.0707 m inside the edge, the faces would need 0.2 m: out along the edge's bisector.
        {"sunk across an edge", Vec3(0.6, 0.3, 0), Vec3(0.3, 0.6, 0), Vec3(s2, s2, 0),
         {0.5 * (Vec3(0.5, 0.5, 0) + Vec3(0.45, 0.45, 0) - r * Vec3(s2, s2, 0))}, r + 0.05 * std::sqrt(2.0)},
        // Beside the same edge and along it, its core 9 cm from it: one contact, the nearest.
        {"along an edge", Vec3(0.5, 0.5, -0.3) + 0.09 * Vec3(s2, s2, 0), Vec3(0.5, 0.5, 0.3) + 0.09 * Vec3(s2, s2, 0),
         Vec3(s2, s2, 0), {Vec3(0.5, 0.5, -0.3) - 0.005 * Vec3(s2, s2, 0)}, 0.01},
        // Pointing away from the corner (0.5, 0.5, 0.5), its end 9 cm from it.
        {"at a corner", Vec3(0.5, 0.5, 0.5) + 0.09 * Vec3(s3, s3, s3), Vec3(0.5, 0.5, 0.5) + 0.49 * Vec3(s3, s3, s3),
         Vec3(s3, s3, s3), {Vec3(0.5, 0.5, 0.5) - 0.005 * Vec3(s3, s3, s3)}, 0.01},
    };
    // The same cube as a box: the same collider over the box's corners (collideBoxCapsule).
    for (const ShapeDef& shape : {test::cubeHull(0.5), ShapeDef::box(Vec3(0.5, 0.5, 0.5))}) {
        for (const Expected& c : cases) {
            SCOPED_TRACE(std::string(c.name) + (shape.type == ShapeType::Box ? " on a box" : " on a hull"));
            WorldSettings settings = test::backendSettings("ode");
            settings.gravity = Vec3::Zero();
            World world(settings);
            BodyDef cube;
            cube.type = BodyType::Static;
            cube.shape = shape;
            world.createBody(cube);  // first: the events' body A, their normal from it to the capsule
            world.createBody(capsuleBetween(c.a, c.b, r));
            world.step();
            ASSERT_EQ(world.lastEvents().size(), 1u);
            const ContactEvent& e = world.lastEvents()[0];
            // 1e-9: each figure is a few products of the step's poses; a wrong feature is centimetres off.
            EXPECT_LT((e.normal - c.outward).norm(), 1e-9) << e.normal.transpose();
            ASSERT_EQ(e.points.size(), c.at.size());
            for (const ContactPoint& p : e.points) {
                EXPECT_NEAR(p.depth, c.depth, 1e-9);
                double nearest = INFINITY;
                for (const Vec3& q : c.at) nearest = std::min(nearest, (p.position - q).norm());
                EXPECT_LT(nearest, 1e-9) << p.position.transpose();
            }
        }
    }
}

// A 0.25 m capsule probe (core 0.6 m) against a unit cube hull turned 30 degrees about Z, a
// compound child at (2, 1, 0): pointing out of a face, an edge and a corner, and lying along
// the face and the edge, at 24 and 26 cm from the hull (0.24 touches, 0.26 does not); then the
// pair the other way round, a hull probe against a static capsule.
TEST(OdeConvexCapsule, CapsuleTouchesAHullExactlyInEveryRegionBothWaysRound) {
    World world(test::backendSettings("ode"));
    const Quat turn(Eigen::AngleAxisd(std::numbers::pi / 6, Vec3::UnitZ()));
    BodyDef holder;
    holder.type = BodyType::Static;
    holder.position = Vec3(1, 0, 0);
    holder.shape = ShapeDef::compound({test::cubeHull(0.5).placed(Vec3(1, 1, 0), turn)});
    world.createBody(holder);
    const Vec3 centre(2, 1, 0);
    struct Region {
        const char* name;
        Vec3 surfacePoint, outward, along;  // along: the core's direction
    };
    const Vec3 face(0, 1, 0), edge = Vec3(1, 1, 0).normalized(), corner = Vec3(1, 1, 1).normalized();
    const std::vector<Region> regions{{"out of a face", Vec3(0, 0.5, 0), face, face},
                                      {"lying on a face", Vec3(0, 0.5, 0), face, Vec3(1, 0, 1).normalized()},
                                      {"out of an edge", Vec3(0.5, 0.5, 0), edge, edge},
                                      {"along an edge", Vec3(0.5, 0.5, 0), edge, Vec3::UnitZ()},
                                      {"across an edge", Vec3(0.5, 0.5, 0), edge, Vec3(1, -1, 0).normalized()},
                                      {"out of a corner", Vec3(0.5, 0.5, 0.5), corner, corner}};
    const double radius = 0.25, halfHeight = 0.3;
    for (const Region& r : regions) {
        SCOPED_TRACE(r.name);
        for (const double gap : {0.24, 0.26}) {
            // The capsule's core starts at `gap` from the surface point; pointing out, it runs
            // on outwards; lying, it is centred there.
            const bool pointing = std::abs(r.along.dot(r.outward)) > 0.5;
            const Vec3 middle = r.surfacePoint + gap * r.outward + (pointing ? halfHeight : 0.0) * r.along;
            const Transform pose{centre + turn * middle, turn * Quat::FromTwoVectors(Vec3::UnitY(), r.along)};
            EXPECT_EQ(world.overlap(ShapeDef::capsule(radius, halfHeight), pose).empty(), gap > radius) << gap;
        }
    }

    World probes(test::backendSettings("ode"));
    BodyDef target;
    target.type = BodyType::Static;
    target.shape = ShapeDef::capsule(0.5, 1.0);
    target.position = Vec3(5, 0, 0);
    probes.createBody(target);
    // The probe cube's corner (0.5, 0.5, 0.5), its nearest point to the capsule's core (which
    // runs along y from (5, -1, 0) to (5, 1, 0)), at 0.49 and 0.51 m from the core's middle.
    const Vec3 across = Vec3(1, 0, 1).normalized();
    for (const double reach : {0.49, 0.51}) {
        const Vec3 at = Vec3(5, 0, 0) - reach * across - Vec3(0.5, 0.5, 0.5);
        EXPECT_EQ(probes.overlap(test::cubeHull(0.5), Transform{at, Quat::Identity()}).size(), reach < 0.5 ? 1u : 0u) << reach;
    }
}

// A capsule dropped lying on a hull slab rests level and still: two contacts hold it, where
// libccd's one point let it roll (8.6 mm/s at its ends after 2 s in ShapePairsTest).
TEST(OdeConvexCapsule, CapsuleLyingOnAHullRestsStill) {
    World world(test::backendSettings("ode"));
    BodyDef slab;
    slab.type = BodyType::Static;
    slab.shape = ShapeDef::convex({{-5, -1, -5}, {5, -1, -5}, {5, -1, 5}, {-5, -1, 5}, {-5, 0, -5}, {5, 0, -5}, {5, 0, 5}, {-5, 0, 5}});
    world.createBody(slab);
    const Body capsule = world.createBody(capsuleBetween(Vec3(-0.4, 0.5, 0.1), Vec3(0.4, 0.5, 0.1), 0.2));
    for (int i = 0; i < 120; ++i) world.step();  // 2 s: lands after 0.2 s
    test::WorstCheck height, speed, tilt;       // a NaN is kept, and fails
    for (int i = 0; i < 60; ++i) {
        world.step();
        const BodyState s = capsule.state();
        height.check(std::abs(s.position.y() - 0.2), "height");
        speed.check(s.linearVelocity.norm() + 0.6 * s.angularVelocity.norm(), "fastest point");  // 0.6: the core's half plus the radius
        tilt.check(std::abs((s.orientation * Vec3::UnitY()).y()), "tilt");
    }
    EXPECT_LT(height.value, 5e-3);  // ODE's soft contacts and surface layer rest millimetres deep
    EXPECT_LT(speed.value, 1e-3);   // still: a rolling or rocking capsule moves centimetres a second
    EXPECT_LT(tilt.value, 1e-3);    // level: both ends held alike
}

// Found by the API fuzzer: a hull of ten points within a metre and one 1e7 m away, and a 5 cm
// capsule of no length, both dynamic and at the same place, beside a static ball; then a second,
// kinematic hull. libccd's MPR looped for ever in the second step.
TEST(OdeConvexCapsule, HullReachingTenThousandKilometresDoesNotHangTheStep) {
    World world(test::backendSettings("ode"));
    const Body hull = world.createBody(ode::test::needleHullFromTheFuzzer());
    BodyDef capsule;
    capsule.shape = ShapeDef::capsule(0.05, 0.0);
    capsule.position = Vec3(-5, -5, -5);
    world.createBody(capsule);
    BodyDef ball = test::ballDef("ball", 0.05, Vec3(-5, -5, -5));
    ball.type = BodyType::Static;
    world.createBody(ball);
    world.step();
    BodyDef wedge;
    wedge.type = BodyType::Kinematic;
    wedge.position = Vec3(-0.650224, -0.0672646, -0.650224);
    wedge.shape = ShapeDef::convex({{0.0313901, -0.0941704, 0.0403587}, {0.0403587, -0.058296, -1}, {-0.0134529, -0.0762332, 0.0313901},
                                    {-0.587444, 0.0044843, -0.0313901}});
    world.createBody(wedge);
    for (int i = 0; i < 10; ++i) world.step();
    EXPECT_TRUE(hull.position().allFinite());
}

}  // namespace
}  // namespace anyphys
