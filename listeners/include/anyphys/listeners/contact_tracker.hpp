#pragma once
// Turns each step's set of touching pairs into enter / stay / exit events. One tracker serves
// every backend, so the semantics are identical everywhere:
//  - pair order fixed: bodyA < bodyB (pairs given in the other order are swapped, normal flipped);
//  - a pair touching now and not before: Enter; touching before and now: Stay (collisions only;
//    triggers get no Stay); touching before, not now: Exit;
//  - a pair whose bodies are (either) asleep keeps its contact: no Exit, no Stay;
//  - a pair no longer listed that the near query finds still touching stays, with the query's
//    contact (World keeps a pair until its shapes are twice linearSlop apart);
//  - removing a body ends its pairs with an Exit flagged `removal`;
//  - a pair reported twice in one step counts once (first report wins);
//  - a body pair's collision and its trigger overlap are two pairs, each with its own enter and
//    exit (a compound whose sensor child overlaps a body its solid child touches has both).
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "anyphys/listeners/events.hpp"

namespace anyphys {

class ContactTracker {
public:
    using AsleepQuery = std::function<bool(BodyId)>;
    /// Asked about a collision pair that touched before, is not listed now and does not sleep:
    /// true when it still touches, after appending its contact to `touching` (bodyA, bodyB as
    /// given, normal from A to B). The pair then stays, with that entry.
    using NearQuery = std::function<bool(BodyId a, BodyId b, std::vector<TouchingRange>& touching)>;

    /// Diffs `touching` against the previous step. Events come out sorted by (bodyA, bodyB),
    /// exits first, then enters, then stays.
    std::vector<ContactEvent> update(std::vector<TouchingPair> touching, const AsleepQuery& asleep = {});

    /// The same diff without allocating once the buffers have grown: diff() then writeEvents().
    /// `touching` lists the step's pairs, their points ranges of `points`, each flagged `asleep`
    /// where a body sleeps. `events` receives the events, overwriting the events it held and
    /// reusing their storage (pass the last step's events back in). `asleep` is asked only about
    /// pairs that touched before and are not listed now.
    void update(std::vector<TouchingRange>& touching, std::span<const ContactPoint> points,
                std::vector<ContactEvent>& events, const AsleepQuery& asleep = {}, const NearQuery& near = {});

    /// The step's diff alone: decides every pair's event and moves the tracker to this step's
    /// pairs (normalising `touching`'s order in place). What World runs every step; it writes the
    /// events only when someone reads them (a listener, World::lastEvents), since copying every
    /// staying pair's points is most of the tracker's cost.
    /// `touching` may grow: the near query appends the pairs it keeps.
    void diff(std::vector<TouchingRange>& touching, const AsleepQuery& asleep = {}, const NearQuery& near = {});
    /// Writes the last diff's events into `events` as update() does. `touching` and `points` must
    /// be what that diff was given (unchanged since); another diff in between replaces the events.
    void writeEvents(const std::vector<TouchingRange>& touching, std::span<const ContactPoint> points,
                     std::vector<ContactEvent>& events);

    /// Empties `events`, keeping their point storage for the next update (a step without events).
    void recycle(std::vector<ContactEvent>& events);

    /// Ends every pair involving `body` (Exit with removal = true) and forgets them.
    std::vector<ContactEvent> removeBody(BodyId body);

    /// Number of pairs currently touching.
    std::size_t activePairs() const { return active_.size(); }
    void clear() {
        active_.clear();
        activeIsLastListing_ = false;
    }

private:
    // A body id as one integer whose order is BodyId's (index, then generation).
    using Key = std::uint64_t;
    struct Active {
        Key a, b;  // a < b
        bool trigger = false;  // part of the pair's identity: a collision and a trigger are two pairs
    };
    struct Listed {  // a listed pair, in (a, b, trigger, listing order) order
        Key a, b;
        bool trigger;
        std::uint32_t index;  // into `touching`
    };
    enum class Outcome : std::uint8_t { Enter, Stay };
    /// What becomes of an active pair the listing lacks.
    enum class Unlisted : std::uint8_t { Exits, Sleeps, StillTouches };
    struct Decision {
        Outcome outcome;
        std::uint32_t ref;  // into `touching`
    };

