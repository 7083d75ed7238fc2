// The per-pair CollideCache of the narrow phase: it may only save work, never change a result.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../../../api/src/geometry/convex_hull.hpp"
#include "collision/collide.hpp"
#include "native_test_shapes.hpp"
#include "../../random_draws.hpp"

namespace anyphys::native {
namespace {

using namespace anyphys::native::test;  // shapes and poses (native_test_shapes.hpp)
using anyphys::test::drawVec3;

// A prism of `sides` sides, radius r and half height h: many faces and edges.
Shape prism(int sides, double r, double h) {
    std::vector<Vec3> points;
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * std::numbers::pi * i / sides + 0.1;
        points.emplace_back(r * std::cos(a), -h, r * std::sin(a));
        points.emplace_back(r * std::cos(a), h, r * std::sin(a));
    }
    return convex(points);
}
// A random blob: faces of every orientation.
Shape blob(unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    std::vector<Vec3> points;
    for (int i = 0; i < 30; ++i)
        points.push_back(drawVec3(g, rng).normalized().cwiseProduct(Vec3(0.5, 0.4, 0.6)));
    return convex(points);
}

std::vector<Manifold> collideWith(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, double speculative,
                          CollideCache* cache = nullptr) {
    std::vector<Manifold> out;
    collide(a, xa, b, xb, speculative, out, cache);
    return out;
}

// Bit for bit: the cache only orders or skips work whose outcome it proves.
void expectSame(const std::vector<Manifold>& with, const std::vector<Manifold>& without) {
    ASSERT_EQ(with.size(), without.size());
    for (std::size_t k = 0; k < with.size(); ++k) {
        EXPECT_EQ(with[k].normal, without[k].normal);
        EXPECT_EQ(with[k].key, without[k].key);
        ASSERT_EQ(with[k].pointCount, without[k].pointCount);
        for (int i = 0; i < with[k].pointCount; ++i) {
            EXPECT_EQ(with[k].points[i].point, without[k].points[i].point);
            EXPECT_EQ(with[k].points[i].separation, without[k].points[i].separation);
            EXPECT_EQ(with[k].points[i].id, without[k].points[i].id);
        }
    }
}

struct ShapePair {
    const char* name;
    Shape a, b;
    double reach;  // centre distance at which they about touch
};

std::vector<ShapePair> pairs() {
    const Shape cube = box(Vec3(0.5, 0.5, 0.5)), slab = box(Vec3(1.2, 0.2, 0.7)), hull = prism(12, 0.5, 0.5);
    return {{"box-box", cube, cube, 1.0},      {"slab-box", slab, cube, 0.8},  {"box-hull", cube, hull, 1.0},
            {"hull-box", hull, cube, 1.0},     {"hull-hull", hull, hull, 1.0}, {"blob-hull", blob(3), hull, 1.0},
            {"blob-blob", blob(4), blob(5), 0.9}};
}

TEST(CollideCache, NeverChangesTheResultAlongRandomMotions) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(-1, 1);
    // Each number in its own statement (random_draws.hpp): the same cases under every compiler.
    auto randomAxis = [&] { return drawVec3(u, rng).normalized(); };
    for (const ShapePair& pair : pairs()) {
        SCOPED_TRACE(pair.name);
        int touching = 0, apart = 0;
        for (int trial = 0; trial < 60; ++trial) {
            // a rests on b or floats near it, then walks: small steps like a resting pile, large
            // ones (turns of up to 0.5 rad) that make any remembered axis stale.
            const bool resting = trial % 2 == 0;
            const Vec3 nearTop = drawVec3(u, rng).cwiseProduct(Vec3(0.3, 0.03 * pair.reach, 0.3)) + Vec3(0, pair.reach, 0);
            const double turnA = resting ? 0.03 * u(rng) : std::numbers::pi * u(rng);
            Transform xa = at(nearTop, rotation(turnA, randomAxis()));
            if (!resting) xa.position = pair.reach * drawVec3(u, rng);
            const double turnB = resting ? 0.03 * u(rng) : std::numbers::pi * u(rng);
            const Transform xb = at(Vec3::Zero(), rotation(turnB, randomAxis()));
            CollideCache cache;
            const double step = trial % 4 < 2 ? 0.002 : 0.05, turn = trial % 4 < 2 ? 0.002 : 0.5;
            for (int k = 0; k < 30; ++k) {
                const double speculative = 0.02 + 0.02 * (0.5 + 0.5 * u(rng));
                const std::vector<Manifold> without = collideWith(pair.a, xa, pair.b, xb, speculative);
                expectSame(collideWith(pair.a, xa, pair.b, xb, speculative, &cache), without);
                (without.empty() ? apart : touching) += 1;
                xa.position += step * drawVec3(u, rng);
                const double angle = turn * u(rng);
                xa.orientation = (rotation(angle, randomAxis()) * xa.orientation).normalized();
            }
        }
        EXPECT_GT(touching, 50);  // both outcomes exercised
        EXPECT_GT(apart, 50);
    }
}

