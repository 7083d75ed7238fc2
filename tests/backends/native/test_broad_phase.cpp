// Native broad phase: the dynamic AABB tree stays valid and balanced under random churn, its
// queries and ray casts equal brute force, and BroadPhase reports exactly the new pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <set>

#include "collision/broad_phase.hpp"
#include "collision/mesh_data.hpp"
#include "../../random_draws.hpp"

namespace anyphys::native {
namespace {

using Pair = std::pair<std::uint64_t, std::uint64_t>;
using anyphys::test::drawVec3;

Aabb randomBox(std::mt19937& rng, double world, double maxSize) {
    std::uniform_real_distribution<double> pos(-world, world);
    std::uniform_real_distribution<double> size(0.01, maxSize);
    const Vec3 c = drawVec3(pos, rng);
    const Vec3 e = drawVec3(size, rng);
    return {c - e, c + e};
}

// An AVL tree of n leaves has height <= 1.44 log2 n; the SAH insertion with rotations is not a
// strict AVL tree, so allow a looser bound.
int heightBound(int n) { return static_cast<int>(2.0 * std::log2(std::max(n, 2)) + 2.0); }

// Brute-force slab test: does the ray meet the box within [0, maxT]? Returns the entry distance.
std::optional<double> rayEntry(const Vec3& o, const Vec3& d, double maxT, const Aabb& b) {
    double t0 = 0.0;
    double t1 = maxT;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            if (o[i] < b.min[i] || o[i] > b.max[i]) return std::nullopt;
            continue;
        }
        double a = (b.min[i] - o[i]) / d[i];
        double c = (b.max[i] - o[i]) / d[i];
        if (a > c) std::swap(a, c);
        t0 = std::max(t0, a);
        t1 = std::min(t1, c);
        if (t0 > t1) return std::nullopt;
    }
    return t0;
}

TEST(DynamicTree, EmptyTree) {
    DynamicTree tree;
    EXPECT_TRUE(tree.isValid());
    EXPECT_EQ(tree.height(), 0);
    EXPECT_EQ(tree.proxyCount(), 0);
    int visits = 0;
    tree.query({Vec3::Constant(-1), Vec3::Constant(1)}, [&](int) { return ++visits, true; });
    EXPECT_EQ(visits, 0);
}

TEST(DynamicTree, StaysValidAndBalancedUnderRandomChurn) {
    std::mt19937 rng(7);
    DynamicTree tree;
    std::map<int, Aabb> live;  // proxy -> box, the brute-force reference
    for (int i = 0; i < 2000; ++i) {
        const Aabb b = randomBox(rng, 50.0, 2.0);
        live[tree.createProxy(b, static_cast<std::uint64_t>(i))] = b;
    }
    ASSERT_TRUE(tree.isValid());
    EXPECT_LE(tree.height(), heightBound(tree.proxyCount()));

    std::uniform_int_distribution<int> op(0, 9);
    std::uint64_t nextData = 2000;
    for (int step = 0; step < 6000; ++step) {
        auto it = live.begin();
        std::advance(it, std::uniform_int_distribution<int>(0, static_cast<int>(live.size()) - 1)(rng));
        const int kind = op(rng);
        if (kind < 6) {  // move
            const Aabb b = randomBox(rng, 50.0, 2.0);
            tree.moveProxy(it->first, b);
            it->second = b;
        } else if (kind < 8 && live.size() > 10) {  // remove
            tree.destroyProxy(it->first);
            live.erase(it);
        } else {  // insert
            const Aabb b = randomBox(rng, 50.0, 2.0);
            live[tree.createProxy(b, nextData++)] = b;
        }
        if (step % 500 == 0) {
            ASSERT_TRUE(tree.isValid()) << "after step " << step;
            EXPECT_LE(tree.height(), heightBound(tree.proxyCount())) << "after step " << step;
        }
    }
    ASSERT_TRUE(tree.isValid());
    EXPECT_EQ(tree.proxyCount(), static_cast<int>(live.size()));
    EXPECT_LE(tree.height(), heightBound(tree.proxyCount()));
    for (const auto& [proxy, box] : live) {
        EXPECT_EQ(tree.fatAabb(proxy).min, box.min);
        EXPECT_EQ(tree.fatAabb(proxy).max, box.max);
    }

    // Queries equal brute force.
    for (int q = 0; q < 200; ++q) {
        const Aabb box = randomBox(rng, 50.0, 8.0);
        std::set<int> found;
        tree.query(box, [&](int proxy) {
            EXPECT_TRUE(found.insert(proxy).second) << "reported twice";
            return true;
        });
        std::set<int> expected;
        for (const auto& [proxy, b] : live)
            if (b.overlaps(box)) expected.insert(proxy);
        ASSERT_EQ(found, expected);
    }

    // Removing everything leaves an empty valid tree.
    for (const auto& [proxy, box] : live) tree.destroyProxy(proxy);
    EXPECT_TRUE(tree.isValid());
    EXPECT_EQ(tree.proxyCount(), 0);
}

