// Planar worlds (settings.planar: XY plane, rotation about Z): the subset of the contract every
// backend with the `planar` capability must meet, 2D engines and 3D engines with a plane
// constraint alike. Scenes come from the catalogue's *_planar entries, so the tool, the tests and
// the benchmarks measure the same thing.
#include <cmath>
#include <limits>
#include <iostream>
#include <vector>
#include <numbers>

#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class PlanarTest : public ContractTest {
protected:
    bool planarTest() const override { return true; }

    /// Runs a catalogue scene and checks its own measure as the contract criterion it names.
    void expectCatalogueCheck(const std::string& scene) {
        const CatalogueScene& entry = catalogueScene(scene);
        const CheckRun run = runCatalogueCheck(entry, backend());
        const SceneCheck& check = *entry.check;
        report(backend() + " " + scene + ": " + check.label, run.value, check.unit);
        EXPECT_TRUE(run.finite) << "a state became NaN or infinite";
        expectCriterion(check.criterion, check.passes(run.value),
                        check.label + " " + std::to_string(run.value) + " " + check.unit + " (want " +
                            std::to_string(check.expected) + " +- " + std::to_string(check.tolerance) + ")");
    }
};

// The catalogue's bouncing ball in the plane: first rebound e^2 = 0.25 of the drop, within 5 %.
TEST_P(PlanarTest, BallReboundsToRestitutionSquared) {
    const std::string missing =
        lacking(caps(), {ShapeType::Sphere, ShapeType::Plane}, Effect::Contacts | Effect::Restitution);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    expectCatalogueCheck("bouncing_ball_planar");
}

// 2 deg below the friction angle (mu 0.5) a box on a plane tilted about Z stays put.
TEST_P(PlanarTest, BoxStaysOnSlopeBelowFrictionAngle) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    constexpr double kMu = 0.5;
    MaterialLibrary materials;
    materials.add("rough", Material{kMu, 0.0, 1000.0});
    World world(settings(), materials);
    const Quat tilt(Eigen::AngleAxisd(std::atan(kMu) - 2 * kDegree, Vec3::UnitZ()));
    const Vec3 normal = tilt * Vec3::UnitY();
    BodyDef slope = groundDef("rough");
    slope.shape = ShapeDef::plane(normal, 0.0);
    world.createBody(slope);
    BodyDef boxDefinition = boxDef("box", Vec3(0.25, 0.25, 0.25), normal * 0.25, "rough");
    boxDefinition.orientation = tilt;
    Body box = world.createBody(boxDefinition);
    const Vec3 start = box.position();
    for (int i = 0; i < 120; ++i) world.step();  // 2 s
    const double moved = (box.position() - start).norm();
    report(backend() + " planar creep 2 deg below the friction angle, 2 s", moved, "m");
    // 1 cm, as in 3D: a box that slipped would be metres away (4.1 m/s^2 unopposed: 8 m in 2 s).
    expectCriterion("planar.slope.static_hold", moved < 0.01, "moved " + std::to_string(moved) + " m in 2 s (bound 0.01)");
}

// The catalogue's slope in the plane: mean slide acceleration g (sin 30 - 0.3 cos 30) within 5 %.
TEST_P(PlanarTest, BoxSlidesWithKineticAcceleration) {
    const std::string missing = lacking(caps(), {ShapeType::Box}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    expectCatalogueCheck("slope_slide_planar");
}

// A ball set sliding in the plane slows at mu g while it slips, then rolls without slipping at
// 5/7 of its speed, as in 3D (slideUntilRolling).
TEST_P(PlanarTest, SlidingBallSlowsAtMuGUntilItRolls) {
    const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const WorstCheck worst = rollingWorst(slideUntilRolling(settings(), ShapeDef::sphere(0.25)), settings());
    report(backend() + " planar sliding ball: worst check as a multiple of its bound (" + worst.what + ")", worst.value);
    expectCriterion("planar.friction.rolling", worst.value <= 1.0,
                    "worst " + worst.what + ", " + std::to_string(worst.value) + " x its bound", worst.value);
}

// The oblique landing of ContactsTest, in the plane: along +x and -x.
TEST_P(PlanarTest, ObliqueLandingGetsItsFrictionInTheImpact) {
    const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Plane},
                                        Effect::Contacts | Effect::Friction | Effect::Restitution);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const WorstCheck worst = obliqueLandings(settings(), {Vec3::UnitX(), -Vec3::UnitX()});
    report(backend() + " planar oblique landing: worst check as a multiple of its bound (" + worst.what + ")", worst.value);
    expectCriterion("planar.friction.impact", worst.value <= 1.0, "worst " + worst.what, worst.value);
}

