// Native geometric queries against analytic answers: bounds, ray casts, GJK distance, overlap
// and time of impact. Tolerances: closed-form cases are exact up to rounding (1e-9); GJK on
// polytopes terminates on an exact vertex set, so it is held to 1e-9 too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "collision/mesh_data.hpp"
#include "collision/queries.hpp"
#include "native_test_shapes.hpp"
#include "../../random_draws.hpp"

namespace anyphys::native {
namespace {

using namespace anyphys::native::test;  // shapes and poses (native_test_shapes.hpp)
using anyphys::test::drawTurn;
using anyphys::test::drawUnitQuat;
using anyphys::test::drawVec3;

constexpr double kTol = 1e-9;
constexpr double kPi = std::numbers::pi;

// A cube hull built by hand (the quickhull lives elsewhere): 8 corners, 6 quads.
Shape hullCube(double h) {
    auto hull = std::make_shared<HullData>();
    for (int i = 0; i < 8; ++i) hull->vertices.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    // Corner index bits: 1 = +x, 2 = +y, 4 = +z. Each face counter-clockwise seen from outside.
    hull->faces = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
    hull->faceNormals = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
    hull->faceOffsets.assign(6, h);
    hull->volume = 8 * h * h * h;
    Shape s;
    s.type = ShapeType::Convex;
    s.hull = hull;
    return s;
}

// A square of side 2 * half on y = 0, facing +y.
Shape floorQuad(double half) {
    return mesh({Vec3(-half, 0, -half), Vec3(half, 0, -half), Vec3(half, 0, half), Vec3(-half, 0, half)},
                     {0, 2, 1, 0, 3, 2});
}

void expectVec(const Vec3& actual, const Vec3& expected, double tol = kTol) {
    EXPECT_LT((actual - expected).norm(), tol) << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

// ---------------------------------------------------------------------------------------------
// Bounds

TEST(Queries, AabbOfEachShape) {
    Aabb b = computeAabb(sphere(0.5), at(Vec3(1, 2, 3)));
    expectVec(b.min, Vec3(0.5, 1.5, 2.5));
    expectVec(b.max, Vec3(1.5, 2.5, 3.5));

    // Box rotated 45 degrees about z: x and y extents become h (cos + sin).
    b = computeAabb(box(Vec3(1, 1, 2)), at(Vec3::Zero(), rotation(kPi / 4, Vec3::UnitZ())));
    expectVec(b.max, Vec3(std::sqrt(2.0), std::sqrt(2.0), 2));
    expectVec(b.min, -b.max);

    // Capsule turned to lie along x.
    b = computeAabb(capsule(0.25, 1.0), at(Vec3(0, 1, 0), rotation(kPi / 2, Vec3::UnitZ())));
    expectVec(b.min, Vec3(-1.25, 0.75, -0.25));
    expectVec(b.max, Vec3(1.25, 1.25, 0.25));

    b = computeAabb(hullCube(0.5), at(Vec3(0, 0, 5), rotation(kPi / 4, Vec3::UnitY())));
    expectVec(b.max, Vec3(std::sqrt(0.5), 0.5, 5 + std::sqrt(0.5)));

    const Shape mesh = floorQuad(3.0);
    b = computeAabb(mesh, at(Vec3(0, -1, 0)));
    expectVec(b.min, Vec3(-3, -1, -3));
    expectVec(b.max, Vec3(3, -1, 3));
}

TEST(Queries, PlaneAabbIsLargeFiniteAndClippedAtTheSurface) {
    Aabb b = computeAabb(plane(Vec3::UnitY(), 2.0), Transform{});
    EXPECT_DOUBLE_EQ(b.max.y(), 2.0);
    EXPECT_TRUE(std::isfinite(b.min.y()));
    EXPECT_LE(b.min.y(), -1e5);
    EXPECT_GE(b.max.x(), 1e5);
    EXPECT_LE(b.min.z(), -1e5);
    // A tilted plane still bounds its whole solid side, and nothing is infinite.
    b = computeAabb(plane(Vec3(1, 1, 0), 0.0), Transform{});
    EXPECT_TRUE(b.min.allFinite() && b.max.allFinite());
    EXPECT_TRUE(b.contains({Vec3(-10, -10, 0), Vec3(-9, -9, 1)}));
}

// ---------------------------------------------------------------------------------------------
// Ray casts

TEST(Queries, RaySphere) {
    const Shape s = sphere(1.0);
    const Transform xf = at(Vec3(2, 0, 0));
    auto hit = raycast(s, xf, Vec3(-3, 0, 0), Vec3::UnitX(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 4.0, kTol);
    expectVec(hit->point, Vec3(1, 0, 0));
    expectVec(hit->normal, -Vec3::UnitX());
    // Oblique: a ray at height 0.6 enters at x = 2 - 0.8.
    hit = raycast(s, xf, Vec3(-3, 0.6, 0), Vec3::UnitX(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 4.2, kTol);
    expectVec(hit->normal, Vec3(-0.8, 0.6, 0));
    EXPECT_FALSE(raycast(s, xf, Vec3(-3, 1.01, 0), Vec3::UnitX(), 10.0));  // passes above
    EXPECT_FALSE(raycast(s, xf, Vec3(-3, 0, 0), Vec3::UnitX(), 3.9));      // too short
    EXPECT_FALSE(raycast(s, xf, Vec3(-3, 0, 0), -Vec3::UnitX(), 10.0));    // pointing away
    EXPECT_FALSE(raycast(s, xf, Vec3(2.5, 0, 0), Vec3::UnitX(), 10.0));    // starts inside
}

TEST(Queries, RayCapsule) {
    const Shape c = capsule(0.5, 1.0);
    // Side: the cylinder at x = -0.5.
    auto hit = raycast(c, Transform{}, Vec3(-5, 0.7, 0), Vec3::UnitX(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 4.5, kTol);
    expectVec(hit->normal, -Vec3::UnitX());
    // Cap: straight down onto the top hemisphere.
    hit = raycast(c, Transform{}, Vec3(0, 5, 0), -Vec3::UnitY(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 3.5, kTol);
    expectVec(hit->normal, Vec3::UnitY());
    // Cap, off axis: x = 0.3 meets the top sphere at y = 1 + 0.4.
    hit = raycast(c, Transform{}, Vec3(0.3, 5, 0), -Vec3::UnitY(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 3.6, kTol);
    expectVec(hit->normal, Vec3(0.6, 0.8, 0));
    // Lying along x at (0, 0, 3): a ray along +x hits the end cap at x = -1.5.
    const Transform lying = at(Vec3(0, 0, 3), rotation(kPi / 2, Vec3::UnitZ()));
    hit = raycast(c, lying, Vec3(-4, 0, 3), Vec3::UnitX(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 2.5, kTol);
    expectVec(hit->point, Vec3(-1.5, 0, 3));
    expectVec(hit->normal, -Vec3::UnitX());
    EXPECT_FALSE(raycast(c, Transform{}, Vec3(-5, 1.6, 0), Vec3::UnitX(), 10.0));  // above the cap
    EXPECT_FALSE(raycast(c, Transform{}, Vec3(0, 1.2, 0), Vec3::UnitX(), 10.0));   // inside the cap
    EXPECT_FALSE(raycast(c, Transform{}, Vec3(0, 0, 0), Vec3::UnitY(), 10.0));     // inside
}

TEST(Queries, RayBoxAndHullAgree) {
    const Shape b = box(Vec3(1, 2, 3));
    // Rotated 90 degrees about y: local z (half 3) lies along world x.
    const Transform xf = at(Vec3(10, 0, 0), rotation(kPi / 2, Vec3::UnitY()));
    auto hit = raycast(b, xf, Vec3::Zero(), Vec3::UnitX(), 20.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 7.0, kTol);
    expectVec(hit->point, Vec3(7, 0, 0));
    expectVec(hit->normal, -Vec3::UnitX());
    EXPECT_FALSE(raycast(b, xf, Vec3(0, 2.1, 0), Vec3::UnitX(), 20.0));
    EXPECT_FALSE(raycast(b, xf, Vec3(10, 0, 0), Vec3::UnitX(), 20.0));  // starts inside
    EXPECT_FALSE(raycast(b, xf, Vec3::Zero(), Vec3::UnitX(), 6.9));

    // Random rotations: a ray aimed along a face normal at the centre enters that face at
    // distance 5 - h; the hull cube and the box give the same hit.
    std::mt19937 rng(2);
    std::normal_distribution<double> gauss;
    const Shape cubeBox = box(Vec3::Constant(0.5));
    const Shape cubeHull = hullCube(0.5);
    for (int i = 0; i < 50; ++i) {
        const Quat q = drawUnitQuat(gauss, rng);
        const Transform pose = at(drawVec3(gauss, rng), q);
        const Vec3 faceNormal = q * Vec3::UnitY();
        const Vec3 origin = pose.position + 5.0 * faceNormal;
        for (const Shape* s : {&cubeBox, &cubeHull}) {
            hit = raycast(*s, pose, origin, -faceNormal, 10.0);
            ASSERT_TRUE(hit);
            EXPECT_NEAR(hit->distance, 4.5, kTol);
            expectVec(hit->normal, faceNormal);
        }
        // A ray through a random point gives the same answer for both.
        const Vec3 dir = drawVec3(gauss, rng).normalized();
        const Vec3 o = pose.position - 3.0 * dir + 0.4 * drawVec3(gauss, rng);
        const auto hb = raycast(cubeBox, pose, o, dir, 10.0);
        const auto hh = raycast(cubeHull, pose, o, dir, 10.0);
        ASSERT_EQ(hb.has_value(), hh.has_value());
        if (hb) {
            EXPECT_NEAR(hb->distance, hh->distance, kTol);
            expectVec(hb->normal, hh->normal);
        }
    }
    EXPECT_FALSE(raycast(cubeHull, Transform{}, Vec3(0.1, 0.2, 0.3), Vec3::UnitX(), 10.0));  // inside
}

TEST(Queries, RayPlane) {
    const Shape p = plane(Vec3::UnitY(), 1.0);
    auto hit = raycast(p, Transform{}, Vec3(3, 5, 0), -Vec3::UnitY(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 4.0, kTol);
    expectVec(hit->point, Vec3(3, 1, 0));
    expectVec(hit->normal, Vec3::UnitY());
    const Vec3 diagonal = Vec3(1, -1, 0).normalized();
    hit = raycast(p, Transform{}, Vec3(0, 3, 0), diagonal, 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 2.0 * std::sqrt(2.0), kTol);
    EXPECT_FALSE(raycast(p, Transform{}, Vec3(0, 3, 0), Vec3::UnitX(), 10.0));   // parallel
    EXPECT_FALSE(raycast(p, Transform{}, Vec3(0, 3, 0), Vec3::UnitY(), 10.0));   // away
    EXPECT_FALSE(raycast(p, Transform{}, Vec3(0, 0, 0), -Vec3::UnitY(), 10.0));  // starts below (inside)
}

TEST(Queries, RayMeshIsTwoSidedAndMatchesBruteForce) {
    const Shape quad = floorQuad(2.0);
    const Transform xf = at(Vec3(0, 1, 0));
    auto hit = raycast(quad, xf, Vec3(0.5, 4, 0.5), -Vec3::UnitY(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 3.0, kTol);
    expectVec(hit->point, Vec3(0.5, 1, 0.5));
    expectVec(hit->normal, Vec3::UnitY());
    hit = raycast(quad, xf, Vec3(0.5, -4, 0.5), Vec3::UnitY(), 10.0);  // from below: normal faces the ray
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 5.0, kTol);
    expectVec(hit->normal, -Vec3::UnitY());
    EXPECT_FALSE(raycast(quad, xf, Vec3(2.5, 4, 0), -Vec3::UnitY(), 10.0));  // beside it

    // A bumpy 20 x 20 grid: the BVH answer equals the nearest plane-crossing found by marching.
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> bump(-0.3, 0.3);
    std::vector<Vec3> vertices;
    std::vector<std::uint32_t> indices;
    constexpr int n = 20;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) vertices.emplace_back(i - n / 2.0, bump(rng), j - n / 2.0);
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = 0; j < n; ++j) {
            const std::uint32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
            indices.insert(indices.end(), {a, b, c, b, d, c});
        }
    const Shape grid = mesh(vertices, indices);
    // The grid's height under p, interpolated on the triangle (a, b, c) or (b, d, c) of its cell.
    auto surfaceY = [&](const Vec3& p) {
        const double gx = p.x() + n / 2.0, gz = p.z() + n / 2.0;
        const int i = static_cast<int>(std::floor(gx)), j = static_cast<int>(std::floor(gz));
        const double fx = gx - i, fz = gz - j;
        auto h = [&](int a, int b) { return vertices[static_cast<std::size_t>(a * (n + 1) + b)].y(); };
        return fx + fz <= 1.0 ? h(i, j) + fx * (h(i + 1, j) - h(i, j)) + fz * (h(i, j + 1) - h(i, j))
                              : h(i + 1, j + 1) + (1 - fx) * (h(i, j + 1) - h(i + 1, j + 1)) +
                                    (1 - fz) * (h(i + 1, j) - h(i + 1, j + 1));
    };
    std::uniform_real_distribution<double> xz(-8.0, 8.0);
    for (int r = 0; r < 100; ++r) {
        const double ox = xz(rng);
        const double oz = xz(rng);
        const Vec3 o(ox, 3.0, oz);
        const double dx = bump(rng);
        const double dz = bump(rng);
        const Vec3 d = Vec3(0.3 * dx, -1.0, 0.3 * dz).normalized();
        hit = raycast(grid, Transform{}, o, d, 10.0);
        ASSERT_TRUE(hit);
        // The hit lies on the surface, and the ray stays above the surface before it.
        EXPECT_NEAR(hit->point.y(), surfaceY(hit->point), 1e-9);
        EXPECT_LT(hit->normal.dot(d), 0.0);
        for (double t = 0.0; t < hit->distance - 1e-6; t += 0.01) {
            const Vec3 p = o + t * d;
            ASSERT_GE(p.y(), surfaceY(p) - 1e-9) << "ray " << r << " passes below the surface at t = " << t;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Distance (GJK)

TEST(Queries, DistanceSpheres) {
    const auto r = distance(sphere(0.5), at(Vec3::Zero()), sphere(0.25), at(Vec3(3, 0, 0)));
    EXPECT_NEAR(r.distance, 2.25, kTol);
    expectVec(r.pointA, Vec3(0.5, 0, 0));
    expectVec(r.pointB, Vec3(2.75, 0, 0));
    expectVec(r.normal, Vec3::UnitX());
    EXPECT_TRUE(overlap(sphere(0.5), at(Vec3::Zero()), sphere(0.5), at(Vec3(0.99, 0, 0))));
    EXPECT_FALSE(overlap(sphere(0.5), at(Vec3::Zero()), sphere(0.5), at(Vec3(1.01, 0, 0))));
}

TEST(Queries, DistanceBoxes) {
    const Shape unit = box(Vec3::Constant(1.0));  // 2 m cubes
    auto r = distance(unit, at(Vec3::Zero()), unit, at(Vec3(3, 0, 0)));
    EXPECT_NEAR(r.distance, 1.0, kTol);
    EXPECT_NEAR(r.pointA.x(), 1.0, kTol);
    EXPECT_NEAR(r.pointB.x(), 2.0, kTol);
    expectVec(r.normal, Vec3::UnitX());
    // B turned 45 degrees about z: its edge points at A.
    r = distance(unit, at(Vec3::Zero()), unit, at(Vec3(3, 0, 0), rotation(kPi / 4, Vec3::UnitZ())));
    EXPECT_NEAR(r.distance, 2.0 - std::sqrt(2.0), kTol);
    // B's corner points at A: its body diagonal along x.
    const Quat cornerFirst = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), -Vec3::UnitX());
    r = distance(unit, at(Vec3::Zero()), unit, at(Vec3(3, 0.1, 0.2), cornerFirst));
    EXPECT_NEAR(r.distance, 2.0 - std::sqrt(3.0), kTol);
    expectVec(r.pointB, Vec3(3 - std::sqrt(3.0), 0.1, 0.2));
    // Offset diagonally: corner to corner.
    r = distance(unit, at(Vec3::Zero()), unit, at(Vec3(3, 3, 3)));
    EXPECT_NEAR(r.distance, std::sqrt(3.0), kTol);
    // A rotated about an arbitrary axis, B's face 0.25 m beyond A's furthest corner along x.
    const Quat q = rotation(0.7, Vec3(1, 2, 3));
    const double reach = (q.toRotationMatrix().cwiseAbs() * Vec3::Ones()).x();
    r = distance(unit, at(Vec3::Zero(), q), box(Vec3(1, 5, 5)), at(Vec3(reach + 1.25, 0, 0)));
    EXPECT_NEAR(r.distance, 0.25, kTol);
    EXPECT_TRUE(overlap(unit, at(Vec3::Zero()), unit, at(Vec3(1.9, 0.3, 0), rotation(0.3, Vec3(1, 2, 3)))));
    EXPECT_EQ(distance(unit, at(Vec3::Zero()), unit, at(Vec3(0.2, 0.1, 0))).distance, 0.0);  // deep
}

TEST(Queries, DistanceCapsules) {
    const Shape c = capsule(0.25, 1.0);
    auto r = distance(c, at(Vec3::Zero()), c, at(Vec3(2, 0.5, 0)));  // parallel
    EXPECT_NEAR(r.distance, 1.5, kTol);
    // Crossed: B lies along x, 2 m in front along z.
    r = distance(c, at(Vec3::Zero()), c, at(Vec3(0.3, 0.4, 2), rotation(kPi / 2, Vec3::UnitZ())));
    EXPECT_NEAR(r.distance, 1.5, kTol);
    expectVec(r.pointA, Vec3(0, 0.4, 0.25));
    expectVec(r.pointB, Vec3(0, 0.4, 1.75));
    // End to end along y.
    r = distance(c, at(Vec3::Zero()), c, at(Vec3(0, 3, 0)));
    EXPECT_NEAR(r.distance, 0.5, kTol);
    // Capsule against a box face.
    r = distance(c, at(Vec3(0, 0, 0), rotation(kPi / 2, Vec3::UnitX())), box(Vec3(1, 1, 1)), at(Vec3(0, 3, 0)));
    EXPECT_NEAR(r.distance, 1.75, kTol);
}

TEST(Queries, DistanceHullEqualsBoxAndSphereBoxIsAnalytic) {
    std::mt19937 rng(9);
    std::normal_distribution<double> gauss;
    const Shape cubeBox = box(Vec3::Constant(0.5));
    const Shape cubeHull = hullCube(0.5);
    const Shape other = capsule(0.2, 0.4);
    for (int i = 0; i < 200; ++i) {
        const Quat qa = drawUnitQuat(gauss, rng);
        const Quat qb = drawUnitQuat(gauss, rng);
        const Transform xa = at(Vec3::Zero(), qa);
        const Transform xb = at(1.5 * drawVec3(gauss, rng), qb);
        const double viaBox = distance(cubeBox, xa, other, xb).distance;
        const double viaHull = distance(cubeHull, xa, other, xb).distance;
        EXPECT_NEAR(viaBox, viaHull, kTol);

        // Sphere vs box: distance from the centre to the box (clamped in the box frame) - r.
        const Vec3 c = qa * (2.0 * drawVec3(gauss, rng));
        const Vec3 local = qa.conjugate() * c;
        const double exact = std::max(0.0, (local - local.cwiseMax(Vec3::Constant(-0.5)).cwiseMin(Vec3::Constant(0.5))).norm() - 0.1);
        const auto r = distance(sphere(0.1), at(c), cubeHull, xa);
        EXPECT_NEAR(r.distance, exact, kTol);
        if (r.distance > 0) {
            EXPECT_NEAR((r.pointB - r.pointA).norm(), r.distance, kTol);
            expectVec(r.normal, (r.pointB - r.pointA).normalized(), 1e-6);
        }
    }
}

// max over the shape of dir . x: the support value, computed independently of the library.
double supportValue(const Shape& s, const Transform& xf, const Vec3& dir) {
    const Vec3 d = xf.orientation.conjugate() * dir;
    double local = 0.0;
    switch (s.type) {
        case ShapeType::Sphere: local = s.radius * d.norm(); break;
        case ShapeType::Capsule: local = s.halfHeight * std::abs(d.y()) + s.radius * d.norm(); break;
        case ShapeType::Box: local = s.halfExtents.dot(d.cwiseAbs()); break;
        default: {
            local = -1e300;
            for (const Vec3& v : s.hull->vertices) local = std::max(local, v.dot(d));
        }
    }
    return local + dir.dot(xf.position);
}

// For random pairs of every convex type, the result is certified optimal: the points lie on the
// shapes' surfaces |pB - pA| apart, and the planes through them normal to n bound each shape.
TEST(Queries, DistanceIsCertifiedBySeparatingPlanes) {
    std::mt19937 rng(21);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> size(0.1, 1.0);
    auto randomShape = [&](int kind) {
        switch (kind % 4) {
            case 0: return sphere(size(rng));
            case 1: {
                const double radius = size(rng);
                return capsule(radius, size(rng));
            }
            case 2: return box(drawVec3(size, rng));
            default: return hullCube(size(rng));
        }
    };
    int separated = 0;
    for (int i = 0; i < 2000; ++i) {
        const Shape a = randomShape(i);
        const Shape b = randomShape(i / 4);
        const Vec3 pa = drawVec3(gauss, rng);
        const Transform xa = at(pa, drawUnitQuat(gauss, rng));
        const Vec3 pb = xa.position + 2.5 * drawVec3(gauss, rng);
        const Transform xb = at(pb, drawUnitQuat(gauss, rng));
        const auto r = distance(a, xa, b, xb);
        const auto swapped = distance(b, xb, a, xa);
        EXPECT_NEAR(r.distance, swapped.distance, 1e-9);
        if (r.distance <= 0.0) continue;
        ++separated;
        const Vec3& n = r.normal;
        EXPECT_NEAR(n.norm(), 1.0, 1e-12);
        EXPECT_NEAR((r.pointB - r.pointA).dot(n), r.distance, 1e-9);
        EXPECT_NEAR(supportValue(a, xa, n), n.dot(r.pointA), 1e-9) << "case " << i;
        EXPECT_NEAR(-supportValue(b, xb, -n), n.dot(r.pointB), 1e-9) << "case " << i;
    }
    EXPECT_GT(separated, 500);
}

TEST(Queries, DistanceToPlaneIsClosedFormEitherOrder) {
    const Shape ground = plane(Vec3::UnitY(), 0.0);
    const Shape unit = box(Vec3::Constant(0.5));
    const Transform tilted = at(Vec3(1, 2, 0), rotation(kPi / 4, Vec3::UnitZ()));
    auto r = distance(unit, tilted, ground, Transform{});
    EXPECT_NEAR(r.distance, 2.0 - std::sqrt(0.5), kTol);
    // The lowest edge runs along z: any point of it is a valid witness.
    EXPECT_NEAR(r.pointA.x(), 1.0, kTol);
    EXPECT_NEAR(r.pointA.y(), 2.0 - std::sqrt(0.5), kTol);
    EXPECT_NEAR(r.pointB.y(), 0.0, kTol);
    EXPECT_NEAR(r.pointB.z(), r.pointA.z(), kTol);
    expectVec(r.normal, -Vec3::UnitY());
    r = distance(ground, Transform{}, unit, tilted);  // swapped: normal still from A to B
    EXPECT_NEAR(r.distance, 2.0 - std::sqrt(0.5), kTol);
    EXPECT_NEAR(r.pointA.y(), 0.0, kTol);
    expectVec(r.normal, Vec3::UnitY());
    r = distance(capsule(0.5, 1.0), at(Vec3(0, 1.2, 0)), ground, Transform{});
    EXPECT_EQ(r.distance, 0.0);
    EXPECT_NEAR(r.pointA.y(), -0.3, kTol);  // the deepest point
    EXPECT_TRUE(overlap(sphere(1.0), at(Vec3(0, 0.5, 0)), ground, Transform{}));
    EXPECT_FALSE(overlap(sphere(1.0), at(Vec3(0, 1.5, 0)), ground, Transform{}));
}

TEST(Queries, DistanceToMesh) {
    const Shape quad = floorQuad(5.0);
    auto r = distance(sphere(0.5), at(Vec3(1, 2, 1)), quad, Transform{});
    EXPECT_NEAR(r.distance, 1.5, kTol);
    expectVec(r.pointB, Vec3(1, 0, 1));
    expectVec(r.normal, -Vec3::UnitY());
    // Beyond the edge: the nearest point is on the rim.
    r = distance(sphere(0.5), at(Vec3(6, 1, 0)), quad, Transform{});
    EXPECT_NEAR(r.distance, std::sqrt(2.0) - 0.5, kTol);
    // Far away: the search widens until it finds the mesh.
    r = distance(box(Vec3::Constant(0.5)), at(Vec3(0, 100, 0)), quad, Transform{});
    EXPECT_NEAR(r.distance, 99.5, kTol);
    // A moved mesh, and the swapped order.
    r = distance(quad, at(Vec3(0, -1, 0)), sphere(0.5), at(Vec3(0, 2, 0)));
    EXPECT_NEAR(r.distance, 2.5, kTol);
    expectVec(r.normal, Vec3::UnitY());
    EXPECT_TRUE(overlap(capsule(0.2, 1.0), at(Vec3(0, 0.15, 0), rotation(kPi / 2, Vec3::UnitX())), quad, Transform{}));
    EXPECT_FALSE(overlap(capsule(0.2, 1.0), at(Vec3(0, 0.25, 0), rotation(kPi / 2, Vec3::UnitX())), quad, Transform{}));
}

// ---------------------------------------------------------------------------------------------
// Time of impact

TEST(Queries, TimeOfImpactFastSphereAgainstThinWall) {
    // A 0.1 m sphere at 200 m/s, one 1/60 s step: 3.33 m toward a 0.1 m thick wall whose near
    // face is at x = 1.95. The gap r + target is reached at x = 1.95 - 0.1 - target.
    const Shape ball = sphere(0.1);
    const Shape wall = box(Vec3(0.05, 2, 2));
    const Transform wallPose = at(Vec3(2, 0, 0));
    const double travel = 200.0 / 60.0;
    const double target = 0.01;
    const double t = timeOfImpact(ball, at(Vec3::Zero()), at(Vec3(travel, 0, 0)), wall, wallPose, target);
    const double expected = (1.95 - 0.1 - target) / travel;
    EXPECT_NEAR(t, expected, 0.05 * target / travel);
    const double gap = distance(ball, at(Vec3(t * travel, 0, 0)), wall, wallPose).distance;
    EXPECT_GE(gap, target - 1e-9);
    EXPECT_LE(gap, 1.05 * target + 1e-9);
}

TEST(Queries, TimeOfImpactMissesAndStartsClose) {
    const Shape ball = sphere(0.1);
    const Shape wall = box(Vec3(0.05, 2, 2));
    // Moving parallel to the wall, or away from it: no impact.
    EXPECT_EQ(timeOfImpact(ball, at(Vec3(0, 0, 0)), at(Vec3(0, 3, 0)), wall, at(Vec3(2, 0, 0)), 0.01), 1.0);
    EXPECT_EQ(timeOfImpact(ball, at(Vec3(0, 0, 0)), at(Vec3(-3, 0, 0)), wall, at(Vec3(2, 0, 0)), 0.01), 1.0);
    // Stops short of the wall.
    EXPECT_EQ(timeOfImpact(ball, at(Vec3(0, 0, 0)), at(Vec3(1.5, 0, 0)), wall, at(Vec3(2, 0, 0)), 0.01), 1.0);
    // Already within the target: 0.
    EXPECT_EQ(timeOfImpact(ball, at(Vec3(1.849, 0, 0)), at(Vec3(3, 0, 0)), wall, at(Vec3(2, 0, 0)), 0.01), 0.0);
}

TEST(Queries, TimeOfImpactRotatingBoxNeverPassesTheTarget) {
    const Shape stick = box(Vec3(1.0, 0.1, 0.1));
    const Shape wall = box(Vec3(0.05, 3, 3));
    const Transform wallPose = at(Vec3(3.5, 0, 0));
    const Transform start = at(Vec3::Zero());
    // Turns 45 degrees while it moves: its tip would reach x = 3 + cos 45 + 0.1 sin 45 = 3.78.
    const Transform end = at(Vec3(3, 0, 0), rotation(kPi / 4, Vec3::UnitZ()));
    const double target = 0.02;
    const double t = timeOfImpact(stick, start, end, wall, wallPose, target);
    ASSERT_LT(t, 1.0);
    auto poseAt = [&](double s) {
        return Transform{start.position + s * (end.position - start.position), start.orientation.slerp(s, end.orientation)};
    };
    EXPECT_LE(distance(stick, poseAt(t), wall, wallPose).distance, 1.05 * target + 1e-9);
    for (double s = 0.0; s <= t; s += t / 200.0)
        EXPECT_GE(distance(stick, poseAt(s), wall, wallPose).distance, target - 1e-9) << "at s = " << s;
}

// Random convex shapes thrown, spinning, at random static convex shapes: the returned
// fraction is never past the target distance (sampled), and where it reports an impact the
// distance there is within the tolerance of the target.
TEST(Queries, TimeOfImpactIsConservativeOnRandomMotions) {
    std::mt19937 rng(33);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> size(0.1, 0.6);
    const double target = 0.01;
    int impacts = 0;
    for (int i = 0; i < 150; ++i) {
        const auto drawCapsule = [&] {
            const double radius = size(rng);
            return capsule(radius, size(rng));
        };
        const Shape moving = i % 3 == 0 ? box(drawVec3(size, rng)) : i % 3 == 1 ? drawCapsule() : hullCube(size(rng));
        const Shape fixed = i % 2 ? box(Vec3(size(rng), 2.0, 2.0)) : sphere(1.0);
        const Transform xb = at(Vec3::Zero(), drawUnitQuat(gauss, rng));
        const Vec3 from = 4.0 * drawVec3(gauss, rng).normalized();
        const Transform start = at(from, drawUnitQuat(gauss, rng));
        const Vec3 endPosition = -from + 0.5 * drawVec3(gauss, rng);
        const Transform end = at(endPosition, start.orientation * drawTurn(gauss, rng, 2.0));
        if (distance(moving, start, fixed, xb).distance <= target) continue;
        const double t = timeOfImpact(moving, start, end, fixed, xb, target);
        auto poseAt = [&](double s) {
            return Transform{start.position + s * (end.position - start.position), start.orientation.slerp(s, end.orientation)};
        };
        for (int k = 0; k <= 100; ++k)
            ASSERT_GE(distance(moving, poseAt(t * k / 100.0), fixed, xb).distance, target - 1e-9) << "case " << i;
        if (t < 1.0) {
            ++impacts;
            EXPECT_LE(distance(moving, poseAt(t), fixed, xb).distance, 1.05 * target + 1e-9) << "case " << i;
        }
    }
    EXPECT_GT(impacts, 100);
}

TEST(Queries, TimeOfImpactAgainstPlaneAndMesh) {
    const Shape ball = sphere(0.1);
    const double target = 0.005;
    // Falling 5 m onto the ground from 1 m up.
    double t = timeOfImpact(ball, at(Vec3(0, 1, 0)), at(Vec3(0, -4, 0)), plane(Vec3::UnitY(), 0.0), Transform{}, target);
    EXPECT_NEAR(t, (1.0 - 0.1 - target) / 5.0, 0.05 * target / 5.0);

    // Skimming 0.3 m over a mesh floor into a mesh wall at x = 3: the floor triangle is the
    // nearest throughout, so only per-triangle advancement finds the wall.
    const Shape room = mesh({Vec3(-5, 0, -5), Vec3(5, 0, -5), Vec3(5, 0, 5), Vec3(-5, 0, 5), Vec3(3, 0, -5),
                                  Vec3(3, 5, -5), Vec3(3, 5, 5), Vec3(3, 0, 5)},
                                 {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7});
    t = timeOfImpact(ball, at(Vec3(0, 0.4, 0)), at(Vec3(4, 0.4, 0)), room, Transform{}, target);
    EXPECT_NEAR(t, (3.0 - 0.1 - target) / 4.0, 0.05 * target / 4.0);
}

}  // namespace
}  // namespace anyphys::native
