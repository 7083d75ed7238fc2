// Narrow phase of the native backend: contact manifolds against closed-form geometry.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "../../../api/src/geometry/convex_hull.hpp"
#include "collision/collide.hpp"
#include "collision/gjk.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/mesh_data.hpp"
#include "native_test_shapes.hpp"
#include "../../random_draws.hpp"

namespace anyphys::native {
namespace {

using namespace anyphys::native::test;  // shapes and poses (native_test_shapes.hpp)
using anyphys::test::drawTurn;
using anyphys::test::drawVec3;

// Exact configurations: only rounding separates the result from the closed form.
constexpr double kTol = 1e-9;
const double kSqrt2 = std::sqrt(2.0);

Shape boxHull(const Vec3& half) {
    Shape s;
    s.type = ShapeType::Convex;
    s.hull = std::make_shared<const HullData>(makeBoxHull(half));
    return s;
}

// A random pose: a position of up to `reach` along each axis, then a turn of up to 3 rad, drawn in
// that order (random_draws.hpp).
Transform randomPose(std::uniform_real_distribution<double>& u, std::mt19937& rng, double reach) {
    const Vec3 position = reach * drawVec3(u, rng);
    return at(position, drawTurn(u, rng, 3.0));
}

std::vector<Manifold> run(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double speculative = 0.0) {
    std::vector<Manifold> out;
    collide(a, xa, b, xb, speculative, out);
    return out;
}

// The single manifold of a convex pair.
Manifold one(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double speculative = 0.0) {
    const std::vector<Manifold> out = run(a, xa, b, xb, speculative);
    EXPECT_EQ(out.size(), 1u);
    return out.empty() ? Manifold{} : out.front();
}

double deepest(const Manifold& m) {
    double d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m.pointCount; ++i) d = std::min(d, m.points[i].separation);
    return d;
}

std::set<std::uint32_t> ids(const Manifold& m) {
    std::set<std::uint32_t> s;
    for (int i = 0; i < m.pointCount; ++i) s.insert(m.points[i].id);
    return s;
}

// Every manifold: unit normal, 1..4 points with distinct ids.
void expectWellFormed(const Manifold& m) {
    EXPECT_NEAR(m.normal.norm(), 1.0, 1e-12);
    EXPECT_GE(m.pointCount, 1);
    EXPECT_LE(m.pointCount, 4);
    EXPECT_EQ(ids(m).size(), static_cast<std::size_t>(m.pointCount)) << "ids must be distinct within a manifold";
}

// Points of m as a sorted list, for comparison with expected sets.
std::vector<Vec3> sortedPoints(const Manifold& m) {
    std::vector<Vec3> p(static_cast<std::size_t>(m.pointCount));
    std::transform(m.points.begin(), m.points.begin() + m.pointCount, p.begin(), [](const ManifoldPoint& x) { return x.point; });
    std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    return p;
}

void expectPoints(const Manifold& m, std::vector<Vec3> expected, double tol = kTol) {
    ASSERT_EQ(m.pointCount, static_cast<int>(expected.size()));
    std::sort(expected.begin(), expected.end(), [](const Vec3& a, const Vec3& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    const std::vector<Vec3> got = sortedPoints(m);
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_TRUE(got[i].isApprox(expected[i], tol) || (got[i] - expected[i]).norm() < tol)
        << "point " << got[i].transpose() << " expected " << expected[i].transpose();
}

// ---------------------------------------------------------------- spheres and capsules

TEST(Collide, SphereSphereDepthNormalAndPoint) {
    // Surfaces at x = 0.5 (a) and x = 0.7 - 0.3 = 0.4 (b): overlap 0.1, midway at 0.45.
    const Manifold m = one(sphere(0.5), at(Vec3(0, 0, 0)), sphere(0.3), at(Vec3(0.7, 0, 0)));
    expectWellFormed(m);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_TRUE(m.normal.isApprox(Vec3(1, 0, 0), kTol));
    EXPECT_NEAR(m.points[0].separation, -0.1, kTol);
    EXPECT_TRUE(m.points[0].point.isApprox(Vec3(0.45, 0, 0), kTol));

    const Manifold swapped = one(sphere(0.3), at(Vec3(0.7, 0, 0)), sphere(0.5), at(Vec3(0, 0, 0)));
    EXPECT_TRUE(swapped.normal.isApprox(Vec3(-1, 0, 0), kTol));
    EXPECT_NEAR(swapped.points[0].separation, -0.1, kTol);
    EXPECT_TRUE(swapped.points[0].point.isApprox(Vec3(0.45, 0, 0), kTol));
}

TEST(Collide, SpeculativePointsAppearWithinTheMarginOnly) {
    // 0.05 m apart along a diagonal.
    const Vec3 dir = Vec3(1, 2, 2) / 3.0;
    const Transform xb = at(dir * 1.05);
    EXPECT_TRUE(run(sphere(0.5), at(Vec3::Zero()), sphere(0.5), xb, 0.0).empty());
    EXPECT_TRUE(run(sphere(0.5), at(Vec3::Zero()), sphere(0.5), xb, 0.04).empty());
    const Manifold m = one(sphere(0.5), at(Vec3::Zero()), sphere(0.5), xb, 0.06);
    EXPECT_NEAR(m.points[0].separation, 0.05, kTol);
    EXPECT_TRUE(m.normal.isApprox(dir, kTol));

    // Boxes 0.05 apart: four speculative points inside a 0.1 margin, none inside 0.04.
    const Shape cube = box(Vec3(0.5, 0.5, 0.5));
    EXPECT_TRUE(run(cube, at(Vec3::Zero()), cube, at(Vec3(0, 1.05, 0)), 0.04).empty());
    const Manifold boxes = one(cube, at(Vec3::Zero()), cube, at(Vec3(0, 1.05, 0)), 0.1);
    EXPECT_EQ(boxes.pointCount, 4);
    for (int i = 0; i < boxes.pointCount; ++i) EXPECT_NEAR(boxes.points[i].separation, 0.05, kTol);

    // The same for a capsule over a plane.
    const Shape ground = plane(Vec3::UnitY(), 0.0);
    const Transform lying = at(Vec3(0, 0.25, 0), rotation(std::numbers::pi / 2, Vec3::UnitZ()));
    EXPECT_TRUE(run(capsule(0.2, 1.0), lying, ground, at(Vec3::Zero()), 0.04).empty());
    EXPECT_EQ(one(capsule(0.2, 1.0), lying, ground, at(Vec3::Zero()), 0.06).pointCount, 2);
}

TEST(Collide, SphereAgainstCapsuleSideAndCap) {
    const Shape c = capsule(0.25, 1.0);  // vertical segment y in [-1, 1]
    const Manifold side = one(sphere(0.5), at(Vec3(-0.7, 0.3, 0)), c, at(Vec3::Zero()));
    EXPECT_TRUE(side.normal.isApprox(Vec3(1, 0, 0), kTol));
    EXPECT_NEAR(side.points[0].separation, 0.7 - 0.75, kTol);
    EXPECT_TRUE(side.points[0].point.isApprox(Vec3(-0.7 + 0.5 - 0.025, 0.3, 0), kTol));

    const Manifold cap = one(c, at(Vec3::Zero()), sphere(0.5), at(Vec3(0, 1.7, 0)));
    EXPECT_TRUE(cap.normal.isApprox(Vec3(0, 1, 0), kTol));
    EXPECT_NEAR(cap.points[0].separation, 0.7 - 0.75, kTol);
}

TEST(Collide, ParallelCapsulesSideBySideGiveTwoPoints) {
    // Both along x (local Y turned onto x), 0.35 apart with radii 0.2: 0.05 overlap along y.
    const Quat alongX = rotation(-std::numbers::pi / 2, Vec3::UnitZ());
    const Shape c = capsule(0.2, 1.0);
    const Manifold m = one(c, at(Vec3::Zero(), alongX), c, at(Vec3(0, 0.35, 0), alongX));
    expectWellFormed(m);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol));
    ASSERT_EQ(m.pointCount, 2);
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -0.05, kTol);
    expectPoints(m, {Vec3(-1, 0.175, 0), Vec3(1, 0.175, 0)});

