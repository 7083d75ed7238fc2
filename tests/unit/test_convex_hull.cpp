// Convex hulls: topology (only hull vertices, coplanar triangles merged, outward CCW faces) and
// mass properties checked against closed-form values.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "../../api/src/geometry/convex_hull.hpp"
#include "../random_draws.hpp"
#include "anyphys/error.hpp"

using namespace anyphys;
using anyphys::test::drawUnitQuat;
using anyphys::test::drawVec3;

namespace {

// Rounding only: every expected value below is exact or a short closed form.
constexpr double kTol = 1e-12;

std::vector<Vec3> cubeCorners(double half) {
    std::vector<Vec3> p;
    for (int i = 0; i < 8; ++i) p.emplace_back((i & 1) ? half : -half, (i & 2) ? half : -half, (i & 4) ? half : -half);
    return p;
}

// Structural invariants every hull must satisfy: unit normals, CCW loops seen from outside,
// vertices on their face planes, all input points inside every face plane, each edge shared by
// exactly two faces in opposite directions, Euler's formula.
void expectValidHull(const HullData& h, const std::vector<Vec3>& input, double tol) {
    ASSERT_EQ(h.faces.size(), h.faceNormals.size());
    ASSERT_EQ(h.faces.size(), h.faceOffsets.size());
    std::set<std::pair<int, int>> directed;
    for (std::size_t f = 0; f < h.faces.size(); ++f) {
        const std::vector<int>& loop = h.faces[f];
        ASSERT_GE(loop.size(), 3u);
        const Vec3& n = h.faceNormals[f];
        EXPECT_NEAR(n.norm(), 1.0, kTol);
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const Vec3& a = h.vertices[loop[i]];
            const Vec3& b = h.vertices[loop[(i + 1) % loop.size()]];
            const Vec3& c = h.vertices[loop[(i + 2) % loop.size()]];
            EXPECT_NEAR(n.dot(a), h.faceOffsets[f], tol) << "vertex off its face plane";
            EXPECT_GT((b - a).cross(c - b).dot(n), 0.0) << "face " << f << " not convex counter-clockwise at " << i;
            EXPECT_TRUE(directed.insert({loop[i], loop[(i + 1) % loop.size()]}).second) << "edge used twice in one direction";
        }
        for (const Vec3& q : input) EXPECT_LE(n.dot(q) - h.faceOffsets[f], tol) << "input point outside face " << f;
    }
    for (const auto& [a, b] : directed) EXPECT_TRUE(directed.count({b, a})) << "edge " << a << "-" << b << " has one face";
    const long v = static_cast<long>(h.vertices.size()), e = static_cast<long>(directed.size() / 2),
               f = static_cast<long>(h.faces.size());
    EXPECT_EQ(v - e + f, 2) << "Euler characteristic";
}

TEST(ConvexHull, CubeFromCornersInteriorAndDuplicatePoints) {
    std::vector<Vec3> points = cubeCorners(1.0);
    points.push_back(Vec3(1, 1, 1));          // duplicate corner
    points.push_back(Vec3(-1, -1, -1));       // duplicate corner
    points.push_back(Vec3(0.2, -0.3, 0.5));   // interior
    points.push_back(Vec3::Zero());           // interior
    points.push_back(Vec3(1, 0.3, -0.2));     // on a face
    points.push_back(Vec3(1, 1, 0.4));        // on an edge
    const auto hull = buildConvexHull(points);

    EXPECT_EQ(hull->vertices.size(), 8u);
    EXPECT_EQ(hull->faces.size(), 6u);
    for (const auto& face : hull->faces) EXPECT_EQ(face.size(), 4u);
    for (const Vec3& v : hull->vertices) EXPECT_NEAR(v.cwiseAbs().minCoeff(), 1.0, 0.0) << "only corners are vertices";
    for (std::size_t f = 0; f < hull->faces.size(); ++f) {
        EXPECT_NEAR(hull->faceNormals[f].cwiseAbs().maxCoeff(), 1.0, kTol);
        EXPECT_NEAR(hull->faceOffsets[f], 1.0, kTol);
    }
    expectValidHull(*hull, points, kTol);

    EXPECT_NEAR(hull->volume, 8.0, kTol);
    EXPECT_LT(hull->centroid.norm(), kTol);
    // A 2 m cube: I = m (a^2 + b^2) / 12 = m (4 + 4) / 12 = 2/3 m about each axis.
    EXPECT_TRUE(hull->inertiaPerMass.isApprox(Mat3::Identity() * (2.0 / 3.0), kTol)) << hull->inertiaPerMass;
}