    /// listed_ sorted into pair order and deduplicated, kept as lastSorted_ (and listed_ as
    /// lastListing_) for the next step.
    const std::vector<Listed>& sortAnew();
    /// An active pair the listing lacks: kept silently while a body sleeps; kept as a Stay whose
    /// contact is touching.back() while the near query finds it touching (collisions only);
    /// otherwise it exits.
    static Unlisted unlisted(const Active& old, std::vector<TouchingRange>& touching, const AsleepQuery& asleep,
                             const NearQuery& near);
    /// Merges the sorted listing with active_ into decisions_, exits_ and next_.
    void walk(std::vector<TouchingRange>& touching, const std::vector<Listed>& sorted, const AsleepQuery& asleep,
              const NearQuery& near);
    /// The diff of a listing that differs from the last one in a few places (an engine's contact
    /// list keeps its order from step to step; a pile gains and loses a few pairs): finds the
    /// changes by walking both listings, then merges the last sorted listing with the sorted new
    /// pairs into the events and the next pairs, without sorting the whole listing. False when the
    /// listings differ too much or the new one repeats a pair: the caller then clears what it
    /// decided and sorts (sortAnew rewrites sortedSlot_, which a failed merge leaves half written).
    bool diffFewChanges(std::vector<TouchingRange>& touching, const AsleepQuery& asleep, const NearQuery& near);
    /// diffFewChanges, unless it failed lately (then false without trying: stepsToNextTry_).
    bool tryFewChanges(std::vector<TouchingRange>& touching, const AsleepQuery& asleep, const NearQuery& near);
    void sortListed();
    /// The pairs the near query kept this step join the last listing (after its own pairs, with
    /// the contacts the query appended) and its sorted form, as if the engine had listed them:
    /// the next step asks about them again where the listing lacks them, and a steady pile
    /// with such pairs keeps the few-changes diff.
    void listHeld();
    /// After lastListing_ and lastSorted_ changed: whether the listing named each pair once, and
    /// if so where each of its pairs sits in lastSorted_ (sortedSlot_).
    void noteSorted(bool unique);
    std::vector<ContactPoint> takePointStorage();
    /// Gives every buffer that trades places with another (by swap) the larger capacity of the
    /// two, so a later step that lists fewer pairs than some earlier one never allocates; exits_
    /// too, which may have to hold every active pair.
    void matchSwappedCapacities();

    // Sorted by (a, b): a step is one sort of the listed pairs and one merge walk, or, when the
    // listing differs from the last in a few places, one walk of both listings and one merge
    // (diffFewChanges). The other vectors are scratch kept between steps, so a steady step
    // allocates nothing.
    std::vector<Active> active_;
    std::vector<Active> next_;
    std::vector<Listed> listed_;
    std::vector<Listed> sorting_;  // radix sort's second buffer; diffFewChanges' sorted listing
    std::vector<Listed> lastListing_, lastSorted_;  // the last listing, and it sorted and deduplicated
    bool lastListingUnique_ = false;    // the last listing named no pair twice
    std::vector<std::uint32_t> sortedSlot_;  // a unique last listing's touching index -> lastSorted_ position
    bool activeIsLastListing_ = false;  // active_ holds exactly lastSorted_'s pairs
    // diffFewChanges' scratch: per lastSorted_ entry, where the new listing has it (or that it
    // does not); the new listing's other pairs.
    std::vector<std::uint32_t> keptIndex_;
    std::vector<Listed> added_;
    std::vector<Listed> held_;  // the pairs the near query kept this step, in pair order (listHeld)
    std::uint32_t stepsToNextTry_ = 0;    // steps tryFewChanges still skips
    std::uint32_t stepsAfterFailure_ = 1; // steps it skips after its next failure
    std::vector<Decision> decisions_;  // the last diff's enters and stays, in pair order
    std::vector<Active> exits_;        // the last diff's exits, in pair order
    std::vector<std::vector<ContactPoint>> spare_;  // point storage of past events, for reuse
    std::size_t storagesMade_ = 0;  // point storages ever made: spare_ never needs to hold more
};

}  // namespace anyphys
