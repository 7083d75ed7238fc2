#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
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

// A compound whose sensor child overlaps a body its solid child touches: the collision and the
// trigger are two pairs of the same bodies, each entering and exiting on its own.
TEST(ContactTracker, CollisionAndTriggerOfOneBodyPairAreTwoPairs) {
    ContactTracker t;
    const auto both = t.update({touch(body(1), body(2), Vec3(0, 1, 0), true), touch(body(2), body(1))});
    ASSERT_EQ(summary(both), (std::vector<Summary>{{P::Enter, 1, 2}, {P::Enter, 1, 2}}));
    EXPECT_FALSE(both[0].trigger);  // collisions first in pair order
    EXPECT_TRUE(both[1].trigger);
    EXPECT_EQ(t.activePairs(), 2u);

    const auto stay = t.update({touch(body(1), body(2)), touch(body(1), body(2), Vec3(0, 1, 0), true)});
    ASSERT_EQ(summary(stay), (std::vector<Summary>{{P::Stay, 1, 2}}));  // triggers never stay
    EXPECT_FALSE(stay[0].trigger);

    const auto triggerOff = t.update({touch(body(1), body(2))});
    ASSERT_EQ(summary(triggerOff), (std::vector<Summary>{{P::Exit, 1, 2}, {P::Stay, 1, 2}}));
    EXPECT_TRUE(triggerOff[0].trigger);

    const auto triggerBack = t.update({touch(body(1), body(2), Vec3(0, 1, 0), true), touch(body(1), body(2))});
    ASSERT_EQ(summary(triggerBack), (std::vector<Summary>{{P::Enter, 1, 2}, {P::Stay, 1, 2}}));
    EXPECT_TRUE(triggerBack[0].trigger);

    const auto off = t.update({});
    ASSERT_EQ(off.size(), 2u);
    EXPECT_EQ(off[0].trigger, false);
    EXPECT_EQ(off[1].trigger, true);
    EXPECT_EQ(t.activePairs(), 0u);
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

// ---- the allocation-free update --------------------------------------------------------------

namespace {

// The rules of the tracker's header, written the plain way: a map of touching pairs, each a
// (body, body, trigger) triple (a collision and a trigger of the same bodies are two pairs).
// Some pairs a listing lacks still touch (an engine finds them within reach, WorldPeer::
// reportNearPair): those for which `holds` is true this step, with a contact of their own.
struct NearRule {
    int step = 0;
    bool holds(BodyId a, BodyId b) const { return (a.index * 7 + b.index * 3 + static_cast<std::uint32_t>(step)) % 3 == 0; }
    TouchingPair contact(BodyId a, BodyId b) const {
        TouchingPair p = touch(a, b, Vec3(0.5, -1.0, double(step)));
        p.points = {{Vec3(double(a.index), double(b.index), double(step)), -0.002, 0.0}};
        return p;
    }
};

class ReferenceTracker {
public:
    using Key = std::tuple<BodyId, BodyId, bool>;

    std::vector<ContactEvent> update(std::vector<TouchingPair> touching, const ContactTracker::AsleepQuery& asleep,
                                     const NearRule* near = nullptr) {
        std::map<Key, TouchingPair> now;  // first report of each pair
        for (TouchingPair& p : touching) {
            if (p.bodyA == p.bodyB) continue;
            if (p.bodyB < p.bodyA) {
                std::swap(p.bodyA, p.bodyB);
                p.normal = -p.normal;
            }
            now.try_emplace({p.bodyA, p.bodyB, p.trigger}, p);
        }
        const auto sleeping = [&](const Key& k) { return asleep(std::get<0>(k)) || asleep(std::get<1>(k)); };
        std::vector<ContactEvent> exits, enters, stays;
        std::set<Key> next;
        const auto stay = [](const TouchingPair& p) {
            ContactEvent e;
            e.bodyA = p.bodyA;
            e.bodyB = p.bodyB;
            e.phase = ContactPhase::Stay;
            e.hasImpulses = p.hasImpulses;
            e.normal = p.normal;
            e.points = p.points;
            return e;
        };
        for (const Key& key : active_) {
            if (now.contains(key)) continue;
            if (sleeping(key)) {
                next.insert(key);
                continue;
            }
            if (near && !std::get<2>(key) && near->holds(std::get<0>(key), std::get<1>(key))) {  // stays, near
                next.insert(key);
                stays.push_back(stay(near->contact(std::get<0>(key), std::get<1>(key))));
                continue;
            }
            ContactEvent e;
            e.bodyA = std::get<0>(key);
            e.bodyB = std::get<1>(key);
            e.phase = ContactPhase::Exit;
            e.trigger = std::get<2>(key);
            exits.push_back(e);
        }
        for (const auto& [key, p] : now) {
            next.insert(key);
            const bool before = active_.contains(key);
            if (before && (p.trigger || sleeping(key))) continue;
            ContactEvent e;
            e.bodyA = p.bodyA;
            e.bodyB = p.bodyB;
            e.phase = before ? ContactPhase::Stay : ContactPhase::Enter;
            e.trigger = p.trigger;
            e.hasImpulses = p.hasImpulses;
            e.normal = p.normal;
            if (!p.trigger) e.points = p.points;
            (before ? stays : enters).push_back(e);
        }
        active_ = next;
        std::sort(stays.begin(), stays.end(), [](const ContactEvent& x, const ContactEvent& y) {  // in pair order
            return std::tie(x.bodyA, x.bodyB) < std::tie(y.bodyA, y.bodyB);
        });
        exits.insert(exits.end(), enters.begin(), enters.end());
        exits.insert(exits.end(), stays.begin(), stays.end());
        return exits;
    }

    std::vector<ContactEvent> removeBody(BodyId body) {
        std::vector<ContactEvent> exits;
        for (auto it = active_.begin(); it != active_.end();) {
            if (std::get<0>(*it) != body && std::get<1>(*it) != body) {
                ++it;
                continue;
            }
            ContactEvent e;
            e.bodyA = std::get<0>(*it);
            e.bodyB = std::get<1>(*it);
            e.phase = ContactPhase::Exit;
            e.trigger = std::get<2>(*it);
            e.removal = true;
            exits.push_back(e);
            it = active_.erase(it);
        }
        return exits;
    }

private:
    std::set<Key> active_;
};

void expectSameEvents(const std::vector<ContactEvent>& got, const std::vector<ContactEvent>& expected, int step) {
    ASSERT_EQ(got.size(), expected.size()) << "step " << step;
    for (std::size_t k = 0; k < got.size(); ++k) {
        const ContactEvent& g = got[k];
        const ContactEvent& e = expected[k];
        SCOPED_TRACE("step " + std::to_string(step) + ", event " + std::to_string(k));
        EXPECT_EQ(g.bodyA, e.bodyA);
        EXPECT_EQ(g.bodyB, e.bodyB);
        EXPECT_EQ(g.phase, e.phase);
        EXPECT_EQ(g.trigger, e.trigger);
        EXPECT_EQ(g.removal, e.removal);
        EXPECT_EQ(g.hasImpulses, e.hasImpulses);
        EXPECT_EQ(g.normal, e.normal);
        ASSERT_EQ(g.points.size(), e.points.size());
        for (std::size_t i = 0; i < g.points.size(); ++i) {
            EXPECT_EQ(g.points[i].position, e.points[i].position);
            EXPECT_EQ(g.points[i].depth, e.points[i].depth);
            EXPECT_EQ(g.points[i].normalImpulse, e.points[i].normalImpulse);
        }
    }
}

// The flat form of a step's pairs, as World builds it: one shared point array.
struct FlatStep {
    std::vector<TouchingRange> ranges;
    std::vector<ContactPoint> points;
};
FlatStep flatten(const std::vector<TouchingPair>& pairs, const ContactTracker::AsleepQuery& asleep) {
    FlatStep flat;
    for (const TouchingPair& p : pairs) {
        flat.ranges.push_back({p.bodyA, p.bodyB, p.trigger, p.hasImpulses, asleep(p.bodyA) || asleep(p.bodyB), p.normal,
                               static_cast<std::uint32_t>(flat.points.size()), static_cast<std::uint32_t>(p.points.size())});
        flat.points.insert(flat.points.end(), p.points.begin(), p.points.end());
    }
    return flat;
}

// The tracker's near query for `rule`, appending its contacts to the step's flat arrays as World
// does (the points to the shared array, which the events are then written from).
ContactTracker::NearQuery nearQuery(const NearRule& rule, FlatStep& flat) {
    return [&rule, &flat](BodyId a, BodyId b, std::vector<TouchingRange>& touching) {
        if (!rule.holds(a, b)) return false;
        const TouchingPair p = rule.contact(a, b);
        touching.push_back({a, b, false, p.hasImpulses, false, p.normal, static_cast<std::uint32_t>(flat.points.size()),
                            static_cast<std::uint32_t>(p.points.size())});
        flat.points.insert(flat.points.end(), p.points.begin(), p.points.end());
        return true;
    };
}

// The randomized cases' bodies: a generator, each body's generation (0 to 2), and the bodies
// asleep this step with the query that asks about them.
struct RandomBodies {
    RandomBodies(std::mt19937::result_type seed, std::uint32_t count) : random(seed), generation(count) {
        for (auto& g : generation) g = random() % 3;
    }
    RandomBodies(const RandomBodies&) = delete;  // `asleep` refers to this object's `sleeping`
    RandomBodies& operator=(const RandomBodies&) = delete;
    std::mt19937 random;
    std::vector<std::uint32_t> generation;
    std::set<std::uint32_t> sleeping;
    ContactTracker::AsleepQuery asleep = [this](BodyId id) { return sleeping.contains(id.index); };
};

}  // namespace

// Random steps (pairs coming, staying and going, in any order, reported twice, triggers, sleeping
// bodies, generations, piles large enough for the radix sort, repeated listings, removed bodies):
// both forms of update give exactly the events of the reference.
TEST(ContactTracker, FlatUpdateFollowsTheRulesOverRandomSteps) {
    constexpr std::uint32_t kBodies = 40;
    RandomBodies bodies(12345, kBodies);
    std::mt19937& random = bodies.random;  // plain references: lambdas below capture them
    const std::vector<std::uint32_t>& generation = bodies.generation;
    std::set<std::uint32_t>& sleeping = bodies.sleeping;
    const ContactTracker::AsleepQuery& asleep = bodies.asleep;
    ReferenceTracker reference, nearReference;
    ContactTracker perPair, flat, withNear;
    std::vector<ContactEvent> events, nearEvents;
    std::vector<TouchingPair> pairs;
    NearRule near;
    for (int step = 0; step < 300; ++step) {
        near.step = step;
        if (step % 7 != 3) {  // otherwise the same listing as the last step (a resting pile)
            const int keep = static_cast<int>(random() % 4);  // 0: all new; 3: mostly the same pairs
            std::vector<TouchingPair> kept;
            for (const TouchingPair& p : pairs)
                if (static_cast<int>(random() % 4) < keep) kept.push_back(p);
            pairs = kept;
            const std::size_t fresh = step % 5 == 0 ? 150 : random() % 12;  // > 64 pairs: the radix sort
            for (std::size_t k = 0; k < fresh; ++k) {
                const std::uint32_t a = random() % kBodies, b = random() % kBodies;
                const bool trigger = random() % 10 == 0;
                TouchingPair p = touch(body(a, generation[a]), body(b, generation[b]),
                                       Vec3(double(random() % 5), 1.0, double(step)), trigger);
                p.hasImpulses = random() % 2 == 0;
                if (!trigger)
                    for (std::size_t i = random() % 4; i > 0; --i)
                        p.points.push_back({Vec3(double(step), double(k), double(i)), 0.001 * double(i), double(random() % 9)});
                pairs.insert(pairs.begin() + static_cast<std::ptrdiff_t>(random() % (pairs.size() + 1)), p);
                if (random() % 8 == 0) pairs.push_back(p);  // reported twice
            }
            std::shuffle(pairs.begin(), pairs.end(), random);
        }
        sleeping.clear();
        if (step % 3 == 0)
            for (int k = 0; k < 4; ++k) sleeping.insert(random() % kBodies);

        if (step % 7 == 2) {  // a body destroyed; the next step lists the same pairs (its own included)
            const std::uint32_t gone = random() % kBodies;
            const std::vector<ContactEvent> removed = reference.removeBody(body(gone, generation[gone]));
            expectSameEvents(perPair.removeBody(body(gone, generation[gone])), removed, step);
            expectSameEvents(flat.removeBody(body(gone, generation[gone])), removed, step);
            expectSameEvents(withNear.removeBody(body(gone, generation[gone])),
                             nearReference.removeBody(body(gone, generation[gone])), step);
        }
        const std::vector<ContactEvent> expected = reference.update(pairs, asleep);
        expectSameEvents(perPair.update(pairs, asleep), expected, step);
        FlatStep f = flatten(pairs, asleep);
        flat.update(f.ranges, f.points, events, asleep);
        expectSameEvents(events, expected, step);
        // With a near query: diff, then write, as World does (the query appends to the points).
        FlatStep g = flatten(pairs, asleep);
        withNear.diff(g.ranges, asleep, nearQuery(near, g));
        withNear.writeEvents(g.ranges, g.points, nearEvents);
        expectSameEvents(nearEvents, nearReference.update(pairs, asleep, &near), step);
        if (::testing::Test::HasFatalFailure()) return;
    }
}

// An engine's contact list keeps its order from step to step, and a pile gains and loses a few
// pairs each step: the listings here change in a few places (pairs gone, new ones anywhere,
// including first; one moved far; a pair listed twice now and then; bodies asleep or destroyed),
// which the tracker diffs without sorting the whole listing (diffFewChanges), falling back to the
// sort when a pair is listed twice or too much changed. Every step gives exactly the reference's
// events.
TEST(ContactTracker, ListingsChangingInAFewPlacesFollowTheRules) {
    constexpr std::uint32_t kBodies = 60;
    RandomBodies bodies(2468, kBodies);
    std::vector<TouchingPair> pairs;
    const auto freshPair = [&](int step) {  // a pair not listed yet (duplicates are made on purpose below)
        std::uint32_t a = 0, b = 0;
        const auto listed = [&](const TouchingPair& p) {
            return std::minmax(p.bodyA.index, p.bodyB.index) == std::minmax(a, b);
        };
        do {
            a = bodies.random() % kBodies;
            b = bodies.random() % kBodies;
        } while (a == b || std::any_of(pairs.begin(), pairs.end(), listed));
        const Vec3 normal(double(bodies.random() % 5), 1.0, double(step));
        TouchingPair p = touch(body(a, bodies.generation[a]), body(b, bodies.generation[b]), normal, bodies.random() % 20 == 0);
        p.hasImpulses = bodies.random() % 2 == 0;
        return p;
    };
    for (int k = 0; k < 400; ++k) pairs.push_back(freshPair(0));
    ReferenceTracker reference, nearReference;
    ContactTracker tracker, withNear;
    std::vector<ContactEvent> events, nearEvents;
    NearRule near;
    const auto at = [&](std::size_t size) { return static_cast<std::ptrdiff_t>(bodies.random() % (size + 1)); };
    for (int step = 0; step < 400; ++step) {
        near.step = step;
        if (step > 0 && step % 5 != 0) {  // every fifth step lists what the last one did
            for (int k = static_cast<int>(bodies.random() % 4); k > 0 && !pairs.empty(); --k)  // gone
                pairs.erase(pairs.begin() + static_cast<std::ptrdiff_t>(bodies.random() % pairs.size()));
            for (int k = static_cast<int>(bodies.random() % 4); k > 0; --k)  // new, anywhere
                pairs.insert(pairs.begin() + at(pairs.size()), freshPair(step));
            if (bodies.random() % 2 == 0) pairs.insert(pairs.begin(), freshPair(step));  // first, as Box2D adds them
            if (bodies.random() % 4 == 0 && !pairs.empty()) {  // moved far
                const TouchingPair moved = pairs[bodies.random() % pairs.size()];
                std::erase_if(pairs, [&](const TouchingPair& p) { return p.bodyA == moved.bodyA && p.bodyB == moved.bodyB; });
                pairs.insert(pairs.begin() + at(pairs.size()), moved);
            }
            std::erase_if(pairs, [](const TouchingPair& p) { return p.normal.y() < 0.0; });  // last step's repeat
            if (bodies.random() % 10 == 0 && !pairs.empty()) {  // the same pair listed twice, the other way round, once
                TouchingPair twice = pairs[bodies.random() % pairs.size()];
                std::swap(twice.bodyA, twice.bodyB);
                twice.normal = -twice.normal;
                pairs.insert(pairs.begin() + at(pairs.size()), twice);
            }
            for (TouchingPair& p : pairs)  // new points on the same pairs
                for (ContactPoint& c : p.points) c.depth = 0.001 * double(bodies.random() % 7);
        }
        bodies.sleeping.clear();
        if (step % 3 == 0)
            for (int k = 0; k < 3; ++k) bodies.sleeping.insert(bodies.random() % kBodies);
        if (step % 11 == 6) {  // a body destroyed: its pairs end now, whatever the listing says next
            const std::uint32_t gone = bodies.random() % kBodies;
            const BodyId destroyed = body(gone, bodies.generation[gone]);
            expectSameEvents(tracker.removeBody(destroyed), reference.removeBody(destroyed), step);
            expectSameEvents(withNear.removeBody(destroyed), nearReference.removeBody(destroyed), step);
        }
        const std::vector<ContactEvent> expected = reference.update(pairs, bodies.asleep);
        FlatStep f = flatten(pairs, bodies.asleep);
        tracker.update(f.ranges, f.points, events, bodies.asleep);
        expectSameEvents(events, expected, step);
        FlatStep g = flatten(pairs, bodies.asleep);
        withNear.diff(g.ranges, bodies.asleep, nearQuery(near, g));
        withNear.writeEvents(g.ranges, g.points, nearEvents);
        expectSameEvents(nearEvents, nearReference.update(pairs, bodies.asleep, &near), step);
        if (::testing::Test::HasFatalFailure()) return;
    }
}

// A steady step writes over the last step's events in place: neither the event array nor any
// event's points move (no allocation), and a step with fewer events keeps the storage for later.
TEST(ContactTracker, FlatUpdateReusesEventStorage) {
    std::vector<TouchingPair> pairs;
    for (std::uint32_t i = 0; i < 100; ++i) {
        TouchingPair p = touch(body(i), body(i + 1));
        p.points.assign(4, ContactPoint{Vec3(double(i), 0, 0), 0.001, 1.0});
        pairs.push_back(p);
    }
    ContactTracker t;
    std::vector<ContactEvent> events;
    const auto run = [&](const std::vector<TouchingPair>& step) {
        FlatStep f = flatten(step, [](BodyId) { return false; });
        t.update(f.ranges, f.points, events);
    };
    run(pairs);
    run(pairs);
    ASSERT_EQ(events.size(), 100u);
    const ContactEvent* array = events.data();
    std::vector<const ContactPoint*> storage;
    for (const ContactEvent& e : events) storage.push_back(e.points.data());
    for (int step = 0; step < 5; ++step) {
        run(pairs);
        ASSERT_EQ(events.data(), array);
        for (std::size_t k = 0; k < events.size(); ++k) EXPECT_EQ(events[k].points.data(), storage[k]) << k;
    }
    // Half the pairs part (50 exits, then 50 stays), then touch again (50 enters): the storage
    // of the events dropped in between is handed back.
    const std::vector<TouchingPair> half(pairs.begin(), pairs.begin() + 50);
    run(half);
    run(half);
    EXPECT_EQ(events.size(), 50u);
    run(pairs);
    ASSERT_EQ(events.size(), 100u);
    ASSERT_EQ(events.data(), array);
    std::set<const ContactPoint*> before(storage.begin(), storage.end()), after;
    for (const ContactEvent& e : events) after.insert(e.points.data());
    EXPECT_EQ(after, before);
}