TEST(ConvexHull, GridsOfCoplanarPointsOnEveryFaceStillGiveSixQuads) {
    // 5 x 5 points on each face of a 2 x 4 x 6 box: edge points and face-interior points must
    // not remain as vertices.
    const Vec3 half(1, 2, 3);
    std::vector<Vec3> points;
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0})
            for (int i = 0; i <= 4; ++i)
                for (int j = 0; j <= 4; ++j) {
                    Vec3 unit;
                    unit[axis] = side;
                    unit[(axis + 1) % 3] = -1.0 + 0.5 * i;
                    unit[(axis + 2) % 3] = -1.0 + 0.5 * j;
                    points.push_back(unit.cwiseProduct(half));
                }
    const auto hull = buildConvexHull(points);
    EXPECT_EQ(hull->vertices.size(), 8u);
    EXPECT_EQ(hull->faces.size(), 6u);
    expectValidHull(*hull, points, kTol);
    EXPECT_NEAR(hull->volume, 48.0, 1e-11);
    // Box of sides a, b, c: I_x = (b^2 + c^2) / 12 per unit mass.
    const Vec3 expected((16.0 + 36.0) / 12.0, (4.0 + 36.0) / 12.0, (4.0 + 16.0) / 12.0);
    EXPECT_TRUE(hull->inertiaPerMass.isApprox(Mat3(expected.asDiagonal()), 1e-12)) << hull->inertiaPerMass;
}

TEST(ConvexHull, TetrahedronVolumeCentroidAndInertia) {
    const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    const auto hull = buildConvexHull(points);
    EXPECT_EQ(hull->vertices.size(), 4u);
    EXPECT_EQ(hull->faces.size(), 4u);
    expectValidHull(*hull, points, kTol);
    EXPECT_NEAR(hull->volume, 1.0 / 6.0, kTol);
    EXPECT_TRUE(hull->centroid.isApprox(Vec3::Constant(0.25), kTol));
    // Per unit mass: <x^2> = 1/10, <xy> = 1/20 about the origin; about the centroid
    // var = 1/10 - 1/16 = 3/80 and cov = 1/20 - 1/16 = -1/80. So I_xx = 2 var, I_xy = -cov.
    Mat3 expected;
    expected << 6.0 / 80, 1.0 / 80, 1.0 / 80, 1.0 / 80, 6.0 / 80, 1.0 / 80, 1.0 / 80, 1.0 / 80, 6.0 / 80;
    EXPECT_TRUE(hull->inertiaPerMass.isApprox(expected, kTol)) << hull->inertiaPerMass;
}

TEST(ConvexHull, PrismMergesItsNonAxisAlignedSides) {
    // A hexagonal prism from trigonometric points: the merge must absorb rounding.
    const int sides = 6;
    const double r = 0.7, h = 0.4;
    std::vector<Vec3> points;
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * std::numbers::pi * i / sides + 0.3;
        points.emplace_back(r * std::cos(a), -h, r * std::sin(a));
        points.emplace_back(r * std::cos(a), h, r * std::sin(a));
        points.emplace_back(0.5 * r * std::cos(a), 0.1, 0.5 * r * std::sin(a));  // interior
    }
    const auto hull = buildConvexHull(points);
    EXPECT_EQ(hull->vertices.size(), 12u);
    EXPECT_EQ(hull->faces.size(), 8u);
    expectValidHull(*hull, points, 1e-12);
    const double area = 0.5 * sides * r * r * std::sin(2 * std::numbers::pi / sides);
    EXPECT_NEAR(hull->volume, area * 2 * h, 1e-12);
}

TEST(ConvexHull, PointsOnASphereAreAllVertices) {
    std::mt19937 rng(7);
    std::normal_distribution<double> gauss;
    std::vector<Vec3> points;
    for (int i = 0; i < 300; ++i) points.push_back(drawVec3(gauss, rng).normalized());
    const auto hull = buildConvexHull(points);
    EXPECT_EQ(hull->vertices.size(), points.size());
    expectValidHull(*hull, points, 1e-12);
    EXPECT_LT(hull->volume, 4.0 / 3.0 * std::numbers::pi);
    EXPECT_GT(hull->volume, 0.95 * 4.0 / 3.0 * std::numbers::pi);
    EXPECT_LT(hull->centroid.norm(), 0.05);
}