TEST(DynamicTree, SortedInsertionStaysBalanced) {
    // Inserting along a line is the classic worst case for an unbalanced tree (a list).
    DynamicTree tree;
    for (int i = 0; i < 4096; ++i) {
        const Vec3 c(i, 0, 0);
        tree.createProxy({c.array() - 0.4, c.array() + 0.4}, static_cast<std::uint64_t>(i));
    }
    EXPECT_TRUE(tree.isValid());
    EXPECT_LE(tree.height(), heightBound(4096));
}

TEST(DynamicTree, QueryStopsWhenVisitReturnsFalse) {
    DynamicTree tree;
    for (int i = 0; i < 100; ++i) tree.createProxy({Vec3::Zero(), Vec3::Ones()}, static_cast<std::uint64_t>(i));
    int visits = 0;
    tree.query({Vec3::Zero(), Vec3::Ones()}, [&](int) { return ++visits < 3; });
    EXPECT_EQ(visits, 3);
}

TEST(DynamicTree, RayCastEqualsBruteForce) {
    std::mt19937 rng(11);
    DynamicTree tree;
    std::vector<Aabb> boxes;
    for (int i = 0; i < 1000; ++i) {
        boxes.push_back(randomBox(rng, 30.0, 1.5));
        tree.createProxy(boxes.back(), static_cast<std::uint64_t>(i));
    }
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> pos(-40.0, 40.0);
    for (int r = 0; r < 200; ++r) {
        const Vec3 o = drawVec3(pos, rng);
        Vec3 d = drawVec3(gauss, rng);
        if (r % 10 == 0) d = Vec3(0, 0, r % 20 == 0 ? 1 : -1);  // axis-parallel rays too
        d.normalize();
        const double maxT = 60.0;

        // All boxes along the ray (visit keeps the clip distance).
        std::set<std::uint64_t> all;
        tree.rayCast(o, d, maxT, [&](int proxy, double clip) {
            all.insert(tree.userData(proxy));
            return clip;
        });
        std::set<std::uint64_t> expected;
        std::optional<double> nearest;
        for (std::size_t i = 0; i < boxes.size(); ++i)
            if (const auto t = rayEntry(o, d, maxT, boxes[i])) {
                expected.insert(i);
                nearest = nearest ? std::min(*nearest, *t) : *t;
            }
        ASSERT_EQ(all, expected);

        // Closest box entry, using clipping.
        std::optional<double> best;
        tree.rayCast(o, d, maxT, [&](int proxy, double clip) {
            const auto t = rayEntry(o, d, clip, tree.fatAabb(proxy));
            if (!t) return clip;
            best = t;
            return std::max(*t, 1e-12);
        });
        ASSERT_EQ(best.has_value(), nearest.has_value());
        if (best) {
            EXPECT_NEAR(*best, *nearest, 1e-12);
        }
    }
}

TEST(DynamicTree, RayCastStopsOnZero) {
    DynamicTree tree;
    for (int i = 0; i < 10; ++i) tree.createProxy({Vec3(i, -1, -1), Vec3(i + 0.5, 1, 1)}, static_cast<std::uint64_t>(i));
    int visits = 0;
    tree.rayCast(Vec3(-1, 0, 0), Vec3::UnitX(), 100.0, [&](int, double) { return ++visits, 0.0; });
    EXPECT_EQ(visits, 1);
}

// ---------------------------------------------------------------------------------------------
// BroadPhase

std::set<Pair> collectPairs(BroadPhase& bp) {
    std::set<Pair> pairs;
    bp.updatePairs([&](std::uint64_t a, std::uint64_t b) {
        EXPECT_LT(a, b) << "keys must be ordered (min, max)";
        EXPECT_TRUE(pairs.insert({a, b}).second) << "pair (" << a << ", " << b << ") reported twice";
    });
    return pairs;
}