TEST(CollideCache, RemembersTheSeparatingAxisAndTheReferenceFace) {
    const Shape cube = box(Vec3(0.5, 0.5, 0.5)), hull = prism(12, 0.5, 0.5);
    CollideCache cache;
    // Side by side, 0.1 apart along x: a's face +x separates them.
    EXPECT_TRUE(collideWith(cube, at(Vec3::Zero()), cube, at(Vec3(1.1, 0, 0)), 0.02, &cache).empty());
    EXPECT_TRUE(cache.separating);
    EXPECT_EQ(cache.axis, CollideCache::FaceOfA);
    EXPECT_EQ(cache.indexA, 0);
    // Hulls resting: the reference face is remembered, not as separating.
    CollideCache resting;
    ASSERT_EQ(collideWith(hull, at(Vec3(0.05, 0.99, 0)), hull, at(Vec3::Zero()), 0.02, &resting).size(), 1u);
    EXPECT_FALSE(resting.separating);
    EXPECT_NE(resting.axis, CollideCache::None);
}

TEST(CollideCache, AStaleAxisGivesNoWrongContacts) {
    // Apart along a's face +x, then b turns 45 degrees about z: its corner now reaches into a,
    // which the remembered axis (still a's +x, now overlapped) must not hide.
    const Shape cube = box(Vec3(0.5, 0.5, 0.5));
    CollideCache cache;
    ASSERT_TRUE(collideWith(cube, at(Vec3::Zero()), cube, at(Vec3(1.1, 0, 0)), 0.02, &cache).empty());
    ASSERT_TRUE(cache.separating);
    const Transform turned = at(Vec3(1.1, 0, 0), rotation(std::numbers::pi / 4, Vec3::UnitZ()));
    const std::vector<Manifold> cached = collideWith(cube, at(Vec3::Zero()), cube, turned, 0.02, &cache);
    const std::vector<Manifold> fresh = collideWith(cube, at(Vec3::Zero()), cube, turned, 0.02);
    ASSERT_EQ(fresh.size(), 1u);
    expectSame(cached, fresh);
    EXPECT_NEAR(fresh[0].points[0].separation, 1.1 - 0.5 - 0.5 * std::numbers::sqrt2, 1e-9);
    EXPECT_FALSE(cache.separating);

    // The same with hulls, and with the pair moved so that another axis separates them.
    const Shape hull = prism(12, 0.5, 0.5);
    CollideCache hullCache;
    ASSERT_TRUE(collideWith(hull, at(Vec3::Zero()), hull, at(Vec3(0, 1.2, 0)), 0.02, &hullCache).empty());
    ASSERT_TRUE(hullCache.separating);
    expectSame(collideWith(hull, at(Vec3::Zero()), hull, at(Vec3(1.2, 0, 0)), 0.02, &hullCache),
               collideWith(hull, at(Vec3::Zero()), hull, at(Vec3(1.2, 0, 0)), 0.02));
    expectSame(collideWith(hull, at(Vec3::Zero()), hull, at(Vec3(0.3, 0.98, 0)), 0.02, &hullCache),
               collideWith(hull, at(Vec3::Zero()), hull, at(Vec3(0.3, 0.98, 0)), 0.02));
}

TEST(CollideCache, ACacheOfAnotherPairIsHarmless) {
    // Indices out of range for these shapes (a cache moved between pairs, or garbage) are ignored.
    const Shape cube = box(Vec3(0.5, 0.5, 0.5)), hull = prism(12, 0.5, 0.5);
    for (const CollideCache::Axis axis : {CollideCache::FaceOfA, CollideCache::FaceOfB, CollideCache::EdgePair})
        for (const bool separating : {true, false})
            for (const int index : {-3, 7, 500}) {
                CollideCache cache{axis, separating, index, index};
                expectSame(collideWith(cube, at(Vec3::Zero()), cube, at(Vec3(0.1, 0.99, 0)), 0.02, &cache),
                           collideWith(cube, at(Vec3::Zero()), cube, at(Vec3(0.1, 0.99, 0)), 0.02));
                cache = {axis, separating, index, index};
                expectSame(collideWith(hull, at(Vec3::Zero()), hull, at(Vec3(0.1, 0.99, 0)), 0.02, &cache),
                           collideWith(hull, at(Vec3::Zero()), hull, at(Vec3(0.1, 0.99, 0)), 0.02));
            }
}

}  // namespace
}  // namespace anyphys::native
