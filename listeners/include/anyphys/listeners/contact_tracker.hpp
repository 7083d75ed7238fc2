#pragma once
// Turns each step's set of touching pairs into enter / stay / exit events. One tracker serves
// every backend, so the semantics are identical everywhere:
//  - pair order fixed: bodyA < bodyB (pairs given in the other order are swapped, normal flipped);
//  - a pair touching now and not before: Enter; touching before and now: Stay (collisions only;
//    triggers get no Stay); touching before, not now: Exit;
//  - a pair whose bodies are (either) asleep keeps its contact: no Exit, no Stay;
//  - removing a body ends its pairs with an Exit flagged `removal`;
//  - a pair reported twice in one step counts once (first report wins).
#include <functional>
#include <utility>
#include <vector>

#include "anyphys/listeners/events.hpp"

namespace anyphys {

class ContactTracker {
public:
    using AsleepQuery = std::function<bool(BodyId)>;

    /// Diffs `touching` against the previous step. Events come out sorted by (bodyA, bodyB),
    /// exits first, then enters, then stays.
    std::vector<ContactEvent> update(std::vector<TouchingPair> touching, const AsleepQuery& asleep = {});

    /// Ends every pair involving `body` (Exit with removal = true) and forgets them.
    std::vector<ContactEvent> removeBody(BodyId body);

    /// Number of pairs currently touching.
    std::size_t activePairs() const { return active_.size(); }
    void clear() { active_.clear(); }

private:
    using PairKey = std::pair<BodyId, BodyId>;
    struct Active {
        PairKey key;
        bool trigger = false;
    };
    // Sorted by key: a step is one sort of the new pairs and one merge walk, with no per-pair
    // allocation (piles report thousands of pairs every step).
    std::vector<Active> active_;
};

}  // namespace anyphys
