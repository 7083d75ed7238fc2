// NearProbe: ODE's colliders find only overlapping shapes; the probe finds shapes a little apart
// by growing one of them, and reports depths against the true surfaces.
#include <gtest/gtest.h>
#include <ode/ode.h>

#include "anyphys/anyphys.hpp"
#include "ode_init.hpp"
#include "ode_near_pairs.hpp"
#include "ode_shapes.hpp"

namespace anyphys {
namespace {

PeerShape probedShape(const ShapeDef& def) {
    PeerShape s;
    s.def = def;
    return s;
}

class OdeNearProbe : public ::testing::Test {
protected:
    void SetUp() override { ode::ensureOdeInitialised(); }

    /// `first` against `second`, each placed at its pose (the plane's pose is its definition).
    int collide(const ShapeDef& first, const Transform& poseA, const ShapeDef& second, const Transform& poseB,
                double reach) {
        ode::OdeShape a(probedShape(first), nullptr), b(probedShape(second), nullptr);
        a.place(poseA);
        b.place(poseB);
        return probe.collide(a, b, reach, contacts, 4);
    }

    ode::NearProbe probe;
    dContactGeom contacts[4];
};

Transform placedAt(const Vec3& p, const Quat& q = Quat::Identity()) { return Transform{p, q}; }

constexpr double kReach = 0.005;  // the default linearSlop
// The depths are sums and differences of metres and millimetres in double: 1e-12 m is far
// below any gap that matters and far above the rounding of such sums.
constexpr double kDepthTolerance = 1e-12;

TEST_F(OdeNearProbe, BoxesAFewMillimetresApartAreFoundWithTheirGap) {
    const ShapeDef cube = ShapeDef::box(Vec3(0.5, 0.5, 0.5));
    const int n = collide(cube, placedAt(Vec3::Zero()), cube, placedAt(Vec3(1.002, 0, 0)), kReach);
    ASSERT_GT(n, 0);
    for (int k = 0; k < n; ++k) {
        EXPECT_NEAR(contacts[k].depth, -0.002, kDepthTolerance);
        EXPECT_NEAR(contacts[k].normal[0], -1.0, 1e-12);  // into the first shape: the second lies at +x
        EXPECT_GT(contacts[k].pos[0], 0.49);  // on the facing sides, between the two faces
        EXPECT_LT(contacts[k].pos[0], 0.51);
    }
    // Turned about y by a quarter turn the box is the same box: the same gap.
    ASSERT_GT(collide(cube, placedAt(Vec3::Zero(), Quat(Eigen::AngleAxisd(1.5707963267948966, Vec3::UnitY()))), cube,
                      placedAt(Vec3(1.002, 0, 0)), kReach), 0);
    EXPECT_NEAR(contacts[0].depth, -0.002, 1e-9);  // the turn's rounding moves the face by ~1e-16
}

TEST_F(OdeNearProbe, ShapesFartherThanTheReachAreNotFound) {
    const ShapeDef cube = ShapeDef::box(Vec3(0.5, 0.5, 0.5));
    EXPECT_EQ(collide(cube, placedAt(Vec3::Zero()), cube, placedAt(Vec3(1.006, 0, 0)), kReach), 0);
    EXPECT_EQ(collide(ShapeDef::sphere(0.5), placedAt(Vec3(0, 0.506, 0)), ShapeDef::plane(Vec3(0, 1, 0), 0), placedAt(Vec3::Zero()), kReach), 0);
}

TEST_F(OdeNearProbe, SphereCapsuleAndPlaneGrowAndReportTheTrueGap) {
    const ShapeDef ground = ShapeDef::plane(Vec3(0, 1, 0), 0);
    // A sphere 3 mm above the ground: the sphere grows (first), or the plane does (first).
    ASSERT_EQ(collide(ShapeDef::sphere(0.5), placedAt(Vec3(0, 0.503, 0)), ground, placedAt(Vec3::Zero()), kReach), 1);
    EXPECT_NEAR(contacts[0].depth, -0.003, kDepthTolerance);
    EXPECT_NEAR(contacts[0].normal[1], 1.0, 1e-12);  // into the sphere, which lies above
    ASSERT_EQ(collide(ground, placedAt(Vec3::Zero()), ShapeDef::sphere(0.5), placedAt(Vec3(0, 0.503, 0)), kReach), 1);
    EXPECT_NEAR(contacts[0].depth, -0.003, kDepthTolerance);
    // A capsule lying on its side (its axis turned onto x), 1 mm above the ground.
    const Quat lying(Eigen::AngleAxisd(1.5707963267948966, Vec3::UnitZ()));
    const int n = collide(ShapeDef::capsule(0.3, 0.5), placedAt(Vec3(0, 0.301, 0), lying), ground, placedAt(Vec3::Zero()), kReach);
    ASSERT_GT(n, 0);
    for (int k = 0; k < n; ++k) EXPECT_NEAR(contacts[k].depth, -0.001, 1e-9);  // the turn's rounding, as above
}

TEST_F(OdeNearProbe, OverlappingShapesKeepTheirDepth) {
    const ShapeDef cube = ShapeDef::box(Vec3(0.5, 0.5, 0.5));
    const int n = collide(cube, placedAt(Vec3::Zero()), cube, placedAt(Vec3(0.999, 0, 0)), kReach);
    ASSERT_GT(n, 0);
    for (int k = 0; k < n; ++k) EXPECT_NEAR(contacts[k].depth, 0.001, kDepthTolerance);
}

}  // namespace
}  // namespace anyphys