TEST(BroadPhase, FirstUpdateReportsAllOverlapsOnceButNoStaticStatic) {
    std::mt19937 rng(3);
    BroadPhase bp(0.1);
    std::vector<int> proxies;
    std::vector<bool> isStatic;
    for (int i = 0; i < 600; ++i) {
        isStatic.push_back(i % 4 == 0);
        proxies.push_back(bp.createProxy(randomBox(rng, 12.0, 1.5), static_cast<std::uint64_t>(i), isStatic.back()));
    }
    const std::set<Pair> pairs = collectPairs(bp);
    std::set<Pair> expected;
    int staticStatic = 0;
    for (int i = 0; i < 600; ++i)
        for (int j = i + 1; j < 600; ++j)
            if (bp.fatAabb(proxies[static_cast<std::size_t>(i)]).overlaps(bp.fatAabb(proxies[static_cast<std::size_t>(j)]))) {
                if (isStatic[static_cast<std::size_t>(i)] && isStatic[static_cast<std::size_t>(j)]) {
                    ++staticStatic;
                } else {
                    expected.insert({i, j});
                }
            }
    EXPECT_GT(expected.size(), 100u);
    EXPECT_GT(staticStatic, 0);  // the scene does have overlapping static boxes
    EXPECT_EQ(pairs, expected);
    EXPECT_TRUE(collectPairs(bp).empty());  // nothing moved since
}

TEST(BroadPhase, LaterUpdatesReportPairsOfMovedProxiesOnly) {
    std::mt19937 rng(5);
    BroadPhase bp(0.05);
    constexpr int n = 800;
    std::vector<int> proxies;
    std::vector<Aabb> tight;
    for (int i = 0; i < n; ++i) {
        tight.push_back(randomBox(rng, 15.0, 1.0));
        proxies.push_back(bp.createProxy(tight.back(), static_cast<std::uint64_t>(i), i < 100));
    }
    collectPairs(bp);
    std::uniform_real_distribution<double> step(-0.3, 0.3);
    for (int round = 0; round < 20; ++round) {
        std::vector<bool> moved(n, false);
        for (int i = 100; i < n; ++i) {
            if ((i + round) % 3 != 0) continue;
            const Vec3 dx = drawVec3(step, rng);
            const Aabb before = bp.fatAabb(proxies[static_cast<std::size_t>(i)]);
            tight[static_cast<std::size_t>(i)] = {tight[static_cast<std::size_t>(i)].min + dx, tight[static_cast<std::size_t>(i)].max + dx};
            bp.moveProxy(proxies[static_cast<std::size_t>(i)], tight[static_cast<std::size_t>(i)], dx);
            const Aabb& after = bp.fatAabb(proxies[static_cast<std::size_t>(i)]);
            ASSERT_TRUE(after.contains(tight[static_cast<std::size_t>(i)]));
            moved[static_cast<std::size_t>(i)] = before.min != after.min || before.max != after.max;
        }
        std::set<Pair> expected;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if ((moved[static_cast<std::size_t>(i)] || moved[static_cast<std::size_t>(j)]) &&
                    bp.fatAabb(proxies[static_cast<std::size_t>(i)]).overlaps(bp.fatAabb(proxies[static_cast<std::size_t>(j)])))
                    expected.insert({i, j});
        ASSERT_EQ(collectPairs(bp), expected) << "round " << round;
    }
    EXPECT_TRUE(bp.dynamicTree().isValid());
    EXPECT_TRUE(bp.staticTree().isValid());
}

TEST(BroadPhase, StaticStaticNeverReportedEvenWhenMoved) {
    BroadPhase bp(0.1);
    const Aabb unit{Vec3::Zero(), Vec3::Ones()};
    const int a = bp.createProxy(unit, 1, true);
    bp.createProxy(unit, 2, true);
    EXPECT_TRUE(collectPairs(bp).empty());
    bp.moveProxy(a, {Vec3::Constant(0.5), Vec3::Constant(1.5)}, Vec3::Zero());
    EXPECT_TRUE(collectPairs(bp).empty());
    bp.createProxy(unit, 0, false);
    EXPECT_EQ(collectPairs(bp), (std::set<Pair>{{0, 1}, {0, 2}}));
}

