// AheadSweep: the look-ahead pass's broad phase must list exactly the pairs a test of every pair
// would (bounds apart, within a moving shape's reach), each once, in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "ode_ahead_sweep.hpp"
#include "../../random_draws.hpp"

namespace anyphys {
namespace {

using ode::AheadSweep;
using ode::SweptBounds;

SweptBounds boundsAround(const Vec3& centre, const Vec3& half, double reach) {
    SweptBounds b{};
    for (int k = 0; k < 3; ++k) {
        b.lo[k] = centre[k] - half[k];
        b.hi[k] = centre[k] + half[k];
    }
    b.reach = reach;
    return b;
}

bool grownOverlaps(const SweptBounds& a, const SweptBounds& b, double reach) {
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] - reach > b.hi[k] || b.lo[k] > a.hi[k] + reach) return false;
    return true;
}

// Every pair tested: the list the sweep must give.
std::vector<AheadSweep::Pair> everyPairTested(const std::vector<SweptBounds>& shapes) {
    std::vector<AheadSweep::Pair> pairs;
    for (std::uint32_t i = 0; i < shapes.size(); ++i)
        for (std::uint32_t j = 0; j < shapes.size(); ++j) {
            const SweptBounds &a = shapes[i], &b = shapes[j];
            if (i == j || a.reach <= 0.0 || grownOverlaps(a, b, 0.0) || !grownOverlaps(a, b, a.reach)) continue;
            if (b.reach > 0.0 && j < i && grownOverlaps(b, a, b.reach)) continue;  // listed from j
            pairs.emplace_back(i, j);
        }
    return pairs;
}

TEST(OdeAheadSweep, ListsWhatTestingEveryPairFinds) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> where(-6.0, 6.0), size(0.05, 0.6), chance(0.0, 1.0), reach(0.0, 0.4);
    std::size_t listed = 0;
    for (int round = 0; round < 40; ++round) {
        // Odd rounds: a few moving shapes, which the sweep tests against every shape directly;
        // even rounds: many, which it sorts.
        const double moving = round % 2 ? 0.01 : 0.3;
        std::vector<SweptBounds> shapes;
        for (int i = 0; i < 300; ++i) {
            const Vec3 centre = test::drawVec3(where, rng);
            const Vec3 half = test::drawVec3(size, rng);
            const double moves = chance(rng) < moving ? reach(rng) : 0.0;
            shapes.push_back(boundsAround(centre, half, moves));
        }
        // Shapes the sweep keeps out of its sorted list: a ground, a wall, a large mover, a plane's
        // half space (infinite below y = -5).
        shapes.push_back(boundsAround(Vec3(0, -6.5, 0), Vec3(8, 0.5, 8), 0.0));
        shapes.push_back(boundsAround(Vec3(6.5, 0, 0), Vec3(0.5, 8, 8), 0.0));
        shapes.push_back(boundsAround(Vec3(0, 2, 0), Vec3(5, 0.1, 0.3), 0.3));
        SweptBounds plane = boundsAround(Vec3::Zero(), Vec3::Zero(), 0.0);
        for (int k = 0; k < 3; ++k) {
            plane.lo[k] = -std::numeric_limits<double>::infinity();
            plane.hi[k] = k == 1 ? -5.0 : std::numeric_limits<double>::infinity();
        }
        shapes.push_back(plane);
        AheadSweep sweep;
        const std::vector<AheadSweep::Pair> expected = everyPairTested(shapes);
        ASSERT_EQ(sweep.find(shapes), expected) << "round " << round;
        listed += expected.size();
    }
    EXPECT_GT(listed, 600u);  // the draws do make pairs, of every kind
}

// A falling grid: every box moves, its neighbours a gap apart; each gap within reach is one pair.
TEST(OdeAheadSweep, GridOfMovingBoxesGivesEachGapOnce) {
    std::vector<SweptBounds> shapes;
    constexpr int n = 6;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) shapes.push_back(boundsAround(Vec3(1.1 * i, 1.1 * j, 1.1 * k), Vec3(0.5, 0.5, 0.5), 0.15));
    AheadSweep sweep;
    // Face neighbours 0.1 apart (within 0.15) along three axes; edge and corner neighbours are 0.1
    // apart along two or three axes at once, which bounds grown by 0.15 also reach.
    const auto& pairs = sweep.find(shapes);
    EXPECT_EQ(pairs, everyPairTested(shapes));
    const std::size_t faces = 3 * n * n * (n - 1), edges = 6 * n * (n - 1) * (n - 1), corners = 4 * (n - 1) * (n - 1) * (n - 1);
    EXPECT_EQ(pairs.size(), faces + edges + corners);
    // At rest nothing is listed.
    for (SweptBounds& s : shapes) s.reach = 0.0;
    EXPECT_TRUE(sweep.find(shapes).empty());
}

}  // namespace
}  // namespace anyphys
