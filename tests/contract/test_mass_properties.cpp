// Mass properties are resolved by the layer from shapes and densities (parallel-axis theorem for
// compounds) and must mean the same on every backend: the body origin is where the user put it,
// the centre of mass where the shapes put it.
#include <cmath>
#include <numbers>

#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class MassPropertiesTest : public ContractTest {
protected:
    WorldSettings weightless() const {
        WorldSettings s = settings();
        s.gravity = Vec3::Zero();
        return s;
    }
};

// Two spheres of radius 0.5 at x = +-1 (density 1000): the centre of mass stays at the origin,
// Ixx = 2 (2/5 m r^2), Iyy = Izz = 2 (2/5 m r^2 + m d^2) with d = 1.
TEST_P(MassPropertiesTest, DumbbellFollowsParallelAxisTheorem) {
    ANYPHYS_REQUIRE(caps().shapes.count(ShapeType::Compound), "compound shapes");
    World world(weightless());
    BodyDef def;
    def.shape = ShapeDef::compound({ShapeDef::sphere(0.5).placed(Vec3(1, 0, 0)), ShapeDef::sphere(0.5).placed(Vec3(-1, 0, 0))});
    const MassProperties m = world.createBody(def).massProperties();
    const double ball = 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.125;
    EXPECT_NEAR(m.mass, 2 * ball, 1e-9);
    EXPECT_NEAR(m.centerOfMass.norm(), 0.0, 1e-12);
    EXPECT_NEAR(m.inertia.x(), 2 * 0.4 * ball * 0.25, 1e-9);
    EXPECT_NEAR(m.inertia.y(), 2 * (0.4 * ball * 0.25 + ball), 1e-9);
    EXPECT_NEAR(m.inertia.z(), 2 * (0.4 * ball * 0.25 + ball), 1e-9);
}

// A single box placed at x = 1 in the body frame: the centre of mass is 1 m from the origin;
// the body's position stays the origin and a spin about the centre of mass keeps it fixed.
TEST_P(MassPropertiesTest, OffsetCentreOfMassIsTrackedSeparatelyFromTheOrigin) {
    ANYPHYS_REQUIRE(caps().shapes.count(ShapeType::Compound), "compound shapes");
    World world(weightless());
    BodyDef def;
    def.position = Vec3(0, 2, 0);
    def.shape = ShapeDef::compound({ShapeDef::box(Vec3(0.5, 0.5, 0.5)).placed(Vec3(1, 0, 0))});
    def.angularVelocity = Vec3(0, 0, std::numbers::pi / 2);  // a quarter turn per second
    Body b = world.createBody(def);
    EXPECT_NEAR((b.massProperties().centerOfMass - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((b.position() - Vec3(0, 2, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((b.centerOfMass() - Vec3(1, 2, 0)).norm(), 0.0, 1e-12);
    for (int i = 0; i < 60; ++i) world.step();
    // After a quarter turn about the centre of mass (1, 2, 0), the origin has swung to (1, 1, 0).
    EXPECT_NEAR((b.centerOfMass() - Vec3(1, 2, 0)).norm(), 0.0, 1e-9);
    // 2e-4 m: semi-implicit Euler's normalised quaternion update turns by 2 atan(w h / 2) per
    // step instead of w h, about 1.5e-6 rad a step here, 9e-5 rad (and m) after 60 steps.
    EXPECT_NEAR((b.position() - Vec3(1, 1, 0)).norm(), 0.0, 2e-4);
}

// A long box rotated 45 degrees in the body frame: its inertia tensor is not diagonal there, so
// the layer simulates it in its principal frame. The principal moments are the box's own.
TEST_P(MassPropertiesTest, RotatedChildUsesPrincipalAxes) {
    ANYPHYS_REQUIRE(caps().shapes.count(ShapeType::Compound), "compound shapes");
    World world(weightless());
    BodyDef def;
    const Quat tilt(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()));
    def.shape = ShapeDef::compound({ShapeDef::box(Vec3(1.0, 0.1, 0.2)).placed(Vec3::Zero(), tilt)});
    def.mass = 1.0;
    const MassProperties m = world.createBody(def).massProperties();
    // Box 2 x 0.2 x 0.4 of mass 1: moments (0.2^2 + 0.4^2, 2^2 + 0.4^2, 2^2 + 0.2^2) / 12, in some order.
    std::vector<double> got{m.inertia.x(), m.inertia.y(), m.inertia.z()};
    std::vector<double> want{(0.04 + 0.16) / 12, (4 + 0.04) / 12, (4 + 0.16) / 12};
    std::sort(got.begin(), got.end());
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], 1e-12);
    // The principal axes map the box's long axis onto the tilted direction.
    const Vec3 longAxisMoment = m.principalAxes.conjugate() * (tilt * Vec3::UnitX());
    EXPECT_NEAR(std::abs(longAxisMoment.dot(m.inertia)), (0.04 + 0.16) / 12, 1e-9);
}

// A convex hull of a cube's corners weighs what the equivalent box weighs.
TEST_P(MassPropertiesTest, ConvexHullMatchesBox) {
    ANYPHYS_REQUIRE(caps().shapes.count(ShapeType::Convex), "convex shapes");
    World world(weightless());
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 1.0 : -1.0, i & 4 ? 0.25 : -0.25);
    corners.emplace_back(0.1, 0.2, 0.0);  // an interior point changes nothing
    BodyDef hullDef;
    hullDef.shape = ShapeDef::convex(corners);
    BodyDef boxDef;
    boxDef.shape = ShapeDef::box(Vec3(0.5, 1.0, 0.25));
    const MassProperties hull = world.createBody(hullDef).massProperties();
    const MassProperties box = world.createBody(boxDef).massProperties();
    EXPECT_NEAR(hull.mass, box.mass, 1e-9);
    EXPECT_NEAR((hull.inertia - box.inertia).norm(), 0.0, 1e-9);
    EXPECT_NEAR(hull.centerOfMass.norm(), 0.0, 1e-12);
}

ANYPHYS_CONTRACT_SUITE(MassPropertiesTest);

}  // namespace
}  // namespace anyphys::test