TEST(BroadPhase, FatBoxStretchesAlongDisplacementAndSmallMovesAreFree) {
    BroadPhase bp(0.1);
    const int p = bp.createProxy({Vec3::Zero(), Vec3::Ones()}, 7, false);
    bp.createProxy({Vec3(3, 0, 0), Vec3(4, 1, 1)}, 8, false);
    EXPECT_TRUE(collectPairs(bp).empty());
    // Leaves its fat box: re-inserted, stretched 1.5 m ahead along +x.
    const Aabb moved{Vec3(0.5, 0, 0), Vec3(1.5, 1, 1)};
    bp.moveProxy(p, moved, Vec3(1.5, 0, 0));
    EXPECT_NEAR(bp.fatAabb(p).max.x(), 1.5 + 0.1 + 1.5, 1e-12);
    EXPECT_NEAR(bp.fatAabb(p).min.x(), 0.5 - 0.1, 1e-12);
    EXPECT_NEAR(bp.fatAabb(p).max.y(), 1.1, 1e-12);
    EXPECT_EQ(collectPairs(bp), (std::set<Pair>{{7, 8}}));
    // Inside the fat box: nothing re-inserted, nothing reported.
    bp.moveProxy(p, {Vec3(0.6, 0, 0), Vec3(1.6, 1, 1)}, Vec3(1.5, 0, 0));
    EXPECT_TRUE(collectPairs(bp).empty());
    EXPECT_TRUE(bp.testOverlap(p, 1));
}

TEST(BroadPhase, DestroyedProxyIsNotReported) {
    BroadPhase bp(0.1);
    const Aabb unit{Vec3::Zero(), Vec3::Ones()};
    const int a = bp.createProxy(unit, 1, false);
    bp.createProxy(unit, 2, false);
    bp.destroyProxy(a);
    EXPECT_TRUE(collectPairs(bp).empty());
    // The freed slot is reused; the new proxy is reported with its own key.
    const int c = bp.createProxy(unit, 3, false);
    EXPECT_EQ(c, a);
    EXPECT_EQ(collectPairs(bp), (std::set<Pair>{{2, 3}}));
    EXPECT_EQ(bp.proxyCount(), 2);
    EXPECT_THROW(bp.fatAabb(99), std::out_of_range);
}

TEST(BroadPhase, CallbackMayCreateMoveAndDestroyProxies) {
    BroadPhase bp(0.1);
    const Aabb unit{Vec3::Zero(), Vec3::Ones()};
    const int a = bp.createProxy(unit, 1, false);
    bp.createProxy(unit, 2, false);
    int created = -1;
    bp.updatePairs([&](std::uint64_t, std::uint64_t) {
        bp.destroyProxy(a);
        created = bp.createProxy({Vec3::Constant(0.5), Vec3::Constant(1.5)}, 3, false);
    });
    EXPECT_EQ(collectPairs(bp), (std::set<Pair>{{2, 3}}));
    EXPECT_TRUE(bp.dynamicTree().isValid());
    EXPECT_EQ(bp.key(created), 3u);
}

TEST(BroadPhase, QueryAndRayCastSeeBothTrees) {
    BroadPhase bp(0.0);
    bp.createProxy({Vec3(-10, -1, -10), Vec3(10, 0, 10)}, 100, true);  // ground
    bp.createProxy({Vec3(2, 1, -0.5), Vec3(3, 2, 0.5)}, 5, false);
    std::set<std::uint64_t> found;
    bp.query({Vec3(-20, -20, -20), Vec3(20, 20, 20)}, [&](std::uint64_t k) { return found.insert(k), true; });
    EXPECT_EQ(found, (std::set<std::uint64_t>{5, 100}));

    // Ray along +x at y = 1.5 meets only the box; straight down meets the ground.
    std::vector<std::uint64_t> hits;
    bp.rayCast(Vec3(-5, 1.5, 0), Vec3::UnitX(), 50.0, [&](std::uint64_t k, double clip) { return hits.push_back(k), clip; });
    EXPECT_EQ(hits, std::vector<std::uint64_t>{5});
    hits.clear();
    bp.rayCast(Vec3(0, 5, 0), -Vec3::UnitY(), 50.0, [&](std::uint64_t k, double clip) { return hits.push_back(k), clip; });
    EXPECT_EQ(hits, std::vector<std::uint64_t>{100});
}

