// The contact tracker reuses its buffers: once a step has listed as many pairs as any later step
// will, later steps allocate nothing, however the number of touching pairs goes up and down
// beneath that mark (a settling pile loses and regains contacts every step). Counted by the
// replaced global operator new of step_allocations.hpp (the only replacement in this program).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "../backends/step_allocations.hpp"
#include "anyphys/listeners/contact_tracker.hpp"

namespace anyphys {
namespace {

TEST(ContactTrackerAllocations, FewerPairsThanTheMarkAllocateNothing) {
    constexpr std::uint32_t kPairs = 300;  // above the tracker's comparison-sort cutoff: the radix path runs
    constexpr int kSteps = 200;
    std::mt19937 random(7);  // fixed seed: the same sequence of pair counts on every run

    // Every step's input is built before counting starts: pair i is (i, i + 1000), one point
    // each, listed in a shuffled order. The first step lists all of them (the mark); later
    // steps a random subset of random size, so the number of events rises and falls.
    const std::vector<ContactPoint> points(kPairs, ContactPoint{Vec3(0, 0, 0), 0.001, 0.0});
    std::vector<std::vector<TouchingRange>> steps(kSteps);
    for (int s = 0; s < kSteps; ++s) {
        std::vector<std::uint32_t> order(kPairs);
        std::iota(order.begin(), order.end(), 0u);
        std::shuffle(order.begin(), order.end(), random);
        const std::uint32_t count = s == 0 ? kPairs : std::uniform_int_distribution<std::uint32_t>(0, kPairs)(random);
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t i = order[k];
            steps[static_cast<std::size_t>(s)].push_back(
                {BodyId{i, 0}, BodyId{i + 1000, 0}, false, false, false, Vec3::UnitY(), i, 1});
        }
    }

    ContactTracker tracker;
    std::vector<ContactEvent> events;
    tracker.update(steps[0], points, events);
    ASSERT_EQ(events.size(), kPairs);  // every pair enters

    std::size_t fewest = kPairs;
    test::StepAllocations::start();
    for (int s = 1; s < kSteps; ++s) {
        tracker.update(steps[static_cast<std::size_t>(s)], points, events);
        fewest = std::min(fewest, tracker.activePairs());
    }
    EXPECT_EQ(test::StepAllocations::stop(), 0u);
    EXPECT_LT(fewest, kPairs / 10);  // the sequence did empty most of the storage into the spares
}

}  // namespace
}  // namespace anyphys
