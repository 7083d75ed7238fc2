#include <map>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "anyphys/listeners/contact_tracker.hpp"

using namespace anyphys;

namespace {

BodyId body(std::uint32_t index, std::uint32_t generation = 0) { return BodyId{index, generation}; }

TouchingPair touch(BodyId a, BodyId b, const Vec3& normal = Vec3(0, 1, 0), bool trigger = false) {
    TouchingPair p;
    p.bodyA = a;
    p.bodyB = b;
    p.trigger = trigger;
    p.normal = normal;
    if (!trigger) p.points.push_back(ContactPoint{Vec3(1, 2, 3), 0.01, 0.0});
    return p;
}

// Each event as (phase, a, b) for compact comparisons.
struct Summary {
    ContactPhase phase;
    std::uint32_t a, b;
    friend bool operator==(const Summary&, const Summary&) = default;
};
std::ostream& operator<<(std::ostream& os, const Summary& s) {
    const char* names[] = {"Enter", "Stay", "Exit"};
    return os << names[static_cast<int>(s.phase)] << "(" << s.a << "," << s.b << ")";
}
std::vector<Summary> summary(const std::vector<ContactEvent>& events) {
    std::vector<Summary> out;
    for (const auto& e : events) out.push_back({e.phase, e.bodyA.index, e.bodyB.index});
    return out;
}

using P = ContactPhase;

}  // namespace

TEST(ContactTracker, EnterStayExitSequence) {
    ContactTracker t;
    const auto enter = t.update({touch(body(1), body(2))});
    ASSERT_EQ(summary(enter), (std::vector<Summary>{{P::Enter, 1, 2}}));
    EXPECT_EQ(enter[0].points.size(), 1u);
    EXPECT_EQ(enter[0].normal, Vec3(0, 1, 0));
    EXPECT_FALSE(enter[0].trigger);
    EXPECT_EQ(t.activePairs(), 1u);

    EXPECT_EQ(summary(t.update({touch(body(1), body(2))})), (std::vector<Summary>{{P::Stay, 1, 2}}));
    EXPECT_EQ(summary(t.update({touch(body(1), body(2))})), (std::vector<Summary>{{P::Stay, 1, 2}}));

    const auto exit = t.update({});
    ASSERT_EQ(summary(exit), (std::vector<Summary>{{P::Exit, 1, 2}}));
    EXPECT_FALSE(exit[0].removal);
    EXPECT_TRUE(exit[0].points.empty());
    EXPECT_EQ(t.activePairs(), 0u);
    EXPECT_TRUE(t.update({}).empty());

    // Touching again after an exit is a fresh enter.
    EXPECT_EQ(summary(t.update({touch(body(1), body(2))})), (std::vector<Summary>{{P::Enter, 1, 2}}));
}

TEST(ContactTracker, SwappedPairOrderIsNormalisedAndNormalFlipped) {
    ContactTracker t;
    const auto events = t.update({touch(body(7), body(3), Vec3(1, 0, 0))});
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].bodyA, body(3));
    EXPECT_EQ(events[0].bodyB, body(7));
    EXPECT_EQ(events[0].normal, Vec3(-1, 0, 0));  // still points from A to B
    EXPECT_EQ(events[0].points[0].position, Vec3(1, 2, 3));  // world-frame points are unchanged

    // The same pair reported in the canonical order next step is the same pair: a stay.
    const auto stay = t.update({touch(body(3), body(7), Vec3(-1, 0, 0))});
    EXPECT_EQ(summary(stay), (std::vector<Summary>{{P::Stay, 3, 7}}));

    // Generations order after indices: (5, gen 1) < (6, gen 0).
    ContactTracker g;
    const auto ge = g.update({touch(body(6, 0), body(5, 1))});
    EXPECT_EQ(ge[0].bodyA, body(5, 1));
}

TEST(ContactTracker, TriggersGetEnterAndExitButNoStay) {
    ContactTracker t;
    const auto enter = t.update({touch(body(1), body(2), Vec3(0, 1, 0), true)});
    ASSERT_EQ(summary(enter), (std::vector<Summary>{{P::Enter, 1, 2}}));
    EXPECT_TRUE(enter[0].trigger);
    EXPECT_TRUE(enter[0].points.empty());

    EXPECT_TRUE(t.update({touch(body(1), body(2), Vec3(0, 1, 0), true)}).empty());
    EXPECT_TRUE(t.update({touch(body(1), body(2), Vec3(0, 1, 0), true)}).empty());
    EXPECT_EQ(t.activePairs(), 1u);

    const auto exit = t.update({});
    ASSERT_EQ(summary(exit), (std::vector<Summary>{{P::Exit, 1, 2}}));
    EXPECT_TRUE(exit[0].trigger);
}