// Cost of pair finding for n boxes at constant density, every proxy moved (worst case).
// Asserted by work, not time: updatePairs runs one tree query per moved proxy, and the nodes a
// query examines must grow like log n (an unbalanced or poorly built tree grows like a power of
// n; n^2 pair finding, like n). Wall-clock times are printed for the record only: they vary by
// machine, load and sanitizer.
class PairScene {
public:
    explicit PairScene(int n) : n_(n), bp_(0.1) {
        std::mt19937 rng(1);
        const double world = 2.0 * std::cbrt(static_cast<double>(n));  // ~ constant density
        for (int i = 0; i < n; ++i) {
            boxes_.push_back(randomBox(rng, world, 0.5));
            proxies_.push_back(bp_.createProxy(boxes_.back(), static_cast<std::uint64_t>(i), false));
        }
        bp_.updatePairs([](std::uint64_t, std::uint64_t) {});
    }
    /// Moves every box out of its fat box, then times updatePairs (seconds).
    double timeUpdate() {
        shift_ = -shift_;
        for (std::size_t i = 0; i < boxes_.size(); ++i) {
            boxes_[i] = {boxes_[i].min + Vec3(shift_, 0, 0), boxes_[i].max + Vec3(shift_, 0, 0)};
            bp_.moveProxy(proxies_[i], boxes_[i], Vec3::Zero());
        }
        const auto t0 = std::chrono::steady_clock::now();
        pairs_ = 0;
        bp_.updatePairs([&](std::uint64_t, std::uint64_t) { ++pairs_; });
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    int n() const { return n_; }
    std::size_t pairs() const { return pairs_; }
    int height() const { return bp_.dynamicTree().height(); }
    /// Mean number of tree nodes examined by the query of one moved proxy.
    double meanQueryCost() const {
        double total = 0.0;
        for (const int p : proxies_) total += bp_.dynamicTree().queryCost(bp_.fatAabb(p));
        return total / n_;
    }

private:
    int n_;
    BroadPhase bp_;
    std::vector<Aabb> boxes_;
    std::vector<int> proxies_;
    double shift_ = 0.5;
    std::size_t pairs_ = 0;
};

TEST(BroadPhase, UpdatePairsCostGrowsLikeNLogN) {
    PairScene small(1000), large(8000);
    double bestSmall = 1e9, bestLarge = 1e9;
    for (int rep = 0; rep < 5; ++rep) {  // interleaved, so that load spikes hit both alike
        bestSmall = std::min(bestSmall, small.timeUpdate());
        bestLarge = std::min(bestLarge, large.timeUpdate());
    }
    for (const auto& [scene, best] : {std::pair<const PairScene*, double>{&small, bestSmall}, {&large, bestLarge}})
        std::cout << "[ cost     ] updatePairs, " << scene->n() << " boxes all moved: " << best * 1e6 << " us, "
                  << scene->pairs() << " pairs, tree height " << scene->height() << ", "
                  << scene->meanQueryCost() << " nodes examined per query\n";
    // log2 n goes from 10 to 13 (x1.3); allow x1.8 and a constant of 6 nodes per level.
    EXPECT_LT(small.meanQueryCost(), 6.0 * std::log2(1000.0));
    EXPECT_LT(large.meanQueryCost(), 6.0 * std::log2(8000.0));
    EXPECT_LT(large.meanQueryCost(), 1.8 * small.meanQueryCost());
}

// ---------------------------------------------------------------------------------------------
// MeshData

TEST(MeshData, BuildsNormalsAndTriangleTree) {
    ShapeDef def = ShapeDef::mesh({Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(-1, 0, 1), Vec3(5, 0, 5),
                                   Vec3(6, 0, 5), Vec3(5, 1, 5)},
                                  {0, 2, 1, 0, 3, 2, 4, 5, 6});
    const auto mesh = MeshData::build(def);
    ASSERT_EQ(mesh->triangles.size(), 3u);
    EXPECT_TRUE(mesh->normals[0].isApprox(Vec3::UnitY()));  // counter-clockwise seen from +y
    EXPECT_TRUE(mesh->normals[1].isApprox(Vec3::UnitY()));
    EXPECT_TRUE(mesh->normals[2].isApprox(Vec3::UnitZ()));
    EXPECT_TRUE(mesh->tree.isValid());
    std::set<int> found;
    mesh->queryTriangles({Vec3(0.5, -0.1, 0.5), Vec3(0.6, 0.1, 0.6)}, [&](int t) { return found.insert(t), true; });
    EXPECT_EQ(found, (std::set<int>{0, 1}));
    found.clear();
    mesh->queryTriangles({Vec3(5.5, 0.5, 4.9), Vec3(5.6, 0.6, 5.1)}, [&](int t) { return found.insert(t), true; });
    EXPECT_EQ(found, (std::set<int>{2}));
}

}  // namespace
}  // namespace anyphys::native
