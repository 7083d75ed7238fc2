// The catalogue's scenes are valid scene files, and the contact scenes' checks measure what they
// claim when fed exact motions (no backend involved).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "anyphys/containers/scene_catalogue.hpp"
#include "anyphys/validation.hpp"

using namespace anyphys;

namespace {

/// Feeds a probe the states of `scene` with body `moving` following `motion(t)` for `duration`.
double probeExactMotion(const CatalogueScene& entry, std::size_t moving,
                        const std::function<BodyState(double)>& motion, double duration) {
    std::vector<BodyState> states;
    for (const BodyDef& def : entry.scene.bodies) {
        BodyState s;
        s.position = def.position;
        s.orientation = def.orientation;
        states.push_back(s);
    }
    auto probe = entry.check->makeProbe();
    const double dt = entry.scene.settings.timeStep;
    const long long steps = std::llround(duration / dt);
    for (long long i = 0; i <= steps; ++i) {
        states[moving] = motion(i * dt);
        probe->observe(i * dt, states);
    }
    return probe->value();
}

}  // namespace

TEST(SceneCatalogue, EverySceneIsAValidSceneFileThatRoundTrips) {
    for (const CatalogueScene& c : sceneCatalogue()) {
        SCOPED_TRACE(c.name);
        validate(c.scene.settings, "settings");
        for (std::size_t i = 0; i < c.scene.bodies.size(); ++i)
            validate(c.scene.bodies[i], "bodies[" + std::to_string(i) + "]");
        const std::string text = sceneToJson(c.scene);
        EXPECT_EQ(sceneToJson(parseScene(text)), text);
        EXPECT_GT(c.duration, 0.0);
        if (c.check) {
            EXPECT_TRUE(c.check->makeProbe) << "a check needs a probe";
        }
    }
}

TEST(SceneCatalogue, ContactScenesAreBuiltAsDescribed) {
    const Scene& stack = catalogueScene("box_stack_10").scene;
    ASSERT_EQ(stack.bodies.size(), 11u);  // ground + 10
    EXPECT_EQ(stack.bodies.back().position, Vec3(0, 9.5, 0));  // no gaps: centres 1 m apart from 0.5
    EXPECT_EQ(catalogueScene("pyramid_20").scene.bodies.size(), 1u + 210u);  // 20 + 19 + ... + 1
    const Scene& grid = catalogueScene("box_grid_1000").scene;
    ASSERT_EQ(grid.bodies.size(), 1001u);
    EXPECT_DOUBLE_EQ(grid.bodies[1].position.y(), 1.5);  // bottoms 1 m above the ground
    EXPECT_EQ(grid.settings.timeStep, 1.0 / 60.0);
    EXPECT_FALSE(catalogueScene("box_grid_1000").compareByDefault);
    const Scene& ball = catalogueScene("bouncing_ball").scene;
    EXPECT_EQ(ball.materials.resolve(ball.bodies[0].material, ball.bodies[1].material).restitution, 0.5);
    const Scene& slope = catalogueScene("slope_slide").scene;
    EXPECT_DOUBLE_EQ(slope.materials.resolve(slope.bodies[0].material, slope.bodies[1].material).friction, 0.3);
    // Free bodies never collide, even where contacts exist.
    for (const BodyDef& def : catalogueScene("free_bodies").scene.bodies) EXPECT_EQ(def.mask, 0u);
}

// An exact bounce with e = 0.5 from a 4.5 m drop gives the ratio 0.25.
TEST(SceneCatalogue, ReboundCheckReadsRestitutionSquared) {
    const CatalogueScene& entry = catalogueScene("bouncing_ball");
    constexpr double g = 9.81, r = 0.5, y0 = 5.0, e = 0.5;
    const double v0 = std::sqrt(2 * g * (y0 - r)), t0 = v0 / g;  // first impact
    const auto motion = [&](double t) {
        BodyState s;
        if (t < t0) {
            s.position.y() = y0 - 0.5 * g * t * t;
            s.linearVelocity.y() = -g * t;
        } else {
            const double u = t - t0, v1 = e * v0;  // ignores later bounces: the check stops at the first apex
            s.position.y() = r + v1 * u - 0.5 * g * u * u;
            s.linearVelocity.y() = v1 - g * u;
        }
        return s;
    };
    const double value = probeExactMotion(entry, 1, motion, 2.0);
    EXPECT_NEAR(value, 0.25, 1e-3);  // apex sampled every 1/60 s: low by at most g dt^2 / 8
    EXPECT_TRUE(entry.check->passes(value));
}

TEST(SceneCatalogue, SlopeCheckAndReferenceAgreeOnTheExactSlide) {
    const CatalogueScene& entry = catalogueScene("slope_slide");
    const double exactAccel = 9.81 * (0.5 - 0.3 * std::cos(std::numbers::pi / 6));
    EXPECT_NEAR(entry.check->expected, exactAccel, 1e-12);
    const auto motion = [&](double t) { return *entry.reference("block", t); };
    const double value = probeExactMotion(entry, 1, motion, entry.duration);
    EXPECT_NEAR(value, exactAccel, 1e-9);
    // Downhill is down: the block loses height as it slides.
    EXPECT_LT(entry.reference("block", 1.0)->position.y(), entry.scene.bodies[1].position.y());
    EXPECT_FALSE(entry.reference("slope", 1.0).has_value());
}

TEST(SceneCatalogue, DriftChecksMeasureSidewaysMotionOnly) {
    const CatalogueScene& stack = catalogueScene("box_stack_10");
    const Vec3 top = stack.scene.bodies.back().position;
    const auto lean = [&](double t) {
        BodyState s;
        s.position = top + Vec3(0.0012 * t, -0.005 * t, 0.0016 * t);  // 2 mm/s sideways, sinking 5 mm/s
        return s;
    };
    EXPECT_NEAR(probeExactMotion(stack, 10, lean, 10.0), 0.02, 1e-12);  // the sinking does not count
    EXPECT_FALSE(stack.check->passes(0.02));
    EXPECT_TRUE(stack.check->passes(0.009));
}