    // Shifted by 1.2 along x they share x in [0.2, 1]: the points sit at the ends of that stretch.
    const Manifold shifted = one(c, at(Vec3::Zero(), alongX), c, at(Vec3(1.2, 0.35, 0), alongX));
    expectPoints(shifted, {Vec3(0.2, 0.175, 0), Vec3(1, 0.175, 0)});

    // Crossing at right angles (b along z): one point over the crossing.
    const Manifold crossing = one(c, at(Vec3::Zero(), alongX), c, at(Vec3(0.3, 0.35, 0), rotation(std::numbers::pi / 2, Vec3::UnitX())));
    EXPECT_EQ(crossing.pointCount, 1);
    EXPECT_TRUE(crossing.normal.isApprox(Vec3(0, 1, 0), kTol));
    EXPECT_NEAR(crossing.points[0].separation, -0.05, kTol);
    EXPECT_TRUE(crossing.points[0].point.isApprox(Vec3(0.3, 0.175, 0), kTol));

    // Cores crossing through each other: the common perpendicular, toward b.
    const Manifold through = one(c, at(Vec3::Zero(), alongX), c, at(Vec3(0.3, 0, 0.2), rotation(std::numbers::pi / 2, Vec3::UnitX())));
    EXPECT_NEAR(std::abs(through.normal.y()), 1.0, kTol);
    EXPECT_NEAR(through.points[0].separation, -0.4, kTol);
}

// ---------------------------------------------------------------- planes

TEST(Collide, CapsuleLyingOnAPlaneGivesTwoPoints) {
    const Shape ground = plane(Vec3::UnitY(), 0.0);
    const Transform lying = at(Vec3(0.5, 0.19, 0), rotation(std::numbers::pi / 2, Vec3::UnitX()));  // along z
    const Manifold m = one(capsule(0.2, 1.0), lying, ground, at(Vec3::Zero()));
    expectWellFormed(m);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, -1, 0), kTol)) << "from the capsule (a) to the plane (b)";
    ASSERT_EQ(m.pointCount, 2);
    expectPoints(m, {Vec3(0.5, -0.005, -1), Vec3(0.5, -0.005, 1)});
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -0.01, kTol);

    const Manifold swapped = one(ground, at(Vec3::Zero()), capsule(0.2, 1.0), lying);
    EXPECT_TRUE(swapped.normal.isApprox(Vec3(0, 1, 0), kTol));
    EXPECT_EQ(swapped.pointCount, 2);
}

TEST(Collide, PlaneIgnoresItsPoseAndKeepsFourOfManyVertices) {
    // A tilted plane through (0, 1, 0); the plane's own pose must not matter.
    const Vec3 n = Vec3(0, 1, 1).normalized();
    const Shape slope = plane(n, n.dot(Vec3(0, 1, 0)));
    const Manifold s = one(slope, at(Vec3(5, 5, 5), rotation(1.0, Vec3::UnitX())), sphere(0.5), at(Vec3(0, 1, 0) + 0.4 * n));
    EXPECT_TRUE(s.normal.isApprox(n, kTol));
    EXPECT_NEAR(s.points[0].separation, -0.1, kTol);

    // A hexagonal prism lying flat: six bottom vertices below the plane reduce to four, the
    // deepest (its prism is tilted a little) among them.
    std::vector<Vec3> points;
    for (int i = 0; i < 6; ++i) {
        const double a = std::numbers::pi / 3 * i;
        points.emplace_back(std::cos(a), -0.2, std::sin(a));
        points.emplace_back(std::cos(a), 0.2, std::sin(a));
    }
    const Shape prism = convex(points);
    const Transform xf = at(Vec3(0, 0.19, 0), rotation(0.001, Vec3::UnitZ()));
    const Manifold m = one(prism, xf, plane(Vec3::UnitY(), 0.0), at(Vec3::Zero()));
    expectWellFormed(m);
    EXPECT_EQ(m.pointCount, 4);
    double lowest = std::numeric_limits<double>::infinity();
    for (const Vec3& p : points) lowest = std::min(lowest, (xf.position + xf.orientation * p).y());
    EXPECT_NEAR(deepest(m), lowest, kTol);
}

TEST(Collide, BoxOnPlaneFaceAndEdge) {
    const Shape ground = plane(Vec3::UnitY(), 0.0);
    const Shape cube = box(Vec3(0.5, 0.5, 0.5));
    const Manifold flat = one(cube, at(Vec3(0, 0.49, 0)), ground, at(Vec3::Zero()));
    EXPECT_EQ(flat.pointCount, 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(flat.points[i].separation, -0.01, kTol);

    // On an edge (45 degrees about z): the two vertices of the lowest edge.
    const Manifold edge = one(cube, at(Vec3(0, 0.5 * kSqrt2 - 0.02, 0), rotation(std::numbers::pi / 4, Vec3::UnitZ())), ground,
                              at(Vec3::Zero()));
    expectPoints(edge, {Vec3(0, -0.01, -0.5), Vec3(0, -0.01, 0.5)});
}

// ---------------------------------------------------------------- boxes

TEST(Collide, BoxRestingOnBoxFaceToFaceGivesFourPoints) {
    // b (half 0.5) sinks 0.02 into the top of a (half 1): the reference face is a's top.
    const Manifold m = one(box(Vec3(1, 1, 1)), at(Vec3::Zero()), box(Vec3(0.5, 0.5, 0.5)), at(Vec3(0.2, 1.48, -0.1)));
    expectWellFormed(m);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol));
    for (int i = 0; i < m.pointCount; ++i) EXPECT_NEAR(m.points[i].separation, -0.02, kTol);
    expectPoints(m, {Vec3(-0.3, 0.99, -0.6), Vec3(0.7, 0.99, -0.6), Vec3(-0.3, 0.99, 0.4), Vec3(0.7, 0.99, 0.4)});

    // A larger box on a smaller one: its bottom face is clipped to the small top face.
    const Manifold big = one(box(Vec3(0.5, 0.5, 0.5)), at(Vec3::Zero()), box(Vec3(2, 0.5, 2)), at(Vec3(0, 0.99, 0)));
    expectPoints(big, {Vec3(-0.5, 0.495, -0.5), Vec3(0.5, 0.495, -0.5), Vec3(-0.5, 0.495, 0.5), Vec3(0.5, 0.495, 0.5)});
}