// The fast oblique landing of ContactsTest, in the plane: along +x and -x.
TEST_P(PlanarTest, FastObliqueLandingGetsItsFrictionInTheImpact) {
    const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Plane},
                                        Effect::Contacts | Effect::Friction | Effect::ContinuousCollision);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const WorstCheck worst = fastObliqueLandings(settings(), {Vec3::UnitX(), -Vec3::UnitX()});
    report(backend() + " planar fast oblique landing: worst check as a multiple of its bound (" + worst.what + ")", worst.value);
    expectCriterion("planar.friction.impact_fast", worst.value <= 1.0, "worst " + worst.what, worst.value);
}

// Planar twin of ContactsTest.FastBoxLandingStopsItsSlide, same bound.
TEST_P(PlanarTest, FastBoxLandingStopsItsSlide) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const CriterionResult r = fastBoxLandings(settings(), "planar.friction.fast_box_landing");
    expectCriterion(r.id, r.met, r.measured, r.value);
}

// The glancing hit of ContactsTest, in the plane (its paths and line of centres lie in XY).
TEST_P(PlanarTest, GlancingBallsLeaveInTheElasticDirections) {
    const std::string missing = lacking(caps(), {ShapeType::Sphere}, Effect::Contacts | Effect::Restitution);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const WorstCheck worst = glancingHits(settings(), backend());
    expectCriterion("planar.restitution.glancing_direction", worst.value <= 4.0, worst.what, worst.value);
}

// The table edge of ContactsTest, in the plane: over an edge on +x and on -x.
TEST_P(PlanarTest, BodyOverATableEdgeTipsOff) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Convex, ShapeType::Capsule},
                                        Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    for (const CriterionResult& r : tableEdgeResults(settings(), {Vec3::UnitX(), -Vec3::UnitX()}, backend() + " planar"))
        expectCriterion("planar." + r.id, r.met, r.measured, r.value);
}

// The tip about a table's edge of ContactsTest, in the plane.
TEST_P(PlanarTest, BoxTipsAboutATableEdgeAsAPendulum) {
    const std::string missing = lacking(caps(), {ShapeType::Box}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    for (const CriterionResult& r : tipResults(settings(), {Vec3::UnitX(), -Vec3::UnitX()}, backend() + " planar"))
        expectCriterion("planar." + r.id, r.met, r.measured, r.value);
}

// The book-stacking problem of ContactsTest, in the plane.
TEST_P(PlanarTest, OverhangingStackStandsBelowTheHarmonicOffsetsAndTopplesAbove) {
    const std::string missing = lacking(caps(), {ShapeType::Box}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    for (const CriterionResult& r : overhangResults(settings(), backend() + " planar"))
        expectCriterion("planar." + r.id, r.met, r.measured, r.value);
}

// 10 unit boxes stand 10 s in the plane: the top box moves less than 1 cm sideways.
TEST_P(PlanarTest, TenBoxStackStands) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    expectCatalogueCheck("box_stack_10_planar");
}

// A 20-row pyramid (210 boxes) stands 5 s in the plane: no box moves 5 cm sideways.
TEST_P(PlanarTest, TwentyRowPyramidStands) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    expectCatalogueCheck("pyramid_20_planar");
}

// The 3D tunnelling case in the plane: a 0.1 m ball at 200 m/s must stop at a 0.1 m wall.
TEST_P(PlanarTest, FastSphereNeverTunnelsThroughThinWall) {
    const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Box},
                                        Effect::Contacts | Effect::ContinuousCollision);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const CriterionResult r = fastSphereResult(settings(), "planar.tunnelling.fast_sphere",
                                               backend() + " planar fast sphere: farthest centre x (wall face at 9.95)");
    expectCriterion(r.id, r.met, r.measured);
}

// ... and on a slider along its flight (contact_helpers.hpp: a body held by joints too).
TEST_P(PlanarTest, FastSphereOnASliderNeverTunnelsThroughThinWall) {
    const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Box},
                                        Effect::Contacts | Effect::ContinuousCollision | Effect::Joints);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    ANYPHYS_REQUIRE(caps().jointTypes.contains("slider"), "joint type slider");
    const CriterionResult r = fastSphereResult(
        settings(), "planar.tunnelling.fast_sphere_jointed",
        backend() + " planar fast sphere on a slider: farthest centre x (wall face at 9.95)", false, true);
    expectCriterion(r.id, r.met, r.measured);
}

