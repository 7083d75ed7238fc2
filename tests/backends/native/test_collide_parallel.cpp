// collide() as the parallel narrow phase uses it: from several threads at once, every pair kind
// (hull faces larger than any fixed-size buffer, so the per-thread scratch buffers are used).
#include <cmath>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "../../../api/src/geometry/convex_hull.hpp"
#include "collision/collide.hpp"
#include "collision/mesh_data.hpp"
#include "native_test_shapes.hpp"
#include "../../random_draws.hpp"

namespace anyphys::native {
namespace {

using namespace anyphys::native::test;  // shapes and poses (native_test_shapes.hpp)
using anyphys::test::drawTurn;
using anyphys::test::drawVec3;

// A prism of 20 sides (larger than every fixed-size buffer: hull faces use the scratch buffers).
Shape prism() {
    std::vector<Vec3> points;
    for (int i = 0; i < 20; ++i) {
        const double a = 2 * std::numbers::pi * i / 20 + 0.1;
        points.emplace_back(0.5 * std::cos(a), -0.5, 0.5 * std::sin(a));
        points.emplace_back(0.5 * std::cos(a), 0.5, 0.5 * std::sin(a));
    }
    return convex(points);
}
// A bumpy 4 x 4 floor of 32 triangles around y = 0.
Shape floorMesh() {
    std::vector<Vec3> vertices;
    for (int i = 0; i <= 4; ++i)
        for (int k = 0; k <= 4; ++k) vertices.emplace_back(i - 2.0, 0.05 * ((i + k) % 2), k - 2.0);
    std::vector<std::uint32_t> indices;
    for (std::uint32_t i = 0; i < 4; ++i)
        for (std::uint32_t k = 0; k < 4; ++k) {
            const std::uint32_t v = 5 * i + k;
            indices.insert(indices.end(), {v, v + 1, v + 5, v + 1, v + 6, v + 5});
        }
    return mesh(vertices, indices);
}

struct Case {
    const Shape* a;
    Transform xa;
    const Shape* b;
    Transform xb;
};

// Every pair kind, touching or near, in random poses.
std::vector<Case> cases(const std::vector<Shape>& convexShapes, const Shape& ground, const Shape& terrain, int count) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    // Each number in its own statement (random_draws.hpp): the same cases under every compiler.
    auto pose = [&](const Vec3& p) { return Transform{p, drawTurn(u, rng, std::numbers::pi)}; };
    auto near = [&](const Vec3& centre, const Vec3& spread) -> Vec3 { return centre + drawVec3(u, rng).cwiseProduct(spread); };
    std::vector<Case> out;
    for (int i = 0; i < count; ++i) {
        const Shape* a = &convexShapes[static_cast<std::size_t>(i) % convexShapes.size()];
        const Shape* b = &convexShapes[static_cast<std::size_t>(i / 7) % convexShapes.size()];
        switch (i % 3) {
            case 0:
                out.push_back({a, pose(near(Vec3(0, 0.9, 0), Vec3(0.3, 0.1, 0.3))), b, pose(Vec3::Zero())});
                break;
            case 1: out.push_back({a, pose(near(Vec3(0, 0.45, 0), Vec3(1, 0.1, 1))), &ground, Transform{}}); break;
            default: out.push_back({a, pose(near(Vec3(0, 0.45, 0), Vec3(1, 0.1, 1))), &terrain, Transform{}}); break;
        }
    }
    return out;
}

std::vector<std::vector<Manifold>> collideAll(const std::vector<Case>& list) {
    std::vector<std::vector<Manifold>> results;
    for (const Case& c : list) {
        std::vector<Manifold>& out = results.emplace_back();
        collide(*c.a, c.xa, *c.b, c.xb, 0.03, out);
    }
    return results;
}

bool same(const std::vector<Manifold>& x, const std::vector<Manifold>& y) {
    if (x.size() != y.size()) return false;
    for (std::size_t k = 0; k < x.size(); ++k) {
        if (x[k].normal != y[k].normal || x[k].key != y[k].key || x[k].pointCount != y[k].pointCount) return false;
        for (int i = 0; i < x[k].pointCount; ++i)
            if (x[k].points[i].point != y[k].points[i].point || x[k].points[i].separation != y[k].points[i].separation ||
                x[k].points[i].id != y[k].points[i].id)
                return false;
    }
    return true;
}

TEST(CollideParallel, ThreadsGetTheSequentialResults) {
    const std::vector<Shape> shapes{sphere(0.4), capsule(0.25, 0.5), box(Vec3(0.5, 0.4, 0.3)), prism()};
    const Shape ground = plane(Vec3::UnitY(), 0.0), terrain = floorMesh();
    const std::vector<Case> list = cases(shapes, ground, terrain, 600);
    const std::vector<std::vector<Manifold>> expected = collideAll(list);
    std::size_t manifolds = 0;
    for (const auto& r : expected) manifolds += r.size();
    EXPECT_GT(manifolds, 300u);

    constexpr int kThreads = 4;
    std::vector<std::vector<std::vector<Manifold>>> got(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (int repeat = 0; repeat < 20; ++repeat) got[static_cast<std::size_t>(t)] = collideAll(list);
        });
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t)
        for (std::size_t i = 0; i < list.size(); ++i)
            EXPECT_TRUE(same(got[static_cast<std::size_t>(t)][i], expected[i])) << "thread " << t << ", case " << i;
}

}  // namespace
}  // namespace anyphys::native