TEST(Collide, BoxAcrossTwoBoxesTakesNoPointBesideTheFaceItRestsOn) {
    // A pyramid row: b (half 0.5) straddles the edge of a's top face at x = 0.5, half over a, and
    // is turned a little so that its corner beside a (at x = 1, over a's neighbour in a pyramid)
    // is its deepest. That corner is outside a whatever its height: a point there held b up by
    // a's plane extended and twisted a about its edge. The turn is small enough that a's face
    // stays the reference (b's beats it by less than the axis bias), where the corner came in.
    // Every point must lie over the overlap of the two faces: from b's lower left corner to a's
    // edge (1e-9: rounding of the clip).
    const double turn = -4e-4, centreY = 0.9995;
    const double leftCorner = 0.5 - 0.5 * std::cos(turn) + 0.5 * std::sin(turn);
    for (const bool hulls : {false, true}) {
        const Shape a = hulls ? boxHull(Vec3(0.5, 0.5, 0.5)) : box(Vec3(0.5, 0.5, 0.5));
        const Shape b = hulls ? boxHull(Vec3(0.5, 0.5, 0.5)) : box(Vec3(0.5, 0.5, 0.5));
        const Manifold m = one(a, at(Vec3::Zero()), b, at(Vec3(0.5, centreY, 0), rotation(turn, Vec3::UnitZ())));
        expectWellFormed(m);
        EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol)) << "a's top face is the reference";
        for (int i = 0; i < m.pointCount; ++i) {
            EXPECT_GE(m.points[i].point.x(), leftCorner - 1e-9) << (hulls ? "hulls" : "boxes") << ", point " << i;
            EXPECT_LE(m.points[i].point.x(), 0.5 + 1e-9) << (hulls ? "hulls" : "boxes") << ", point " << i;
        }
        // The overlap is deepest at a's edge (x = 0.5, under b's centre), where b's bottom face
        // lies 0.5 / cos(turn) below b's centre.
        EXPECT_NEAR(deepest(m), centreY - 0.5 / std::cos(turn) - 0.5, kTol) << (hulls ? "hulls" : "boxes");
    }
}

TEST(Collide, HullWideningBelowItsFaceKeepsTheCornerInsideIt) {
    // The other side of the test above: a frustum (top half 0.5 at y = 0.5, bottom half 1 at
    // y = -0.5) widens below its top face, so a corner beside that face can be inside it. A flat
    // box lies on the top overhanging the +x edge, its far end dipped (turned 0.01 rad) so that
    // its corner at x = 0.52 is 5 cm down, where the frustum reaches x = 0.525: inside. The top
    // face stays the reference (the box's face beats it by less than the axis bias), the clip
    // stops at the edge 0.2 mm shallower, and the corner, a true contact, must be kept: the
    // deepest point is the corner's depth, exact up to rounding.
    const Shape frustum = convex({Vec3(-0.5, 0.5, -0.5), Vec3(0.5, 0.5, -0.5), Vec3(-0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5),
                                  Vec3(-1, -0.5, -1), Vec3(1, -0.5, -1), Vec3(-1, -0.5, 1), Vec3(1, -0.5, 1)});
    const Vec3 half(0.5, 0.05, 0.3);
    const Quat turn = rotation(-0.01, Vec3::UnitZ());
    const Vec3 corner(0.52, 0.45, 0.0);  // the dipped end's bottom edge, at z = 0 (its mid-point)
    const Vec3 centre = corner - turn * Vec3(half.x(), -half.y(), 0.0);
    ASSERT_LT(corner.x(), 0.5 + 0.5 * (0.5 - corner.y()));  // inside the frustum's side
    const Manifold m = one(frustum, at(Vec3::Zero()), boxHull(half), at(centre, turn));
    expectWellFormed(m);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol)) << "the frustum's top is the reference";
    EXPECT_NEAR(deepest(m), corner.y() - 0.5, kTol);
}

TEST(Collide, BoxTurnedOnBoxKeepsFourOfTheOctagon) {
    // Turned 45 degrees about y, b's bottom square meets a's top square in an octagon.
    const Manifold m = one(box(Vec3(1, 1, 1)), at(Vec3::Zero()), box(Vec3(1, 1, 1)),
                           at(Vec3(0, 1.97, 0), rotation(std::numbers::pi / 4, Vec3::UnitY())));
    expectWellFormed(m);
    EXPECT_EQ(m.pointCount, 4);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol));
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(m.points[i].separation, -0.03, kTol);
        const Vec3& p = m.points[i].point;
        EXPECT_LE(p.cwiseAbs().x(), 1 + kTol);
        EXPECT_LE(p.cwiseAbs().z(), 1 + kTol);
        EXPECT_LE(std::abs(p.x()) + std::abs(p.z()), kSqrt2 + kTol);
    }
    // Four of the octagon's corners spanning most of it: area of the kept quad > half the octagon's.
    const std::vector<Vec3> p = sortedPoints(m);
    double area = 0;
    std::vector<Vec3> ring = p;
    std::sort(ring.begin(), ring.end(), [](const Vec3& a, const Vec3& b) { return std::atan2(a.z(), a.x()) < std::atan2(b.z(), b.x()); });
    for (int i = 0; i < 4; ++i) area += 0.5 * (ring[i].x() * ring[(i + 1) % 4].z() - ring[(i + 1) % 4].x() * ring[i].z());
    const double octagon = 4.0 - 4 * 0.5 * std::pow(2 - kSqrt2, 2) / 2 * 2;  // square minus four corner triangles
    EXPECT_GT(std::abs(area), 0.5 * octagon);
}

TEST(Collide, CrossedEdgesGiveOnePointWithTheAnalyticDepth) {
    // a turned 45 degrees about z: its top is an edge along z at y = sqrt 2. b turned 45 degrees
    // about x: its bottom is an edge along x at y = yb - sqrt 2. Depth = 2 sqrt 2 - yb.
    const double depth = 0.1;
    const double yb = 2 * kSqrt2 - depth;
    const Shape cube = box(Vec3(1, 1, 1));
    const Manifold m = one(cube, at(Vec3::Zero(), rotation(std::numbers::pi / 4, Vec3::UnitZ())), cube,
                           at(Vec3(0, yb, 0), rotation(std::numbers::pi / 4, Vec3::UnitX())));
    expectWellFormed(m);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol)) << m.normal.transpose();
    EXPECT_NEAR(m.points[0].separation, -depth, kTol);
    EXPECT_TRUE(m.points[0].point.isApprox(Vec3(0, kSqrt2 - depth / 2, 0), kTol)) << m.points[0].point.transpose();

    // The same as hulls: the polyhedral routine finds the same edge pair.
    const Shape hull = boxHull(Vec3(1, 1, 1));
    const Manifold h = one(hull, at(Vec3::Zero(), rotation(std::numbers::pi / 4, Vec3::UnitZ())), hull,
                           at(Vec3(0, yb, 0), rotation(std::numbers::pi / 4, Vec3::UnitX())));
    ASSERT_EQ(h.pointCount, 1);
    EXPECT_TRUE(h.normal.isApprox(Vec3(0, 1, 0), kTol));
    EXPECT_NEAR(h.points[0].separation, -depth, kTol);
    EXPECT_TRUE(h.points[0].point.isApprox(Vec3(0, kSqrt2 - depth / 2, 0), kTol));
}

