// The submerged part of shapes below a plane against closed forms: volumes and centres of
// buoyancy of boxes (any orientation), spheres (the cap), capsules and convex hulls, and the
// projected areas drag uses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "anyphys/fields/field_forces.hpp"
#include "anyphys/fields/submerged_volume.hpp"

namespace anyphys {
namespace {

constexpr double kPi = std::numbers::pi;
// Exact methods (clipping, caps) agree with the closed forms to rounding of a few operations on
// unit-sized numbers.
constexpr double kExact = 1e-12;

Quat about(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

FieldShape hullOfBox(const Vec3& half) {
    FieldShape s;
    s.type = ShapeType::Convex;
    s.hull = std::make_shared<const ConvexFaces>(boxFaces(half));
    return s;
}

TEST(SubmergedVolume, BoxFullyUnderIsItsVolumeAndCentre) {
    const Vec3 half(0.5, 0.25, 1.0);
    const Transform pose{Vec3(1, -5, 2), about(Vec3(1, 2, 3), 0.7)};
    const SubmergedVolume s = submergedBox(half, pose, FluidPlane{});
    EXPECT_NEAR(s.volume, 1.0, kExact);
    EXPECT_NEAR((s.centroid - pose.position).norm(), 0.0, kExact);
    EXPECT_EQ(submergedBox(half, {Vec3(0, 5, 0), pose.orientation}, FluidPlane{}).volume, 0.0);
}

TEST(SubmergedVolume, BoxHalfUnderIsHalf) {
    // Axis-aligned at the surface: the lower half, centroid a quarter of the height below.
    const Vec3 half(0.5, 0.5, 0.5);
    const SubmergedVolume s = submergedBox(half, {Vec3(0, 0, 0), Quat::Identity()}, FluidPlane{});
    EXPECT_NEAR(s.volume, 0.5, kExact);
    EXPECT_NEAR((s.centroid - Vec3(0, -0.25, 0)).norm(), 0.0, kExact);
    // Any orientation: a box is symmetric through its centre, so a plane through the centre halves it.
    for (double angle : {0.1, 0.5, 1.0, 2.0}) {
        const SubmergedVolume t = submergedBox(Vec3(0.3, 0.7, 1.1), {Vec3(2, 0, -1), about(Vec3(1, 1, 0.2), angle)}, FluidPlane{});
        EXPECT_NEAR(t.volume, 0.5 * 8 * 0.3 * 0.7 * 1.1, kExact) << angle;
    }
}

TEST(SubmergedVolume, BoxDraftAlongItsHeight) {
    // A 1 x 2 x 1 box whose bottom is d below the surface: V = 1 * d * 1, centroid at -d/2.
    const Vec3 half(0.5, 1.0, 0.5);
    for (double d : {0.1, 0.6, 1.3, 1.9}) {
        const SubmergedVolume s = submergedBox(half, {Vec3(0, 1.0 - d, 0), Quat::Identity()}, FluidPlane{});
        EXPECT_NEAR(s.volume, d, kExact);
        EXPECT_NEAR(s.centroid.y(), -d / 2, kExact);
    }
}

TEST(SubmergedVolume, BoxTilted45DegreesAboutAnEdgeDirection) {
    // A unit cube turned 45 degrees about Z, centre at height c: its cross-section is a square
    // of diagonal sqrt(2) standing on a corner; the part below y = 0 is a triangle prism when the
    // bottom corner is less than sqrt(2)/2 deep: area = depth^2 (the 45-degree triangle), times 1 in Z.
    const Quat q = about(Vec3::UnitZ(), kPi / 4);
    const double corner = std::sqrt(0.5);
    for (double depth : {0.1, 0.3, 0.6}) {
        const SubmergedVolume s = submergedBox(Vec3(0.5, 0.5, 0.5), {Vec3(0, corner - depth, 0), q}, FluidPlane{});
        EXPECT_NEAR(s.volume, depth * depth, kExact) << depth;
        // The triangle's centroid is the mean of its corners (-depth, 0, 0).
        EXPECT_NEAR(s.centroid.y(), -depth / 3, kExact) << depth;
        EXPECT_NEAR(s.centroid.x(), 0.0, kExact);
    }
}

TEST(SubmergedVolume, TiltedPlaneOffsetAndNormal) {
    // The same cube, axis aligned, with the surface tilted instead: the results turn with it.
    const Vec3 n = Vec3(1, 1, 0).normalized();
    const FluidPlane fluid{n, 0.2};
    const SubmergedVolume a = submergedBox(Vec3(0.5, 0.5, 0.5), {Vec3(0, 0, 0), Quat::Identity()}, fluid);
    // Rotating everything by -45 degrees about Z gives the cube tilted under a level surface at 0.2.
    const Quat q = about(Vec3::UnitZ(), kPi / 4);  // turns n onto +Y
    const SubmergedVolume b = submergedBox(Vec3(0.5, 0.5, 0.5), {Vec3(0, -0.2, 0), q}, FluidPlane{});
    EXPECT_NEAR(a.volume, b.volume, kExact);
    EXPECT_NEAR((q * a.centroid - b.centroid - Vec3(0, 0.2, 0)).norm(), 0.0, kExact);
}

TEST(SubmergedVolume, HullOfABoxEqualsTheBox) {
    const Vec3 half(0.4, 0.9, 0.3);
    const FieldShape hull = hullOfBox(half);
    EXPECT_NEAR(shapeVolume(hull), 8 * 0.4 * 0.9 * 0.3, kExact);
    for (double angle : {0.0, 0.3, 1.2, 2.5})
        for (double height : {-1.2, -0.4, 0.0, 0.35, 0.8}) {
            const Transform pose{Vec3(0.3, height, -0.7), about(Vec3(0.2, 1, 0.5), angle)};
            const SubmergedVolume box = submergedBox(half, pose, FluidPlane{});
            const SubmergedVolume convex = submergedConvex(*hull.hull, pose, FluidPlane{});
            EXPECT_NEAR(box.volume, convex.volume, kExact);
            if (box.volume > 0) {
                EXPECT_NEAR((box.centroid - convex.centroid).norm(), 0.0, 1e-11);
            }
        }
}

TEST(SubmergedVolume, SphereCap) {
    const double r = 0.5;
    for (double h : {0.0, 0.1, 0.5, 0.77, 1.0}) {
        // The cap of height h: V = pi h^2 (3r - h) / 3; centroid 3 (2r - h)^2 / (4 (3r - h)) below the centre.
        const Vec3 c(1, r - h, 3);
        const SubmergedVolume s = submergedSphere(r, c, FluidPlane{});
        EXPECT_NEAR(s.volume, kPi * h * h * (3 * r - h) / 3, kExact) << h;
        if (h > 0) {
            EXPECT_NEAR(s.centroid.y(), c.y() - 3 * (2 * r - h) * (2 * r - h) / (4 * (3 * r - h)), kExact);
        }
    }
    EXPECT_NEAR(submergedSphere(r, Vec3(0, -0.1, 0), FluidPlane{}).volume + submergedSphere(r, Vec3(0, 0.1, 0), FluidPlane{}).volume,
                4.0 / 3.0 * kPi * r * r * r, kExact);  // two caps of a plane at +-0.1 make the sphere
}

// The capsule's quadrature: measured relative errors are far below this bound (they are
// printed); 1e-9 of its volume is what docs and the header promise.
constexpr double kCapsule = 1e-9;

TEST(SubmergedVolume, CapsuleUprightIsCylinderPlusCaps) {
    const double r = 0.3, h = 0.5;
    const double full = kPi * r * r * (2 * h + 4 * r / 3);
    const Transform up{Vec3(0, 0, 0), Quat::Identity()};
    // Surface through the centre: half. Through the top cap at height h + 0.1: all but a cap of 0.2.
    EXPECT_NEAR(submergedCapsule(r, h, up, FluidPlane{}).volume, full / 2, kCapsule * full);
    const double cap = 0.2;
    EXPECT_NEAR(submergedCapsule(r, h, up, FluidPlane{Vec3(0, 1, 0), h + r - cap}).volume,
                full - kPi * cap * cap * (3 * r - cap) / 3, kCapsule * full);
    // Through the cylinder at height 0.2: the bottom cap, and the cylinder up to 0.2.
    const SubmergedVolume mid = submergedCapsule(r, h, up, FluidPlane{Vec3(0, 1, 0), 0.2});
    const double expected = 2.0 / 3 * kPi * r * r * r + kPi * r * r * (h + 0.2);
    EXPECT_NEAR(mid.volume, expected, kCapsule * full);
    const double moment = 2.0 / 3 * kPi * r * r * r * (-h - 3 * r / 8) + kPi * r * r * (h + 0.2) * (0.2 - h) / 2;
    EXPECT_NEAR(mid.centroid.y(), moment / expected, 1e-9);
}

TEST(SubmergedVolume, CapsuleLyingIsCylinderSegmentPlusSphereCap) {
    // Axis along X, surface at height y0: the cylinder's circular segment times the length, plus
    // the two half spheres forming one sphere cut at y0.
    const double r = 0.4, h = 0.7;
    const Transform lying{Vec3(0, 0, 0), about(Vec3::UnitZ(), kPi / 2)};
    for (double y0 : {-0.3, -0.1, 0.0, 0.25}) {
        const double u0 = y0;  // wet: y < y0
        const double segment = r * r * std::acos(-u0 / r) + u0 * std::sqrt(r * r - u0 * u0);
        const double capHeight = r + y0;
        const double expected = segment * 2 * h + kPi * capHeight * capHeight * (3 * r - capHeight) / 3;
        const SubmergedVolume s = submergedCapsule(r, h, lying, FluidPlane{Vec3(0, 1, 0), y0});
        const double full = kPi * r * r * (2 * h + 4 * r / 3);
        std::cout << "  capsule lying, surface " << y0 << ": relative volume error " << std::abs(s.volume - expected) / full << '\n';
        EXPECT_NEAR(s.volume, expected, kCapsule * full) << y0;
        EXPECT_NEAR(s.centroid.x(), 0.0, 1e-12);
    }
}

TEST(SubmergedVolume, CapsuleTiltedHalvesAndComplementsAddUp) {
    // Tilted: no closed form. A capsule is convex, so its wet volume is continuous and monotonic
    // in the surface height; the two halves of a plane through its centre are equal by symmetry.
    const double r = 0.25, h = 0.6;
    const double full = kPi * r * r * (2 * h + 4 * r / 3);
    for (double angle : {0.2, 0.7, 1.1}) {
        const Transform pose{Vec3(0, 0, 0), about(Vec3(1, 0, 1), angle)};
        const SubmergedVolume below = submergedCapsule(r, h, pose, FluidPlane{});
        const SubmergedVolume above = submergedCapsule(r, h, pose, FluidPlane{Vec3(0, -1, 0), 0.0});
        EXPECT_NEAR(below.volume, full / 2, kCapsule * full) << angle;
        EXPECT_NEAR(below.volume + above.volume, full, kCapsule * full);
        // The two halves' centroids are mirror images through the centre.
        EXPECT_NEAR((below.centroid + above.centroid).norm(), 0.0, 1e-9);
        for (double y0 : {-0.5, -0.2, 0.1, 0.4}) {
            const SubmergedVolume lower = submergedCapsule(r, h, pose, FluidPlane{Vec3(0, 1, 0), y0});
            const SubmergedVolume upper = submergedCapsule(r, h, pose, FluidPlane{Vec3(0, -1, 0), -y0});
            std::cout << "  capsule tilted " << angle << ", surface " << y0 << ": relative sum error "
                      << std::abs(lower.volume + upper.volume - full) / full << '\n';
            EXPECT_NEAR(lower.volume + upper.volume, full, kCapsule * full);
            // Moments add up to the whole capsule's (centred on the origin).
            EXPECT_NEAR((lower.centroid * lower.volume + upper.centroid * upper.volume).norm(), 0.0, 1e-9);
        }
    }
}

TEST(SubmergedVolume, CapsuleTiltedCutThroughItsCylinder) {
    // A plane that crosses only the cylinder (not its end discs) leaves pi r^2 times the wet
    // length of the axis (an oblique cut keeps the volume of the square cut through the same
    // axis point), plus the lower half sphere whole.
    const double r = 0.25, h = 0.6;
    const double full = kPi * r * r * (2 * h + 4 * r / 3);
    for (double angle : {0.1, 0.3, 0.6}) {
        const Transform pose{Vec3(0, 0, 0), about(Vec3::UnitZ(), angle)};
        const double reach = r * std::tan(angle);  // axial half-extent of the cut inside the cylinder
        for (double y0 : {-0.3, 0.0, 0.2}) {
            const double t = y0 / std::cos(angle);  // where the surface meets the axis
            ASSERT_LT(std::abs(t) + reach, h);
            const double expected = 2.0 / 3 * kPi * r * r * r + kPi * r * r * (t + h);
            const SubmergedVolume s = submergedCapsule(r, h, pose, FluidPlane{Vec3(0, 1, 0), y0});
            std::cout << "  capsule tilted " << angle << " cut at " << y0 << ": relative volume error "
                      << std::abs(s.volume - expected) / full << '\n';
            EXPECT_NEAR(s.volume, expected, kCapsule * full) << angle << " " << y0;
        }
    }
}

TEST(SubmergedVolume, CompoundSumsItsChildren) {
    std::vector<FieldShape> shapes(2);
    shapes[0].type = ShapeType::Sphere;
    shapes[0].radius = 0.5;
    shapes[0].local.position = Vec3(-1, 0, 0);
    shapes[1].type = ShapeType::Box;
    shapes[1].halfExtents = Vec3(0.5, 0.5, 0.5);
    shapes[1].local.position = Vec3(1, 0, 0);
    const SubmergedVolume s = submergedShapes(shapes, {Vec3(0, 0, 0), Quat::Identity()}, FluidPlane{});
    const double sphereHalf = 2.0 / 3 * kPi * 0.125;
    EXPECT_NEAR(s.volume, sphereHalf + 0.5, kExact);
    EXPECT_NEAR(s.centroid.x(), (-sphereHalf + 0.5) / (sphereHalf + 0.5), kExact);
}

TEST(ProjectedArea, Primitives) {
    FieldShape sphere;
    sphere.type = ShapeType::Sphere;
    sphere.radius = 0.5;
    EXPECT_NEAR(projectedArea(sphere, Quat::Identity(), Vec3(0, 1, 0)), kPi * 0.25, kExact);
    FieldShape box;
    box.type = ShapeType::Box;
    box.halfExtents = Vec3(0.5, 1.0, 1.5);
    EXPECT_NEAR(projectedArea(box, Quat::Identity(), Vec3(1, 0, 0)), 2.0 * 3.0, kExact);
    const Vec3 d = Vec3(1, 2, 3).normalized();
    EXPECT_NEAR(projectedArea(box, Quat::Identity(), d), 6 * d.x() + 3 * d.y() + 2 * d.z(), kExact);
    // The hull of that box projects to the same silhouette, in any orientation.
    FieldShape hull = hullOfBox(box.halfExtents);
    const Quat q = about(Vec3(0.3, 1, -0.2), 0.9);
    EXPECT_NEAR(projectedArea(hull, q, d), projectedArea(box, q, d), kExact);
    FieldShape capsule;
    capsule.type = ShapeType::Capsule;
    capsule.radius = 0.2;
    capsule.halfHeight = 0.5;
    EXPECT_NEAR(projectedArea(capsule, Quat::Identity(), Vec3(0, 1, 0)), kPi * 0.04, kExact);
    EXPECT_NEAR(projectedArea(capsule, Quat::Identity(), Vec3(1, 0, 0)), kPi * 0.04 + 0.4 * 1.0, kExact);
}

TEST(Explosion, NearestSurfacePointAndFalloff) {
    FieldBody body;
    body.shapes.resize(1);
    body.shapes[0].type = ShapeType::Box;
    body.shapes[0].halfExtents = Vec3(0.5, 0.5, 0.5);
    const Transform pose{Vec3(3, 0, 0), Quat::Identity()};
    EXPECT_NEAR((nearestSurfacePoint(body, pose, Vec3(0, 0.2, 0)) - Vec3(2.5, 0.2, 0)).norm(), 0.0, kExact);
    FieldBody hull;
    hull.shapes.push_back(hullOfBox(Vec3(0.5, 0.5, 0.5)));
    for (const Vec3& p : {Vec3(0, 0.2, 0), Vec3(0, 3, 1), Vec3(3.2, 0.1, -0.1)})
        EXPECT_NEAR((nearestSurfacePoint(hull, pose, p) - nearestSurfacePoint(body, pose, p)).norm(), 0.0, kExact);
    const FieldDef e = FieldDef::explosion(Vec3::Zero(), 0.0, 100.0, 4.0);
    EXPECT_DOUBLE_EQ(explosionImpulse(e, 0.0), 100.0);
    EXPECT_DOUBLE_EQ(explosionImpulse(e, 1.0), 75.0);
    EXPECT_DOUBLE_EQ(explosionImpulse(e, 4.0), 0.0);
    const auto hit = explosionHit(e, body, FieldState{pose});
    ASSERT_TRUE(hit);
    EXPECT_NEAR((hit->impulse - Vec3(100.0 * (1 - 2.5 / 4), 0, 0)).norm(), 0.0, kExact);
}

}  // namespace
}  // namespace anyphys