// A plane holds what rests on it anywhere along it: from 10 km out to 9 000 km, either way. Box2D
// stood a plane in with one edge 2 km long, and the catalogue's hard_far_stack_planar (five boxes
// 10 km out) fell through its ground, unseen by that case's sideways measure; native's broad
// phase saw a plane only 1e6 m either way.
TEST_P(PlanarTest, BoxRestsOnAPlaneFarFromTheOrigin) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    expectRestsFarOut(settings(), {Vec3(1e4, 0, 0), Vec3(-1e4, 0, 0), Vec3(1e5, 0, 0), Vec3(-1e5, 0, 0), Vec3(3e6, 0, 0),
                                   Vec3(-9e6, 0, 0)});
}

// A plane is solid below its surface: Box2D's one-sided edges let go of a box whose centre was
// set behind them, and it fell through the ground; a polygon under each edge now holds it.
TEST_P(PlanarTest, BodiesSetIntoAPlaneRiseOntoIt) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Sphere, ShapeType::Plane}, Effect::Contacts);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const double sideways = sunkBodiesRiseOntoThePlane(settings());
    expectCriterion("planar.contacts.sunk_rises_straight", sideways < 0.05, "farthest sideways " + std::to_string(sideways) + " m (bound 0.05)", sideways);
}

// Planar twin of ContactsTest.KinematicPaddlePushesABoxAtItsOwnSpeed, same bounds.
TEST_P(PlanarTest, KinematicPaddlePushesABoxAtItsOwnSpeed) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const CriterionResult r = paddlePushesABox(settings(), "planar.contacts.paddle_push");
    expectCriterion(r.id, r.met, r.measured, r.value);
}

// Planar twin of ContactsTest.BoxRidesADescendingPlatform, same bounds.
TEST_P(PlanarTest, BoxRidesADescendingPlatform) {
    const std::string missing = lacking(caps(), {ShapeType::Box}, Effect::Contacts);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const CriterionResult r = boxRidesADescendingPlatform(settings(), "planar.contacts.descending_platform");
    expectCriterion(r.id, r.met, r.measured, r.value);
}

// Planar twin of ContactsTest.BoxSlidingIntoAWallStopsThere, same bounds.
TEST_P(PlanarTest, BoxSlidingIntoAWallStopsThere) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const CriterionResult r = boxSlidesIntoAWall(settings(), "planar.contacts.wall_stop");
    expectCriterion(r.id, r.met, r.measured, r.value);
}

// Planar twin of ContactsTest.SwallowedBoxIsPushedOutThroughTheNearestFace, same bounds.
TEST_P(PlanarTest, SwallowedBoxIsPushedOutThroughTheNearestFace) {
    const std::string missing = lacking(caps(), {ShapeType::Box}, Effect::Contacts);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    const CriterionResult r = swallowedBoxIsPushedOut(everySolverAndSubstepCount(settings()),
                                                       caps().parameters.contains("settings.contactPushMaxVelocity"), "planar.contacts.swallowed_box");
    expectCriterion(r.id, r.met, r.measured, r.value);
}