TEST(Collide, FeatureIdsStayPutUnderSmallMotion) {
    const Shape cube = box(Vec3(0.5, 0.5, 0.5));
    const Shape hull = boxHull(Vec3(0.5, 0.5, 0.5));
    const Quat tilt = rotation(0.3, Vec3::UnitY());
    for (const Shape* top : {&cube, &hull}) {
        const Manifold before = one(cube, at(Vec3::Zero()), *top, at(Vec3(0.3, 0.99, 0.1), tilt));
        const Manifold after = one(cube, at(Vec3::Zero()), *top, at(Vec3(0.3002, 0.9899, 0.0997), tilt * rotation(1e-4, Vec3::UnitY())));
        expectWellFormed(before);
        EXPECT_EQ(before.pointCount, 4);
        EXPECT_EQ(ids(before), ids(after));
    }
    // Parallel capsules and a capsule on a box keep their ids too.
    const Quat alongX = rotation(-std::numbers::pi / 2, Vec3::UnitZ());
    const Shape c = capsule(0.2, 1.0);
    EXPECT_EQ(ids(one(c, at(Vec3::Zero(), alongX), c, at(Vec3(0.5, 0.39, 0), alongX))),
              ids(one(c, at(Vec3::Zero(), alongX), c, at(Vec3(0.5001, 0.3899, 0.0001), alongX))));
    EXPECT_EQ(ids(one(c, at(Vec3(0.1, 0.69, 0), alongX), cube, at(Vec3::Zero()))),
              ids(one(c, at(Vec3(0.1001, 0.6899, 0), alongX), cube, at(Vec3::Zero()))));
    // Ids carry over from a speculative (apart) manifold to the touching one.
    const Manifold apart = one(cube, at(Vec3::Zero()), cube, at(Vec3(0.3, 1.02, 0.1), tilt), 0.05);
    const Manifold touching = one(cube, at(Vec3::Zero()), cube, at(Vec3(0.3, 0.99, 0.1), tilt), 0.05);
    EXPECT_EQ(apart.pointCount, 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(apart.points[i].separation, 0.02, kTol);
    EXPECT_EQ(ids(apart), ids(touching));
    // Distinct features give distinct ids: a box turned over lands on other faces.
    const Manifold other = one(cube, at(Vec3::Zero()), cube, at(Vec3(0.3, 0.99, 0.1), rotation(std::numbers::pi / 2, Vec3::UnitX())));
    const Manifold same = one(cube, at(Vec3::Zero()), cube, at(Vec3(0.3, 0.99, 0.1)));
    EXPECT_NE(ids(other), ids(same));
}

TEST(Collide, SphereAgainstBoxFaceEdgeCornerAndInside) {
    const Shape cube = box(Vec3(1, 1, 1));
    const Manifold face = one(sphere(0.5), at(Vec3(0.3, 1.4, 0)), cube, at(Vec3::Zero()));
    EXPECT_TRUE(face.normal.isApprox(Vec3(0, -1, 0), kTol));
    EXPECT_NEAR(face.points[0].separation, -0.1, kTol);
    EXPECT_TRUE(face.points[0].point.isApprox(Vec3(0.3, 0.95, 0), kTol));

    const Vec3 diagonal = Vec3(1, 1, 1).normalized();
    const Manifold corner = one(cube, at(Vec3::Zero()), sphere(0.5), at(Vec3(1, 1, 1) + 0.4 * diagonal));
    EXPECT_TRUE(corner.normal.isApprox(diagonal, kTol));
    EXPECT_NEAR(corner.points[0].separation, -0.1, kTol);

    // Centre inside, nearest the +x face 0.2 away: out through +x, depth 0.2 + radius.
    const Manifold inside = one(cube, at(Vec3::Zero()), sphere(0.5), at(Vec3(0.8, 0.1, -0.3)));
    EXPECT_TRUE(inside.normal.isApprox(Vec3(1, 0, 0), kTol));
    EXPECT_NEAR(inside.points[0].separation, -0.7, kTol);

    // Rotated box: the same answers in its frame.
    const Quat q = rotation(0.7, Vec3(1, -2, 0.5));
    const Manifold turned = one(sphere(0.5), at(Vec3(2, 3, 4) + q * Vec3(0.3, 1.4, 0)), cube, at(Vec3(2, 3, 4), q));
    EXPECT_TRUE(turned.normal.isApprox(q * Vec3(0, -1, 0), kTol));
    EXPECT_NEAR(turned.points[0].separation, -0.1, kTol);
}

TEST(Collide, CapsuleOnBoxLyingStandingAndSunk) {
    const Shape cube = box(Vec3(1, 0.5, 1));
    const Quat alongX = rotation(-std::numbers::pi / 2, Vec3::UnitZ());
    // Lying on the top face (0.01 deep), longer than the face: clipped at the face's sides.
    const Manifold lying = one(capsule(0.2, 1.5), at(Vec3(0.2, 0.69, 0.3), alongX), cube, at(Vec3::Zero()));
    expectWellFormed(lying);
    EXPECT_TRUE(lying.normal.isApprox(Vec3(0, -1, 0), kTol));
    expectPoints(lying, {Vec3(-1, 0.495, 0.3), Vec3(1, 0.495, 0.3)});
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(lying.points[i].separation, -0.01, kTol);

    // Standing: only the lower end touches.
    const Manifold standing = one(capsule(0.2, 1.5), at(Vec3(0.2, 2.19, 0.3)), cube, at(Vec3::Zero()));
    ASSERT_EQ(standing.pointCount, 1);
    EXPECT_NEAR(standing.points[0].separation, -0.01, kTol);
    EXPECT_TRUE(standing.points[0].point.isApprox(Vec3(0.2, 0.495, 0.3), kTol));

    // Sunk: the core segment is inside the box (separating axes), 0.3 below the top face.
    const Manifold sunk = one(capsule(0.2, 0.5), at(Vec3(0.2, 0.2, 0.3), alongX), cube, at(Vec3::Zero()));
    EXPECT_TRUE(sunk.normal.isApprox(Vec3(0, -1, 0), kTol));
    ASSERT_EQ(sunk.pointCount, 2);
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(sunk.points[i].separation, -0.5, kTol);

    // Over a top edge of the box, apart: the closest points of the distance routine.
    const Manifold edge = one(cube, at(Vec3::Zero()), capsule(0.2, 0.5), at(Vec3(1.1, 0.6, 0), rotation(std::numbers::pi / 2, Vec3::UnitX())),
                              0.1);
    EXPECT_EQ(edge.pointCount, 1);
    EXPECT_TRUE(edge.normal.isApprox(Vec3(1, 1, 0).normalized(), kTol));
    EXPECT_NEAR(edge.points[0].separation, 0.1 * kSqrt2 - 0.2, kTol);
}

// ---------------------------------------------------------------- convex hulls

TEST(Collide, HullsAgreeWithBoxesAcrossRandomPoses) {
    // Independent routines (15-axis box SAT vs polyhedral SAT on hulls) must find the same depth
    // and normal; sphere and capsule against a box hull must match the exact box routines.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec3 halfA(0.6, 0.4, 0.8), halfB(0.5, 0.7, 0.3);
    const Shape boxA = box(halfA), boxB = box(halfB), hullA = boxHull(halfA), hullB = boxHull(halfB);
    int compared = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Transform xa = randomPose(u, rng, 0.2);
        const Transform xb = randomPose(u, rng, 1.2);
        const std::vector<Manifold> boxes = run(boxA, xa, boxB, xb, 0.05);
        const std::vector<Manifold> hulls = run(hullA, xa, hullB, xb, 0.05);
        const std::vector<Manifold> mixed = run(boxA, xa, hullB, xb, 0.05);
        ASSERT_EQ(boxes.size(), hulls.size()) << trial;
        ASSERT_EQ(boxes.size(), mixed.size()) << trial;
        if (boxes.empty()) continue;
        ++compared;
        expectWellFormed(boxes[0]);
        expectWellFormed(hulls[0]);
        // Contact depth is what the solver acts on; both take the minimum over the same axes.
        EXPECT_NEAR(deepest(boxes[0]), deepest(hulls[0]), 2e-3) << trial;
        EXPECT_NEAR(deepest(boxes[0]), deepest(mixed[0]), 2e-3) << trial;
        EXPECT_GT(boxes[0].normal.dot(hulls[0].normal), 0.99) << trial;

        const Shape ball = sphere(0.3);
        const std::vector<Manifold> sb = run(ball, xb, boxA, xa, 0.05), sh = run(ball, xb, hullA, xa, 0.05);
        ASSERT_EQ(sb.size(), sh.size()) << trial;
        if (!sb.empty()) {
            EXPECT_NEAR(sb[0].points[0].separation, sh[0].points[0].separation, 1e-9) << trial;
            EXPECT_TRUE(sb[0].normal.isApprox(sh[0].normal, 1e-6)) << trial;
        }
    }
    EXPECT_GT(compared, 100);
}

