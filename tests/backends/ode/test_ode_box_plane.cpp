// The ODE backend's own box-against-plane collider (ode_box_plane.hpp): a box resting on the
// ground keeps all four corners in contact in every step, and the reach that takes is a few
// micrometres: a corner a millimetre up does not touch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"
#include "ode_box_plane.hpp"

namespace anyphys {
namespace {

// Placed exactly on the ground, a 100 kg box rests at depth 0 give or take the solver's rounding,
// which lifted corners up to 1.1e-6 m above it. ODE's collider dropped those corners: the box
// stood on three, then one, and when a ball landed on it in such a step it tipped and sank 4.5 mm.
TEST(OdeBoxPlane, RestingBoxKeepsItsFourCornersInEveryStep) {
    World world(test::backendSettings("ode"));
    world.createBody(test::groundDef());
    BodyDef box = test::boxDef("box", Vec3::Constant(0.5), Vec3(0, 0.5, 0));
    box.mass = 100.0;
    box.allowSleep = false;
    world.createBody(box);
    int stepsShort = 0;
    for (int step = 0; step < 120; ++step) {
        world.step();
        ASSERT_EQ(world.lastEvents().size(), 1u);
        stepsShort += world.lastEvents()[0].points.size() == 4 ? 0 : 1;
    }
    EXPECT_EQ(stepsShort, 0) << "steps in which the resting box stood on fewer than its four corners";
}

// A box turned about z so that two corners are 1e-7 m into the ground and the other two `rise`
// above it, with no gravity: the first step's events list what the collider found. Within the
// reach the raised corners touch at depth 0 (ODE's own collider gave the two sunk ones only); a
// millimetre up, a hundred reaches, they do not.
std::size_t cornersTouching(double rise, double& deepest, double& shallowest) {
    WorldSettings settings = test::backendSettings("ode");
    settings.gravity = Vec3::Zero();
    World world(settings);
    world.createBody(test::groundDef());
    const double angle = std::asin(rise);  // the box's edge is 1 m
    BodyDef box = test::boxDef("box", Vec3::Constant(0.5), Vec3(0, 0.5 * (std::sin(angle) + std::cos(angle)) - 1e-7, 0));
    box.orientation = Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
    world.createBody(box);
    world.step();
    if (world.lastEvents().size() != 1) return 0;
    deepest = 0.0;
    shallowest = 1.0;
    for (const ContactPoint& p : world.lastEvents()[0].points) {
        deepest = std::max(deepest, p.depth);
        shallowest = std::min(shallowest, p.depth);
    }
    return world.lastEvents()[0].points.size();
}

TEST(OdeBoxPlane, CornersWithinTheReachTouchAtDepthZero) {
    double deepest = 0.0, shallowest = 0.0;
    ASSERT_EQ(cornersTouching(0.5 * ode::kBoxPlaneReach, deepest, shallowest), 4u);
    EXPECT_NEAR(deepest, 1e-7, 1e-12);  // 1e-12: the rounding of a unit box's corners
    EXPECT_EQ(shallowest, 0.0);
    ASSERT_EQ(cornersTouching(1e-3, deepest, shallowest), 2u);
    EXPECT_NEAR(shallowest, 1e-7, 1e-12);
}

}  // namespace
}  // namespace anyphys