TEST(ConvexHull, RandomCloudContainsEveryInputPoint) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Vec3> points;
    for (int i = 0; i < 2000; ++i) points.push_back(drawVec3(u, rng).cwiseProduct(Vec3(1, 0.3, 2)));
    const auto hull = buildConvexHull(points);
    expectValidHull(*hull, points, 1e-12);
    for (const Vec3& v : hull->vertices)
        EXPECT_TRUE(std::any_of(points.begin(), points.end(), [&](const Vec3& p) { return p == v; }));
    EXPECT_LT(hull->volume, 2 * 0.6 * 4 + 1e-9);
    EXPECT_GT(hull->volume, 0.9 * 2 * 0.6 * 4);
}

TEST(ConvexHull, ResultDoesNotDependOnUnitOrPlacement) {
    // A millimetre cube a kilometre away: the relative tolerances still find six quads.
    const Quat q = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
    std::vector<Vec3> points;
    for (const Vec3& c : cubeCorners(1e-3)) points.push_back(Vec3(1e3, -2e3, 5e2) + q * c);
    points.push_back(Vec3(1e3, -2e3, 5e2));
    const auto hull = buildConvexHull(points);
    EXPECT_EQ(hull->vertices.size(), 8u);
    EXPECT_EQ(hull->faces.size(), 6u);
    EXPECT_NEAR(hull->volume, 8e-9, 1e-15);
    // Rotating a cube does not change its (isotropic) inertia: 2/3 (1e-3)^2 per unit mass.
    EXPECT_TRUE(hull->inertiaPerMass.isApprox(Mat3::Identity() * (2.0 / 3.0 * 1e-6), 1e-6)) << hull->inertiaPerMass;
}

TEST(ConvexHull, DegenerateInputThrows) {
    const std::vector<std::vector<Vec3>> cases{
        {},
        {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},                                // 3 points
        {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)},                 // one point
        {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(-3, -3, -3)},              // on a line
        {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.5, 0, 3)}  // on a plane
    };
    for (const auto& points : cases) {
        try {
            buildConvexHull(points);
            ADD_FAILURE() << "no error for " << points.size() << " degenerate points";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("must span a volume"), std::string::npos) << e.what();
        }
    }
}

TEST(ConvexHull, BoxHullMatchesTheHullOfItsCorners) {
    const Vec3 half(0.5, 1.0, 2.0);
    const HullData box = makeBoxHull(half);
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.push_back(box.vertices[i]);
    expectValidHull(box, corners, kTol);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(box.faceNormals[2 * k], Vec3::Unit(k));
        EXPECT_EQ(box.faceNormals[2 * k + 1], -Vec3::Unit(k));
    }
    const auto built = buildConvexHull(corners);
    EXPECT_NEAR(box.volume, built->volume, kTol);
    EXPECT_TRUE(box.inertiaPerMass.isApprox(built->inertiaPerMass, kTol));
    EXPECT_NEAR(box.volume, 8.0, kTol);
    EXPECT_NEAR(box.inertiaPerMass(0, 0), (4.0 + 16.0) / 12.0, kTol);  // (b^2 + c^2) / 12 with b = 2, c = 4
}

}  // namespace

// Point clouds whose coplanar and collinear points are jittered by 1e-4 to 1e-13 of their size,
// around the hull's own tolerances (1e-10 to build, 1e-9 to merge): integer grids, cubes with
// points on their faces, octagonal prisms with points along the cap edges.
std::vector<std::vector<Vec3>> nearlyDegenerateClouds(int count) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<std::vector<Vec3>> clouds;
    for (int trial = 0; trial < count; ++trial) {
        std::vector<Vec3> points;
        const double jitter = std::pow(10.0, -4 - (trial / 3) % 10);
        const auto shake = [&] { return jitter * u(rng); };
        if (trial % 3 == 0) {
            std::uniform_int_distribution<int> g(0, 3);
            for (int i = 0; i < 20; ++i) {
                const Vec3 gridPoint = drawVec3(g, rng);
                points.push_back(gridPoint + jitter * drawVec3(u, rng));
            }
        } else if (trial % 3 == 1) {
            points = cubeCorners(1);
            for (int i = 0; i < 30; ++i) {
                Vec3 q = drawVec3(u, rng);
                q[i % 3] = (i % 2 ? 1 : -1) * (1 + shake());
                points.push_back(q);
            }
        } else {
            const auto rim = [](int k, double y) {
                const double a = 2 * std::numbers::pi * k / 8;
                return Vec3(std::cos(a), y, std::sin(a));
            };
            for (int k = 0; k < 8; ++k) points.insert(points.end(), {rim(k, -1), rim(k, 1)});
            for (int i = 0; i < 10; ++i) {
                const int k = static_cast<int>((u(rng) + 1) * 4) % 8;
                const double t = (u(rng) + 1) / 2, y = u(rng) > 0 ? 1 : -1;
                points.push_back((1 - t) * rim(k, y) + t * rim(k + 1, y) + jitter * drawVec3(u, rng));
            }
        }
        clouds.push_back(std::move(points));
    }
    return clouds;
}