TEST(Collide, CapsuleDistanceMatchesSampling) {
    // While apart, the capsule's separation is the exact segment-to-box distance minus the radius:
    // compare with the sphere-box routine swept densely along the segment.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    const Shape target = boxHull(Vec3(0.5, 0.3, 0.4));
    const Shape targetBox = box(Vec3(0.5, 0.3, 0.4));
    int checked = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Transform xc = randomPose(u, rng, 1.5);
        const Shape c = capsule(0.1, 0.6);
        const std::vector<Manifold> got = run(c, xc, target, at(Vec3::Zero()), 0.5);
        double sampled = std::numeric_limits<double>::infinity();
        const Vec3 axis = xc.orientation * Vec3(0, 0.6, 0);
        for (int i = 0; i <= 4000; ++i) {
            const std::vector<Manifold> s = run(sphere(0.1), at(xc.position + (-1 + i / 2000.0) * axis), targetBox, at(Vec3::Zero()), 0.5);
            if (!s.empty()) sampled = std::min(sampled, s[0].points[0].separation);
        }
        if (sampled <= 0.0 || sampled >= 0.5) continue;  // only the separated, in-range cases
        ASSERT_EQ(got.size(), 1u) << trial;
        ++checked;
        EXPECT_NEAR(deepest(got[0]), sampled, 1e-4) << trial;
        EXPECT_LE(deepest(got[0]), sampled + 1e-9) << trial;
    }
    EXPECT_GT(checked, 20);
}

TEST(Collide, MovingBySeparationAlongTheNormalJustTouches) {
    // The reported depth is the minimum translation: moving b by -separation x normal leaves the
    // pair touching, neither apart nor overlapping. Exact for the closest-point routines; the
    // separating-axis routines may prefer a face up to kAxisBias (1e-3) x size (the radius of
    // the smaller polytope, < 1 m here) deeper than the best edge axis, hence 1e-3 m. While apart,
    // the distance routines are exact, so moving closer by the separation also touches.
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g;
    std::vector<Vec3> blob;
    for (int i = 0; i < 30; ++i) blob.push_back(drawVec3(g, rng).cwiseProduct(Vec3(1, 0.6, 1)).normalized() * 0.6);
    const Shape shapes[] = {sphere(0.4), capsule(0.25, 0.6), box(Vec3(0.5, 0.3, 0.7)), convex(blob)};
    for (const Shape& a : shapes)
        for (const Shape& b : shapes)
            for (int trial = 0; trial < 150; ++trial) {
                const Transform xa = randomPose(u, rng, 0.1);
                const Transform xb = randomPose(u, rng, 1.0);
                const std::vector<Manifold> before = run(a, xa, b, xb, 0.2);
                if (before.empty()) continue;
                const double d = deepest(before[0]);
                const std::vector<Manifold> after = run(a, xa, b, at(xb.position - d * before[0].normal, xb.orientation), 0.5);
                ASSERT_EQ(after.size(), 1u) << toString(a.type) << "-" << toString(b.type) << " trial " << trial;
                EXPECT_NEAR(deepest(after[0]), 0.0, 1e-3) << toString(a.type) << "-" << toString(b.type) << " trial " << trial;
            }
}