// Motion stays in the plane: a box thrown spinning onto the ground, pushed out of the plane by a
// force and an impulse (which the plane absorbs), keeps z = 0 and turns about Z only.
TEST_P(PlanarTest, MotionStaysInThePlane) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    World world(settings());
    world.createBody(groundDef());
    BodyDef thrown = boxDef("thrown", Vec3(0.5, 0.25, 0.5), Vec3(0, 2, 0));
    thrown.linearVelocity = Vec3(3, 1, 0);
    thrown.angularVelocity = Vec3(0, 0, 4);
    Body box = world.createBody(thrown);
    // A lopsided body: a hull reaching 0.6 m in front of the plane and 0.1 m behind it, its bottom
    // sloping in depth, so its contacts are off the plane and would tip it over in 3D. Only the backend's own planar handling (not
    // the layer, which sees no out-of-plane input here) can keep it in the plane.
    std::vector<Body> bodies{box};
    if (caps().shapes.count(ShapeType::Convex)) {
        BodyDef lopsided = boxDef("lopsided", Vec3(0.3, 0.3, 0.3), Vec3(3, 1.5, 0));
        // A wedge in depth: 0.1 m behind the plane, 0.6 m in front, its bottom sloping in z.
        lopsided.shape = ShapeDef::convex({{-0.3, -0.3, -0.1}, {0.3, -0.3, -0.1}, {-0.3, 0.3, -0.1}, {0.3, 0.3, -0.1},
                                           {-0.3, -0.1, 0.6}, {0.3, -0.1, 0.6}, {-0.3, 0.3, 0.6}, {0.3, 0.3, 0.6}});
        lopsided.angularVelocity = Vec3(0, 0, -2);
        bodies.push_back(world.createBody(lopsided));
    } else {
        std::cout << "[ NOT RUN  ] " << backend() << " lacks convex shapes: the lopsided body is left out\n";
    }
    double worstZ = 0.0, worstTilt = 0.0;
    for (int i = 0; i < 120; ++i) {
        box.applyForce(Vec3(0, 0, 500));          // out of the plane: dropped
        if (i == 30) box.applyLinearImpulse(Vec3(0, 0, 50));
        world.step();
        for (const Body& b : bodies) {
            const Quat q = b.orientation();
            worstZ = std::max(worstZ, std::abs(b.position().z()));
            worstTilt = std::max({worstTilt, std::abs(q.x()), std::abs(q.y())});
            ASSERT_TRUE(finite(b.state()));
        }
    }
    if (bodies.size() > 1) {
        EXPECT_LT(bodies[1].position().y(), 1.0) << "the lopsided body should have landed";
    }
    report(backend() + " planar: largest |z|", worstZ, "m");
    report(backend() + " planar: largest |q.x|, |q.y|", worstTilt);
    // 1 micrometre and 1e-6: engines that hold the plane with a constraint (rather than by
    // construction) correct drift each step; anything visible would be millimetres.
    EXPECT_LT(worstZ, 1e-6);
    EXPECT_LT(worstTilt, 1e-6);
    EXPECT_GT(box.position().x(), 1.0) << "the box should have travelled along x";
}

// Non-planar input to a planar world is refused with the body and the field named, and the
// world is left as it was.
TEST_P(PlanarTest, NonPlanarInputIsRejectedNamingBodyAndField) {
    World world(settings());
    const auto expectRejected = [&](const BodyDef& def, const std::string& field) {
        try {
            world.createBody(def);
            ADD_FAILURE() << "accepted " << field;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(field), std::string::npos) << message;
            EXPECT_NE(message.find("\"" + def.name + "\""), std::string::npos) << message;
            EXPECT_NE(message.find("planar"), std::string::npos) << message;
        }
    };
    BodyDef off = ballDef("off_plane", 0.5, Vec3(0, 1, 0.5));
    expectRejected(off, "BodyDef.position");
    BodyDef tilted = ballDef("tilted", 0.5, Vec3(0, 1, 0));
    tilted.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
    expectRejected(tilted, "BodyDef.orientation");
    BodyDef leaving = ballDef("leaving", 0.5, Vec3(0, 1, 0));
    leaving.linearVelocity = Vec3(0, 0, 1);
    expectRejected(leaving, "BodyDef.linearVelocity");
    BodyDef rolling = ballDef("rolling", 0.5, Vec3(0, 1, 0));
    rolling.angularVelocity = Vec3(1, 0, 0);
    expectRejected(rolling, "BodyDef.angularVelocity");
    EXPECT_EQ(world.bodyCount(), 0u);

    Body ok = world.createBody(ballDef("ok", 0.5, Vec3(0, 1, 0)));
    EXPECT_THROW(ok.setLinearVelocity(Vec3(0, 0, 2)), Error);
    EXPECT_THROW(ok.setTransform(Vec3(0, 1, 1), Quat::Identity()), Error);
    EXPECT_EQ(ok.position(), Vec3(0, 1, 0));  // unchanged by the rejected calls
}

// A 3D world on a planar-only backend is refused naming settings.planar; a backend with three
// dimensions takes it.
TEST_P(PlanarTest, ThreeDimensionalWorldNeedsThreeDimensions) {
    WorldSettings s = settings();
    s.planar = false;
    if (caps().dimensions < 3) {
        try {
            World world(s);
            ADD_FAILURE() << "a 3D world was accepted by a " << caps().dimensions << "D backend";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("WorldSettings.planar"), std::string::npos) << e.what();
        }
    } else {
        World world(s);
        EXPECT_FALSE(world.settings().planar);
    }
}

ANYPHYS_CONTRACT_SUITE(PlanarTest);

}  // namespace
}  // namespace anyphys::test
