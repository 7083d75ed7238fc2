// The ODE backend's own hull-against-sphere collider (ode_convex_sphere.hpp), which replaces
// libccd's MPR: exact in the face, edge and corner regions of a hull, inside it, at a hull's pose
// as a compound child, both ways round; and a hull reaching 1e7 m no longer hangs the step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"
#include "ode_test_helpers.hpp"

namespace anyphys {
namespace {

ShapeDef unitCubeHull() {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    return ShapeDef::convex(corners);
}

/// Whether a sphere of `radius` centred at `centre` overlaps a body of `world` (the ODE overlap
/// query collides the probe with each candidate geom, through the collider under test).
bool sphereTouches(World& world, double radius, const Vec3& centre) {
    return !world.overlap(ShapeDef::sphere(radius), Transform{centre, Quat::Identity()}).empty();
}

// A 0.25 m sphere against a unit cube hull turned 30 degrees about Z and placed at (2, 1, 0) as
// a compound child of a body at (1, 0, 0): at 24 and 26 cm from the hull's surface along the
// outward direction of a face, an edge and a corner (0.24 touches, 0.26 does not; a test by the
// face planes alone would find the sphere 18 cm from the edge's planes and 15 cm from the
// corner's, and call both touching), and with its centre inside the hull.
TEST(OdeConvexSphere, SphereTouchesAHullExactlyByFaceEdgeAndCorner) {
    World world(test::backendSettings("ode"));
    const Quat turn(Eigen::AngleAxisd(0.5235987755982988, Vec3::UnitZ()));
    BodyDef holder;
    holder.type = BodyType::Static;
    holder.position = Vec3(1, 0, 0);
    holder.shape = ShapeDef::compound({unitCubeHull().placed(Vec3(1, 1, 0), turn)});
    world.createBody(holder);
    const Vec3 centre(2, 1, 0);
    const auto place = [&](const Vec3& surfacePoint, const Vec3& outward, double gap) -> Vec3 {
        return centre + turn * (surfacePoint + gap * outward.normalized());
    };
    struct Region {
        const char* name;
        Vec3 surfacePoint, outward;
    };
    for (const Region& r : {Region{"face", Vec3(0, 0.5, 0), Vec3(0, 1, 0)}, Region{"edge", Vec3(0.5, 0.5, 0), Vec3(1, 1, 0)},
                            Region{"corner", Vec3(0.5, 0.5, 0.5), Vec3(1, 1, 1)}}) {
        SCOPED_TRACE(r.name);
        EXPECT_TRUE(sphereTouches(world, 0.25, place(r.surfacePoint, r.outward, 0.24)));
        EXPECT_FALSE(sphereTouches(world, 0.25, place(r.surfacePoint, r.outward, 0.26)));
    }
    EXPECT_TRUE(sphereTouches(world, 0.25, centre + turn * Vec3(0.1, 0.2, -0.1)));  // centre inside
}

// The pair the other way round: a hull probe against a static sphere, and a resting contact's
// depth and normal. A 0.2 m ball dropped onto a static cube hull rests on its top face, its
// contact normal along +Y and its depth within the contact's slop.
TEST(OdeConvexSphere, BallRestsOnAHullAndAHullProbeFindsABall) {
    World world(test::backendSettings("ode"));
    BodyDef cube;
    cube.type = BodyType::Static;
    cube.shape = unitCubeHull();
    world.createBody(cube);
    BodyDef ballDef = test::ballDef("ball", 0.2, Vec3(0.1, 1.0, -0.1));
    ballDef.allowSleep = false;
    const Body ball = world.createBody(ballDef);
    // Resting on the top face (y = 0.5) with its centre 0.2 m above, less ODE's contact
    // softness and surface layer (millimetres), at every step once landed: the 0.3 m fall takes
    // 0.25 s (15 steps), and 30 steps leave it time to settle.
    test::WorstCheck worstHeightError, worstDrift;  // a NaN is kept, and fails
    for (int i = 0; i < 120; ++i) {
        world.step();
        if (i < 30) continue;
        worstHeightError.check(std::abs(ball.position().y() - 0.7), "height");
        worstDrift.check((Vec3(ball.position().x(), 0, ball.position().z()) - Vec3(0.1, 0, -0.1)).norm(), "drift");
    }
    EXPECT_LT(worstHeightError.value, 5e-3);
    EXPECT_LT(worstDrift.value, 1e-6);  // a ball straight above a face has nothing to push it aside
    ASSERT_FALSE(world.lastEvents().empty());
    for (const ContactEvent& e : world.lastEvents()) {
        EXPECT_NEAR(std::abs(e.normal.y()), 1.0, 1e-9);
        for (const ContactPoint& p : e.points) {
            EXPECT_NEAR(p.position.y(), 0.5, 5e-3);  // on the top face, midway into the overlap
            EXPECT_LT(p.depth, 5e-3);
        }
    }

    BodyDef target = test::ballDef("target", 0.5, Vec3(5, 0, 0));
    target.type = BodyType::Static;
    World probes(test::backendSettings("ode"));
    probes.createBody(target);
    // The probe cube's corner (0.5, 0.5, 0.5) from its centre, its nearest point to the ball, at
    // 0.49 and 0.51 m from the ball's centre: inside its 0.5 m radius, then not.
    const Vec3 diagonal = Vec3(1, 1, 1).normalized();
    for (const double reach : {0.49, 0.51}) {
        const Vec3 at = Vec3(5, 0, 0) - reach * diagonal - Vec3(0.5, 0.5, 0.5);
        EXPECT_EQ(probes.overlap(unitCubeHull(), Transform{at, Quat::Identity()}).size(), reach < 0.5 ? 1u : 0u) << reach;
    }
}

// Found by the API fuzzer: a hull of ten points within a metre and one 1e7 m away, created with
// a 5 cm static sphere at its origin; libccd's MPR looped for ever in the first step.
TEST(OdeConvexSphere, HullReachingTenThousandKilometresDoesNotHangTheStep) {
    World world(test::backendSettings("ode"));
    const Body hull = world.createBody(ode::test::needleHullFromTheFuzzer());
    BodyDef ball = test::ballDef("ball", 0.05, Vec3(-5, -5, -5));
    ball.type = BodyType::Static;
    world.createBody(ball);
    for (int i = 0; i < 10; ++i) world.step();
    EXPECT_TRUE(hull.position().allFinite());
}

}  // namespace
}  // namespace anyphys