// A hull with an edge only one face walks (a vertex on an edge that one face's loop holds and its
// neighbour's skips: the API fuzzer built such a hull from nearly coplanar points, and the edge
// query read a face index of -1). The geometry is still the box's, so it must collide like it.
TEST(Collide, HullWithAnEdgeOneFaceWalksCollidesLikeItsClosedTwin) {
    const Vec3 half(0.5, 0.5, 0.5);
    HullData split = makeBoxHull(half);
    std::vector<int>& loop = split.faces[0];
    const int v0 = loop[0], v1 = loop[1];
    split.vertices.push_back((split.vertices[static_cast<std::size_t>(v0)] + split.vertices[static_cast<std::size_t>(v1)]) / 2);
    loop.insert(loop.begin() + 1, static_cast<int>(split.vertices.size()) - 1);  // face 0 only
    split.edges.clear();  // recomputed from the loops: three edges now have a face on one side only
    split.edgeFaces.clear();
    Shape tJunction;
    tJunction.type = ShapeType::Convex;
    tJunction.hull = std::make_shared<const HullData>(split);
    const Shape closed = boxHull(half), other = box(Vec3(0.3, 0.2, 0.4));

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    int touching = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Transform xa = at(Vec3::Zero(), drawTurn(u, rng, 3.0));
        const Transform xb = randomPose(u, rng, 0.9);
        const std::vector<Manifold> expected = run(closed, xa, other, xb, 0.05);
        const std::vector<Manifold> got = run(tJunction, xa, other, xb, 0.05);
        ASSERT_EQ(expected.size(), got.size()) << trial;
        if (expected.empty()) continue;
        ++touching;
        expectWellFormed(got[0]);
        // Same solid, same minimum over the same axes: the depth agrees to rounding, the normal
        // to the tolerance with which a face is preferred over a nearly equal edge axis.
        EXPECT_NEAR(deepest(expected[0]), deepest(got[0]), 1e-6) << trial;
        EXPECT_GT(expected[0].normal.dot(got[0].normal), 0.99) << trial;
    }
    EXPECT_GT(touching, 50);  // the poses must exercise the contact path, not only separation
}

TEST(Collide, ManySidedHullsLyingOnEachOtherKeepFourPointsOfTheirOverlap) {
    // Two 24-sided prisms, the upper one turned 7.5 degrees and sunk 0.01: their clipped faces
    // give more candidates than any fixed buffer holds (the per-thread scratch takes them).
    std::vector<Vec3> points;
    for (int i = 0; i < 24; ++i) {
        const double a = 2 * std::numbers::pi * i / 24;
        points.emplace_back(0.5 * std::cos(a), -0.25, 0.5 * std::sin(a));
        points.emplace_back(0.5 * std::cos(a), 0.25, 0.5 * std::sin(a));
    }
    const Shape prism = convex(points);
    ASSERT_EQ(prism.hull->faces.size(), 26u);
    const Manifold m = one(prism, at(Vec3(0.1, 0.49, 0)), prism, at(Vec3::Zero(), rotation(std::numbers::pi / 24, Vec3::UnitY())));
    expectWellFormed(m);
    ASSERT_EQ(m.pointCount, 4);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, -1, 0), kTol));
    for (int i = 0; i < 4; ++i) {
        const Vec3& p = m.points[i].point;
        EXPECT_NEAR(m.points[i].separation, -0.01, kTol);
        EXPECT_NEAR(p.y(), 0.245, kTol);
        EXPECT_LE(std::hypot(p.x(), p.z()), 0.5 + kTol);          // over the lower face
        EXPECT_LE(std::hypot(p.x() - 0.1, p.z()), 0.5 + kTol);    // and under the upper one
    }
    // Spread over the overlap: the kept quad covers most of it (two discs 0.1 apart, about 0.66).
    const std::vector<Vec3> p = sortedPoints(m);
    std::vector<Vec3> ring = p;
    std::sort(ring.begin(), ring.end(), [](const Vec3& a, const Vec3& b) {
        return std::atan2(a.z(), a.x() - 0.05) < std::atan2(b.z(), b.x() - 0.05);
    });
    double area = 0;
    for (int i = 0; i < 4; ++i) area += 0.5 * (ring[i].x() * ring[(i + 1) % 4].z() - ring[(i + 1) % 4].x() * ring[i].z());
    EXPECT_GT(std::abs(area), 0.4);
}

TEST(Collide, TetrahedronTipIntoABoxFace) {
    // Apex down at y = -0.05 into the box top at y = 0: one point, depth 0.05.
    const Shape tetra = convex({Vec3(0, -0.5, 0), Vec3(-0.5, 0.5, -0.5), Vec3(0.5, 0.5, -0.5), Vec3(0, 0.5, 0.6)});
    const Manifold m = one(box(Vec3(1, 0.5, 1)), at(Vec3(0, -0.5, 0)), tetra, at(Vec3(0.1, 0.45, 0.2)));
    expectWellFormed(m);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol));
    EXPECT_NEAR(m.points[0].separation, -0.05, kTol);
    EXPECT_TRUE(m.points[0].point.isApprox(Vec3(0.1, -0.025, 0.2), kTol));
}

TEST(Collide, SphereInsideAHullLeavesThroughTheNearestFace) {
    const Shape hull = boxHull(Vec3(1, 1, 1));
    const Manifold m = one(sphere(0.5), at(Vec3(0.1, -0.8, 0.2)), hull, at(Vec3::Zero()));
    EXPECT_TRUE(m.normal.isApprox(Vec3(0, 1, 0), kTol)) << "the sphere leaves through -y: normal from it into the hull";
    EXPECT_NEAR(m.points[0].separation, -0.7, kTol);
}

// A point of two overlapping shapes lies in both (collide.cpp, keepDeepPointsInBothBounds). A
// 0.1 m box swallowed by a large one, turned or not, in either order: midway between the surfaces
// lay half the large box away (4.7 m at half extent 10, 5e6 m at 1e7), a friction arm of that
// length. Each point must lie within the small box's bounds grown by the 1 cm clamp margin; the
// depth keeps the true overlap, the distance to the nearest outer face.
TEST(Collide, PointsOfASwallowedBoxLieWithinIt) {
    const Quat turned(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
    for (const double half : {10.0, 1e3, 1e7})
        for (const Quat& q : {Quat::Identity(), turned})
            for (const bool smallFirst : {true, false}) {
                SCOPED_TRACE("outer half extent " + std::to_string(half) + (smallFirst ? ", small box first" : ", large box first"));
                const Shape small = box(Vec3::Constant(0.05)), large = box(Vec3::Constant(half));
                const Transform smallPose = at(Vec3(0.3, 0.2, 0), q), largePose = at(Vec3::Zero());
                const Manifold m = smallFirst ? one(small, smallPose, large, largePose) : one(large, largePose, small, smallPose);
                ASSERT_GT(m.pointCount, 0);
                // The small box's bounds: its centre +- the extent of its turned corners, plus 1 cm.
                const Vec3 reach = q.toRotationMatrix().cwiseAbs() * Vec3::Constant(0.05) + Vec3::Constant(0.01);
                for (int i = 0; i < m.pointCount; ++i) {
                    const Vec3 off = (m.points[i].point - smallPose.position).cwiseAbs();
                    EXPECT_TRUE((off.array() <= reach.array() + 1e-9).all()) << "point " << m.points[i].point.transpose();
                    EXPECT_LT(m.points[i].separation, -(half - 0.4));  // through the nearest face, +x
                }
            }
}

TEST(Collide, NormalsPointFromAToBWhateverTheOrder) {
    const Shape shapes[] = {sphere(0.4), capsule(0.3, 0.5), box(Vec3(0.4, 0.3, 0.5)), convex({Vec3(-0.4, -0.4, -0.4), Vec3(0.5, -0.4, -0.3),
                                                                                           Vec3(0, 0.5, 0), Vec3(0, -0.3, 0.5), Vec3(0.1, 0.1, -0.5)})};
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-1, 1);
    int pairs = 0;
    for (const Shape& a : shapes)
        for (const Shape& b : shapes)
            for (int trial = 0; trial < 20; ++trial) {
                const Transform xa = randomPose(u, rng, 0.1);
                const Vec3 pb = 0.8 * drawVec3(u, rng).normalized();
                const Transform xb = at(pb, drawTurn(u, rng, 3.0));
                const std::vector<Manifold> ab = run(a, xa, b, xb, 0.1), ba = run(b, xb, a, xa, 0.1);
                ASSERT_EQ(ab.size(), ba.size());
                if (ab.empty()) continue;
                ++pairs;
                expectWellFormed(ab[0]);
                // Shapes around the origin vs shapes 0.8 away: b lies on the side the normal points to.
                EXPECT_GT(ab[0].normal.dot(xb.position - xa.position), 0) << toString(a.type) << "-" << toString(b.type);
                EXPECT_GT(ba[0].normal.dot(xa.position - xb.position), 0) << toString(b.type) << "-" << toString(a.type);
                if (a.type != b.type) {  // one routine, called both ways: exactly opposite
                    EXPECT_TRUE(ab[0].normal.isApprox(-ba[0].normal, 1e-12));
                    EXPECT_EQ(ab[0].pointCount, ba[0].pointCount);
                    EXPECT_NEAR(deepest(ab[0]), deepest(ba[0]), 1e-12);
                }
            }
    EXPECT_GT(pairs, 100);
}