// Whether every edge is walked once each way (and then whether Euler's formula holds).
bool pairsEveryEdge(const HullData& h) {
    std::set<std::pair<int, int>> directed;
    for (const std::vector<int>& loop : h.faces)
        for (std::size_t i = 0; i < loop.size(); ++i)
            if (!directed.insert({loop[i], loop[(i + 1) % loop.size()]}).second) return false;
    for (const auto& [a, b] : directed)
        if (!directed.count({b, a})) return false;
    const long v = static_cast<long>(h.vertices.size()), e = static_cast<long>(directed.size() / 2),
               f = static_cast<long>(h.faces.size());
    return v - e + f == 2 && h.edgeFaces.size() == h.edges.size();
}

// Hulls of nearly degenerate clouds: how many pair every edge, and how many have a face some
// input point lies more than 1e-6 of the cloud's size outside of.
struct HullCensus {
    int hulls = 0, unpaired = 0, pointsOutside = 0;
};
HullCensus census(const std::vector<std::vector<Vec3>>& clouds) {
    HullCensus c;
    for (const std::vector<Vec3>& points : clouds) {
        std::shared_ptr<const HullData> hull;
        try {
            hull = buildConvexHull(points);
        } catch (const Error&) {
            continue;  // too flat at this jitter: refused, which is fine
        }
        ++c.hulls;
        c.unpaired += pairsEveryEdge(*hull) ? 0 : 1;
        double size = 0;
        for (const Vec3& q : points) size = std::max(size, (q - points.front()).norm());
        bool outside = false;
        for (std::size_t f = 0; f < hull->faces.size() && !outside; ++f)
            for (const Vec3& q : points)
                outside = outside || hull->faceNormals[f].dot(q) - hull->faceOffsets[f] > 1e-6 * size;
        c.pointsOutside += outside ? 1 : 0;
    }
    return c;
}

// Near the build tolerance quickhull could take a point within the tolerance of a face as a
// vertex and leave triangles folded over the face or a cone of them through the solid: 81 of
// these 3 000 hulls had input points up to the hull's size outside a face, 2 an edge with a face
// on one side only (185 before 9d9f08d). An unsound hull is now built again at a coarser
// tolerance: every hull pairs its edges and holds every point.
TEST(ConvexHull, NearlyDegenerateCloudsGiveSoundHulls) {
    const HullCensus c = census(nearlyDegenerateClouds(3000));
    std::cout << "  " << c.hulls << " hulls: " << c.pointsOutside << " with a point outside a face, " << c.unpaired
              << " with an unpaired edge\n";
    EXPECT_EQ(c.hulls, 3000);
    EXPECT_EQ(c.unpaired, 0);
    EXPECT_EQ(c.pointsOutside, 0);
}

// The same clouds turned by a random rotation (so their faces are no longer on the axes and the
// coordinates carry rounding of their own), at 1/100, 1 and 100 times the size, the last about
// 1 100 m from the origin: 157 of these 9 000 hulls were unsound before the rebuild.
TEST(ConvexHull, NearlyDegenerateCloudsTurnedScaledAndMovedGiveSoundHulls) {
    std::mt19937 rng(7);
    std::normal_distribution<double> gauss;
    std::vector<std::vector<Vec3>> clouds;
    for (int variant = 0; variant < 3; ++variant)
        for (std::vector<Vec3> points : nearlyDegenerateClouds(3000)) {
            const Quat turn = drawUnitQuat(gauss, rng);
            const double scale = std::pow(10.0, 2 * variant - 2);
            const Vec3 offset = variant == 2 ? Vec3(1000, -500, 30) : Vec3::Zero();
            for (Vec3& q : points) q = scale * (turn * q) + offset;
            clouds.push_back(std::move(points));
        }
    const HullCensus c = census(clouds);
    std::cout << "  " << c.hulls << " hulls: " << c.pointsOutside << " with a point outside a face, " << c.unpaired
              << " with an unpaired edge\n";
    EXPECT_EQ(c.hulls, 9000);
    EXPECT_EQ(c.unpaired, 0);
    EXPECT_EQ(c.pointsOutside, 0);
}
