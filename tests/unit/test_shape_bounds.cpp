// The layer's world bounds of each primitive shape (debug drawing): tight boxes, by closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/shape_bounds.hpp"

namespace anyphys {
namespace {

void expectBox(const std::optional<Aabb>& box, const Vec3& min, const Vec3& max) {
    ASSERT_TRUE(box.has_value());
    EXPECT_LT((box->min - min).norm(), 1e-12) << box->min.transpose();
    EXPECT_LT((box->max - max).norm(), 1e-12) << box->max.transpose();
}

TEST(ShapeBounds, SphereIsCentrePlusMinusRadius) {
    expectBox(shapeBounds(ShapeDef::sphere(0.5), {Vec3(1, 2, 3), Quat(Eigen::AngleAxisd(1.0, Vec3::UnitX()))}),
              Vec3(0.5, 1.5, 2.5), Vec3(1.5, 2.5, 3.5));
}

TEST(ShapeBounds, BoxTurnedAboutZReachesItsDiagonal) {
    // A unit square turned 45 deg about Z spans its half diagonal, sqrt(2) / 2, along X and Y.
    const double h = std::sqrt(0.5);
    expectBox(shapeBounds(ShapeDef::box(Vec3(0.5, 0.5, 0.2)), {Vec3::Zero(), Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()))}),
              Vec3(-h, -h, -0.2), Vec3(h, h, 0.2));
}

TEST(ShapeBounds, CapsuleLyingAlongXIsItsSegmentSweptByTheRadius) {
    // Core along body Y turned onto world X: half length 1 + radius 0.25 along X.
    const Quat onX(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));
    expectBox(shapeBounds(ShapeDef::capsule(0.25, 1.0), {Vec3(0, 1, 0), onX}), Vec3(-1.25, 0.75, -0.25),
              Vec3(1.25, 1.25, 0.25));
}

TEST(ShapeBounds, ConvexAndMeshAreTheirPointsPlaced) {
    const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
    expectBox(shapeBounds(ShapeDef::convex(points), {Vec3(1, 1, 1), Quat::Identity()}), Vec3(1, 1, 1), Vec3(2, 3, 4));
    expectBox(shapeBounds(ShapeDef::mesh(points, {0, 1, 2, 0, 2, 3}), {Vec3::Zero(), Quat::Identity()}), Vec3::Zero(),
              Vec3(1, 2, 3));
}

TEST(ShapeBounds, PlaneHasNone) {
    EXPECT_FALSE(shapeBounds(ShapeDef::plane(Vec3::UnitY(), 0.0), {}).has_value());
}

}  // namespace
}  // namespace anyphys