// ---------------------------------------------------------------- meshes

// A 4 x 4 square floor at y = 0 from two triangles, seen from above.
Shape floorMesh() {
    return mesh({Vec3(-2, 0, -2), Vec3(2, 0, -2), Vec3(2, 0, 2), Vec3(-2, 0, 2)}, {0, 2, 1, 0, 3, 2});
}

TEST(Collide, MeshGivesOneManifoldPerTouchedFlatStretch) {
    const Shape ground = floorMesh();
    // A sphere well inside triangle 0 (x > z half): one manifold keyed 0.
    const std::vector<Manifold> s = run(sphere(0.5), at(Vec3(1, 0.45, -1)), ground, at(Vec3::Zero()));
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].key, 0u);
    EXPECT_TRUE(s[0].normal.isApprox(Vec3(0, -1, 0), kTol));
    EXPECT_NEAR(s[0].points[0].separation, -0.05, kTol);

    // A box over the diagonal touches both triangles: coplanar, their clipped parts are merged into
    // one manifold (one friction centre for the face), keyed by the lower triangle, its four corners.
    const std::vector<Manifold> b = run(box(Vec3(0.5, 0.5, 0.5)), at(Vec3(0, 0.49, 0)), ground, at(Vec3::Zero()));
    ASSERT_EQ(b.size(), 1u);
    expectWellFormed(b[0]);
    EXPECT_EQ(b[0].key, 0u);
    EXPECT_EQ(b[0].pointCount, 4);
    EXPECT_TRUE(b[0].normal.isApprox(Vec3(0, -1, 0), kTol));
    for (int i = 0; i < b[0].pointCount; ++i) EXPECT_NEAR(b[0].points[i].separation, -0.01, kTol);

    // A capsule lying on it gives two points; the mesh as shape a flips the normal.
    const std::vector<Manifold> c =
        run(ground, at(Vec3::Zero()), capsule(0.2, 0.5), at(Vec3(1.2, 0.19, -0.8), rotation(std::numbers::pi / 2, Vec3::UnitZ())));
    ASSERT_EQ(c.size(), 1u);
    EXPECT_TRUE(c[0].normal.isApprox(Vec3(0, 1, 0), kTol));
    EXPECT_EQ(c[0].pointCount, 2);

    // A hull resting on it: the same as the box.
    const std::vector<Manifold> h = run(boxHull(Vec3(0.5, 0.5, 0.5)), at(Vec3(1, 0.49, -1)), ground, at(Vec3::Zero()));
    ASSERT_EQ(h.size(), 1u);
    EXPECT_EQ(h[0].pointCount, 4);
    EXPECT_NEAR(deepest(h[0]), -0.01, kTol);
}

TEST(Collide, NoGhostBumpsAtInternalEdges) {
    // A box turned 45 degrees about y sits 0.01 deep on triangle 0, one face parallel to the
    // floor's diagonal seam and 0.005 past it. Alone, triangle 1 would push it sideways by 0.005
    // (its seam edge); the floor is flat there, so both triangles push it up by 0.01.
    const Shape ground = floorMesh();
    const double s = 0.495 / kSqrt2;
    const std::vector<Manifold> m =
        run(box(Vec3(0.5, 0.5, 0.5)), at(Vec3(s, 0.49, -s), rotation(std::numbers::pi / 4, Vec3::UnitY())), ground, at(Vec3::Zero()));
    ASSERT_EQ(m.size(), 1u);  // the two triangles' manifolds, coplanar, merged
    for (const Manifold& manifold : m) {
        expectWellFormed(manifold);
        EXPECT_TRUE(manifold.normal.isApprox(Vec3(0, -1, 0), kTol)) << "triangle " << manifold.key << ": " << manifold.normal.transpose();
        EXPECT_NEAR(deepest(manifold), -0.01, kTol);
    }

    // A convex ridge (a tent, faces at 45 degrees): on top of it the edge normal is real and kept.
    const Shape tent = mesh({Vec3(-1, 0, -1), Vec3(0, 1, -1), Vec3(0, 1, 1), Vec3(-1, 0, 1), Vec3(1, 0, -1), Vec3(1, 0, 1)},
                            {0, 2, 1, 0, 3, 2, 1, 2, 5, 1, 5, 4});
    const std::vector<Manifold> ridge = run(sphere(0.5), at(Vec3(0, 1.45, 0)), tent, at(Vec3::Zero()));
    ASSERT_FALSE(ridge.empty());
    for (const Manifold& manifold : ridge) {
        EXPECT_TRUE(manifold.normal.isApprox(Vec3(0, -1, 0), kTol)) << manifold.normal.transpose();
        EXPECT_NEAR(deepest(manifold), -0.05, kTol);
    }

    // An open boundary: beside a lone triangle's edge the sideways normal is real too.
    const Shape lone = mesh({Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0)}, {0, 1, 2});
    const std::vector<Manifold> side = run(sphere(0.5), at(Vec3(-0.45, 0.0, 0.5)), lone, at(Vec3::Zero()));
    ASSERT_EQ(side.size(), 1u);
    EXPECT_TRUE(side[0].normal.isApprox(Vec3(1, 0, 0), kTol)) << side[0].normal.transpose();
    EXPECT_NEAR(deepest(side[0]), -0.05, kTol);
}