TEST(ContactTracker, SleepingPairNeitherExitsNorStays) {
    ContactTracker t;
    std::set<BodyId> sleeping;
    const auto asleep = [&](BodyId id) { return sleeping.count(id) > 0; };
    ASSERT_EQ(t.update({touch(body(1), body(2)), touch(body(3), body(4))}, asleep).size(), 2u);

    // Body 2 falls asleep; the backend stops reporting its pair. No exit, no stay.
    sleeping.insert(body(2));
    EXPECT_EQ(summary(t.update({touch(body(3), body(4))}, asleep)), (std::vector<Summary>{{P::Stay, 3, 4}}));
    // Even when the backend still reports the sleeping pair, it gets no stay.
    EXPECT_EQ(summary(t.update({touch(body(1), body(2)), touch(body(3), body(4))}, asleep)),
              (std::vector<Summary>{{P::Stay, 3, 4}}));
    EXPECT_EQ(t.activePairs(), 2u);

    // Woken up and still touching: stays resume, no second enter.
    sleeping.clear();
    EXPECT_EQ(summary(t.update({touch(body(1), body(2))}, asleep)),
              (std::vector<Summary>{{P::Exit, 3, 4}, {P::Stay, 1, 2}}));
    // Woken up and apart: exit.
    EXPECT_EQ(summary(t.update({}, asleep)), (std::vector<Summary>{{P::Exit, 1, 2}}));
}

TEST(ContactTracker, RemoveBodyEndsItsPairsWithRemovalExits) {
    ContactTracker t;
    t.update({touch(body(1), body(2)), touch(body(2), body(3)), touch(body(3), body(4)),
              touch(body(4), body(5), Vec3(0, 1, 0), true)});
    ASSERT_EQ(t.activePairs(), 4u);

    const auto removed = t.removeBody(body(2));
    ASSERT_EQ(summary(removed), (std::vector<Summary>{{P::Exit, 1, 2}, {P::Exit, 2, 3}}));
    for (const auto& e : removed) EXPECT_TRUE(e.removal);
    EXPECT_EQ(t.activePairs(), 2u);

    // The trigger flag is kept on a removal exit.
    const auto removedTrigger = t.removeBody(body(5));
    ASSERT_EQ(removedTrigger.size(), 1u);
    EXPECT_TRUE(removedTrigger[0].trigger);
    EXPECT_TRUE(removedTrigger[0].removal);

    // The removed pairs are forgotten: no second exit next step; others carry on.
    EXPECT_EQ(summary(t.update({touch(body(3), body(4))})), (std::vector<Summary>{{P::Stay, 3, 4}}));
    EXPECT_TRUE(t.removeBody(body(99)).empty());
}

TEST(ContactTracker, DuplicateReportsCountOnceFirstWins) {
    ContactTracker t;
    const auto events = t.update({touch(body(1), body(2), Vec3(0, 1, 0)), touch(body(2), body(1), Vec3(0, 0, 1)),
                                  touch(body(1), body(2), Vec3(1, 0, 0))});
    ASSERT_EQ(summary(events), (std::vector<Summary>{{P::Enter, 1, 2}}));
    EXPECT_EQ(events[0].normal, Vec3(0, 1, 0));
    EXPECT_EQ(t.activePairs(), 1u);
    const auto stays = t.update({touch(body(1), body(2)), touch(body(1), body(2))});
    EXPECT_EQ(summary(stays), (std::vector<Summary>{{P::Stay, 1, 2}}));
}

TEST(ContactTracker, EventsSortedExitsThenEntersThenStaysAndOneEventPerPair) {
    ContactTracker t;
    t.update({touch(body(1), body(2)), touch(body(5), body(6)), touch(body(3), body(4))});
    const auto events = t.update({touch(body(7), body(8)), touch(body(3), body(4)), touch(body(0), body(9)),
                                  touch(body(1), body(2))});
    EXPECT_EQ(summary(events),
              (std::vector<Summary>{{P::Exit, 5, 6}, {P::Enter, 0, 9}, {P::Enter, 7, 8}, {P::Stay, 1, 2}, {P::Stay, 3, 4}}));

    // Never an enter and an exit (or any two events) for the same pair in one step.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> perPair;
    for (const auto& s : summary(events)) ++perPair[{s.a, s.b}];
    for (const auto& [pair, count] : perPair) EXPECT_EQ(count, 1) << pair.first << "," << pair.second;

    // A self-pair is not a contact.
    EXPECT_EQ(summary(t.update({touch(body(4), body(4))})).size(), 4u);  // exits of the four live pairs only
    EXPECT_EQ(t.activePairs(), 0u);
}

TEST(ContactTracker, ClearForgetsEverythingSilently) {
    ContactTracker t;
    t.update({touch(body(1), body(2))});
    t.clear();
    EXPECT_EQ(t.activePairs(), 0u);
    EXPECT_TRUE(t.update({}).empty());
}