TEST(Collide, FlatMeshFloorActsAsAPlane) {
    // A 6 x 6 grid of 0.5 m squares (72 triangles) at y = 0 against the plane y = 0: for any shape
    // over its middle, every manifold's normal is straight down and the deepest point matches.
    std::vector<Vec3> vertices;
    std::vector<std::uint32_t> indices;
    for (int i = 0; i <= 6; ++i)
        for (int j = 0; j <= 6; ++j) vertices.emplace_back(-1.5 + 0.5 * i, 0, -1.5 + 0.5 * j);
    for (std::uint32_t i = 0; i < 6; ++i)
        for (std::uint32_t j = 0; j < 6; ++j) {
            const std::uint32_t v = 7 * i + j;
            indices.insert(indices.end(), {v, v + 1, v + 8, v, v + 8, v + 7});
        }
    const Shape grid = mesh(vertices, indices);
    const Shape ground = plane(Vec3::UnitY(), 0.0);
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(-1, 1);
    const Shape shapes[] = {sphere(0.3), capsule(0.2, 0.4), box(Vec3(0.4, 0.2, 0.3)),
                            convex({Vec3(-0.3, -0.2, -0.3), Vec3(0.4, -0.25, -0.2), Vec3(0, 0.3, 0), Vec3(0, -0.2, 0.4),
                                    Vec3(0.1, 0.1, -0.4)})};
    int checked = 0;
    for (const Shape& shape : shapes)
        for (int trial = 0; trial < 200; ++trial) {
            const Vec3 pf = Vec3(0, 0.3, 0) + drawVec3(u, rng).cwiseProduct(Vec3(0.6, 0.1, 0.6));
            const Transform xf = at(pf, drawTurn(u, rng, 3.0));
            const std::vector<Manifold> onPlane = run(shape, xf, ground, at(Vec3::Zero()), 0.02);
            const std::vector<Manifold> onMesh = run(shape, xf, grid, at(Vec3::Zero()), 0.02);
            ASSERT_EQ(onPlane.empty(), onMesh.empty()) << toString(shape.type) << " trial " << trial;
            if (onPlane.empty()) continue;
            ++checked;
            double lowest = std::numeric_limits<double>::infinity();
            for (const Manifold& m : onMesh) {
                EXPECT_TRUE(m.normal.isApprox(Vec3(0, -1, 0), 1e-9)) << toString(shape.type) << " trial " << trial << ": "
                                                                     << m.normal.transpose();
                lowest = std::min(lowest, deepest(m));
            }
            EXPECT_NEAR(lowest, deepest(onPlane[0]), 1e-9) << toString(shape.type) << " trial " << trial;
        }
    EXPECT_GT(checked, 200);
}

TEST(Collide, DeeplySunkHullIsPushedOutOfTheMeshFront) {
    // Apex down: base at y = 0.3, apex at y = -0.6, centroid at 0.3 - 0.9 / 4 > 0 (in front). Its
    // top is nearer the back of the floor than its apex the front, yet the floor is one-sided:
    // the contact must push it up by the apex depth.
    const Shape spike = convex({Vec3(-0.5, 0.3, -0.4), Vec3(0.5, 0.3, -0.4), Vec3(0, 0.3, 0.6), Vec3(0, -0.6, 0)});
    const std::vector<Manifold> m = run(spike, at(Vec3(1, 0, -1)), floorMesh(), at(Vec3::Zero()));
    ASSERT_EQ(m.size(), 1u);
    EXPECT_TRUE(m[0].normal.isApprox(Vec3(0, -1, 0), kTol)) << m[0].normal.transpose();
    EXPECT_NEAR(deepest(m[0]), -0.6, kTol);
}

TEST(Collide, MeshIsOneSidedAndPlacedByItsPose) {
    const Shape ground = floorMesh();
    // Just below the floor: behind every triangle, so nothing.
    EXPECT_TRUE(run(sphere(0.5), at(Vec3(1, -0.45, -1)), ground, at(Vec3::Zero())).empty());
    // The mesh moved up by 1 and turned upside down: now the sphere below is in front of it.
    const std::vector<Manifold> m = run(sphere(0.5), at(Vec3(1, 0.55, 1)), ground, at(Vec3(0, 1, 0), rotation(std::numbers::pi, Vec3::UnitX())));
    ASSERT_EQ(m.size(), 1u);
    EXPECT_TRUE(m[0].normal.isApprox(Vec3(0, 1, 0), kTol));
    EXPECT_NEAR(m[0].points[0].separation, -0.05, kTol);
    // Beyond the speculative distance: nothing; within it: a speculative point.
    EXPECT_TRUE(run(sphere(0.5), at(Vec3(1, 0.55, -1)), ground, at(Vec3::Zero()), 0.04).empty());
    EXPECT_EQ(run(sphere(0.5), at(Vec3(1, 0.55, -1)), ground, at(Vec3::Zero()), 0.06).size(), 1u);
}

// ---------------------------------------------------------------- building blocks

TEST(Collide, ReductionKeepsTheDeepestAndTheLargestArea) {
    ManifoldBuilder builder(Vec3::UnitY());
    // Eight points on a circle, the deepest at angle 3; then points near the centre.
    for (int i = 0; i < 8; ++i) {
        const double a = std::numbers::pi / 4 * i;
        builder.add(Vec3(std::cos(a), 0, std::sin(a)), i == 3 ? -0.2 : -0.1, static_cast<std::uint32_t>(i));
    }
    builder.add(Vec3(0.1, 0, 0.1), -0.15, 100);
    Manifold m;
    ASSERT_TRUE(builder.finish(m));
    ASSERT_EQ(m.pointCount, 4);
    EXPECT_TRUE(ids(m).count(3));
    EXPECT_FALSE(ids(m).count(100));
    // The quad of alternate circle points (area 2) is the best one containing point 3.
    EXPECT_EQ(ids(m), (std::set<std::uint32_t>{1, 3, 5, 7}));
}

TEST(Collide, DistanceRoutineOnSimpleSets) {
    const std::vector<Vec3> cube = [] {
        std::vector<Vec3> c;
        for (int i = 0; i < 8; ++i) c.emplace_back((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
        return c;
    }();
    const Vec3 point(3, 2, 0.5);
    const ConvexCore cubeCore = ConvexCore::points(cube);
    const GjkResult toFace = gjkFromFirstVertices(ConvexCore::points({&point, 1}), cubeCore);
    EXPECT_NEAR(toFace.distance, std::sqrt(4.0 + 1.0), 1e-12);  // to the edge x = y = 1
    EXPECT_TRUE(toFace.pointB.isApprox(Vec3(1, 1, 0.5), 1e-12));
    EXPECT_EQ(toFace.featureB.size(), 2);

    const std::vector<Vec3> segment{Vec3(-5, 3, 0), Vec3(5, 3, 0)};
    EXPECT_NEAR(gjkFromFirstVertices(ConvexCore::points(segment), cubeCore).distance, 2.0, 1e-12);
    const std::vector<Vec3> through{Vec3(-5, 0.5, 0), Vec3(5, 0.5, 0)};
    EXPECT_EQ(gjkFromFirstVertices(ConvexCore::points(through), cubeCore).distance, 0.0);
}

}  // namespace
}  // namespace anyphys::native
