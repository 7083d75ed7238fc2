#include "anyphys/listeners/contact_tracker.hpp"

#include <algorithm>
#include <utility>

namespace anyphys {

namespace {

// Point storage handed to a new event holds a box face's manifold, so that in a steady step
// the reused vectors rarely need to grow.
constexpr std::size_t kPointsPerEvent = 4;

std::uint64_t keyOf(BodyId id) { return (std::uint64_t(id.index) << 32) | id.generation; }
BodyId idOf(std::uint64_t key) { return BodyId{std::uint32_t(key >> 32), std::uint32_t(key)}; }

// Pairs are (a, b, trigger) and order by a, then b, then the flag: a collision before the same
// bodies' trigger overlap. For any two records carrying those three fields (Active, Listed).
template <class X, class Y>
bool samePair(const X& x, const Y& y) {
    return x.a == y.a && x.b == y.b && x.trigger == y.trigger;
}
template <class X, class Y>
bool pairBefore(const X& x, const Y& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.trigger < y.trigger;
}

ContactEvent exitEvent(BodyId a, BodyId b, bool trigger, bool removal) {
    ContactEvent e;
    e.bodyA = a;
    e.bodyB = b;
    e.phase = ContactPhase::Exit;
    e.trigger = trigger;
    e.removal = removal;
    return e;
}

}  // namespace

std::vector<ContactEvent> ContactTracker::update(std::vector<TouchingPair> touching, const AsleepQuery& asleep) {
    // The same diff over one shared point array; reported pairs are asked about sleep here.
    std::vector<TouchingRange> ranges;
    std::vector<ContactPoint> points;
    ranges.reserve(touching.size());
    for (const TouchingPair& p : touching) {
        const bool sleeping = asleep && (asleep(p.bodyA) || asleep(p.bodyB));
        ranges.push_back({p.bodyA, p.bodyB, p.trigger, p.hasImpulses, sleeping, p.normal,
                          static_cast<std::uint32_t>(points.size()), static_cast<std::uint32_t>(p.points.size())});
        points.insert(points.end(), p.points.begin(), p.points.end());
    }
    std::vector<ContactEvent> events;
    update(ranges, points, events, asleep);
    return events;
}

void ContactTracker::update(std::vector<TouchingRange>& touching, std::span<const ContactPoint> points,
                            std::vector<ContactEvent>& events, const AsleepQuery& asleep, const NearQuery& near) {
    diff(touching, asleep, near);
    writeEvents(touching, points, events);
}

void ContactTracker::diff(std::vector<TouchingRange>& touching, const AsleepQuery& asleep, const NearQuery& near) {
    // Normalise order (A < B, normal from A to B), sort by pair then listing order, and keep the
    // first listing of each pair.
    listed_.resize(touching.size());  // written through a pointer, then trimmed (see diffFewChanges)
    Listed* const listing = listed_.data();
    std::size_t listedCount = 0;
    const auto pairCount = static_cast<std::uint32_t>(touching.size());  // read once (see diffFewChanges)
    for (std::uint32_t i = 0; i < pairCount; ++i) {
        TouchingRange& p = touching[i];
        if (p.bodyA == p.bodyB) continue;  // never itself
        if (p.bodyB < p.bodyA) {
            std::swap(p.bodyA, p.bodyB);
            p.normal = -p.normal;
        }
        listing[listedCount++] = {keyOf(p.bodyA), keyOf(p.bodyB), p.trigger, i};
    }
    listed_.resize(listedCount);
    const auto equal = [](const Listed& x, const Listed& y) { return samePair(x, y) && x.index == y.index; };
    const bool sameListing = std::equal(listed_.begin(), listed_.end(), lastListing_.begin(), lastListing_.end(), equal);

    decisions_.clear();
    exits_.clear();
    held_.clear();
    if (sameListing && activeIsLastListing_) {
        // The pairs of the last step and no others: every pair stays (a resting pile, step
        // after step), and the touching set is the same.
        for (std::size_t k = 0; k < lastSorted_.size(); ++k) {
            const TouchingRange& p = touching[lastSorted_[k].index];
            active_[k].trigger = p.trigger;
            if (!p.trigger && !p.asleep) decisions_.push_back({Outcome::Stay, lastSorted_[k].index});
        }
    } else if (sameListing || !activeIsLastListing_ || !lastListingUnique_ || !tryFewChanges(touching, asleep, near)) {
        decisions_.clear();  // what diffFewChanges decided before it gave up
        exits_.clear();
        held_.clear();
        touching.resize(pairCount);  // and the contacts its near queries appended
        walk(touching, sameListing ? lastSorted_ : sortAnew(), asleep, near);
        active_.swap(next_);
    }
    listHeld();
    matchSwappedCapacities();
}

bool ContactTracker::tryFewChanges(std::vector<TouchingRange>& touching, const AsleepQuery& asleep, const NearQuery& near) {
    // A backend whose listing order moves (ODE's hash space) makes every attempt fail: after each
    // failure the next attempts wait, twice as many steps each time, up to kMostStepsBetweenTries.
    constexpr std::uint32_t kMostStepsBetweenTries = 64;
    if (stepsToNextTry_ > 0) {
        --stepsToNextTry_;
        return false;
    }
    if (diffFewChanges(touching, asleep, near)) {
        stepsAfterFailure_ = 1;
        return true;
    }
    stepsToNextTry_ = stepsAfterFailure_;
    stepsAfterFailure_ = std::min(2 * stepsAfterFailure_, kMostStepsBetweenTries);
    return false;
}

bool ContactTracker::diffFewChanges(std::vector<TouchingRange>& touching, const AsleepQuery& asleep, const NearQuery& near) {
    constexpr std::uint32_t kGone = ~std::uint32_t(0);  // keptIndex_ of a pair this listing lacks
    // A pair gone or new shifts the listing from that place on, so the walk looks a few places
    // ahead on both sides to find where the listings agree again; a pair that moved far counts
    // as gone and new, and the merge below finds it in both.
    constexpr std::size_t kLookAhead = 8;
    // Past a quarter of the listing changed, sorting it whole costs less than the search.
    const std::size_t budget = 16 + listed_.size() / 4;
    const std::vector<Listed>& before = lastListing_;  // no pair twice: each is in lastSorted_
    const std::vector<Listed>& now = listed_;
    keptIndex_.assign(lastSorted_.size(), kGone);
    added_.clear();
    // Sizes read once: the loops' stores through pointers keep the compiler from hoisting them.
    const std::size_t beforeSize = before.size(), nowSize = now.size();
    std::size_t i = 0, j = 0, changes = 0, keptCount = 0;
    while (i < beforeSize && j < nowSize) {
        if (samePair(before[i], now[j])) {
            const std::uint32_t slot = sortedSlot_[before[i++].index];
            keptIndex_[slot] = now[j++].index;
            ++keptCount;
            continue;
        }
        std::size_t gone = 1;  // old pairs that this listing no longer has, before the next agreement
        while (gone <= kLookAhead && i + gone < beforeSize && !samePair(before[i + gone], now[j])) ++gone;
        std::size_t fresh = 1;  // or new pairs, before it
        if (gone <= kLookAhead && i + gone < beforeSize) {
            i += gone;
            changes += gone;
        } else {
            while (fresh <= kLookAhead && j + fresh < nowSize && !samePair(before[i], now[j + fresh])) ++fresh;
            if (fresh <= kLookAhead && j + fresh < nowSize) {
                added_.insert(added_.end(), now.begin() + std::ptrdiff_t(j), now.begin() + std::ptrdiff_t(j + fresh));
                j += fresh;
                changes += fresh;
            } else {  // one pair replaced by another
                added_.push_back(now[j++]);
                ++i;
                changes += 2;
            }
        }
        if (changes > budget) return false;
    }
    changes += (beforeSize - i) + (nowSize - j);
    if (changes > budget) return false;
    added_.insert(added_.end(), now.begin() + std::ptrdiff_t(j), now.end());
    std::sort(added_.begin(), added_.end(), [](const Listed& x, const Listed& y) { return pairBefore(x, y); });

    // Merge the last sorted listing (its pairs kept, gone, or gone but asleep) with the new pairs,
    // in pair order: the events, the next active pairs and this listing's sorted form (with
    // where each of its pairs sits in it, for the next step) at once.
    // Written through pointers into room for every pair (a push per pair costs as much as the
    // rest of the merge), then trimmed: this listing's pairs, and the next active pairs and
    // decisions, which may also keep old pairs gone but asleep or still touching.
    const std::size_t unlistedMost = lastSorted_.size() - keptCount;
    sorting_.resize(now.size());
    decisions_.resize(now.size() + unlistedMost);
    next_.resize(now.size() + unlistedMost);
    Listed* const sorted = sorting_.data();
    Active* const nextPairs = next_.data();
    Decision* const decided = decisions_.data();
    std::uint32_t sortedCount = 0, nextCount = 0, decidedCount = 0;
    sortedSlot_.resize(now.empty() ? 0 : now.back().index + 1);
    bool keptAsleep = false;
    bool afterNew = false;  // the last pair listed came from added_: the next may repeat it
    // Inlined: it runs for every pair, and a call costs more than its body.
    const auto list = [&](const Listed& pair, std::uint32_t index, bool isNew, bool entered) __attribute__((always_inline)) {
        // Kept pairs are distinct (the last listing named each once); a new pair may repeat one.
        if ((isNew || afterNew) && sortedCount > 0 && samePair(sorted[sortedCount - 1], pair)) return false;  // listed twice
        afterNew = isNew;
        sortedSlot_[index] = sortedCount;
        sorted[sortedCount++] = {pair.a, pair.b, pair.trigger, index};
        nextPairs[nextCount++] = {pair.a, pair.b, pair.trigger};
        const TouchingRange& p = touching[index];
        if (entered)
            decided[decidedCount++] = {Outcome::Enter, index};
        else if (!p.trigger && !p.asleep)
            decided[decidedCount++] = {Outcome::Stay, index};
        return true;
    };
    const Listed* const old = lastSorted_.data();
    const Listed* const newPairs = added_.data();
    const std::size_t oldSize = lastSorted_.size(), newCount = added_.size();
    std::size_t p = 0, q = 0;
    while (p < oldSize || q < newCount) {
        if (q == newCount || (p < oldSize && pairBefore(old[p], newPairs[q]))) {
            const Listed& o = old[p];
            if (keptIndex_[p] != kGone) {
                if (!list(o, keptIndex_[p], false, false)) return false;
            } else {
                const Active pair{o.a, o.b, o.trigger};
                const Unlisted fate = unlisted(pair, touching, asleep, near);
                if (fate == Unlisted::Exits) {
                    exits_.push_back(pair);
                } else if (fate == Unlisted::Sleeps) {  // the contact persists silently
                    nextPairs[nextCount++] = pair;
                    keptAsleep = true;
                } else {
                    const auto contact = static_cast<std::uint32_t>(touching.size() - 1);
                    nextPairs[nextCount++] = pair;
                    decided[decidedCount++] = {Outcome::Stay, contact};
                    held_.push_back({o.a, o.b, false, contact});
                }
            }
            ++p;
        } else if (p < oldSize && samePair(old[p], newPairs[q])) {  // moved in the listing: it stays
            if (keptIndex_[p] != kGone || !list(newPairs[q], newPairs[q].index, true, false)) return false;
            ++p;
            ++q;
        } else {
            if (!list(newPairs[q], newPairs[q].index, true, true)) return false;
            ++q;
        }
    }
    sorting_.resize(sortedCount);
    next_.resize(nextCount);
    decisions_.resize(decidedCount);
    active_.swap(next_);
    activeIsLastListing_ = !keptAsleep;  // the held pairs join the last listing (listHeld)
    lastListing_.swap(listed_);  // diff() rebuilds listed_ whole
    lastSorted_.swap(sorting_);
    lastListingUnique_ = true;  // sortedSlot_ written above
    return true;
}

void ContactTracker::writeEvents(const std::vector<TouchingRange>& touching, std::span<const ContactPoint> points,
                                 std::vector<ContactEvent>& events) {
    // Exits, then enters, then stays, each in pair order (the walk's), written over the last
    // step's events so their point storage is reused.
    std::size_t used = 0;
    const auto nextEvent = [&]() -> ContactEvent& {
        if (used < events.size()) return events[used++];
        ++used;
        return events.emplace_back();
    };
    for (const Active& old : exits_) {
        ContactEvent& e = nextEvent();
        e.bodyA = idOf(old.a);
        e.bodyB = idOf(old.b);
        e.phase = ContactPhase::Exit;
        e.trigger = old.trigger;
        e.removal = false;
        e.hasImpulses = false;
        e.normal = Vec3::Zero();
        e.points.clear();
    }
    for (const Outcome phase : {Outcome::Enter, Outcome::Stay})
        for (const Decision& d : decisions_) {
            if (d.outcome != phase) continue;
            const TouchingRange& p = touching[d.ref];
            ContactEvent& e = nextEvent();
            e.bodyA = p.bodyA;
            e.bodyB = p.bodyB;
            e.phase = phase == Outcome::Enter ? ContactPhase::Enter : ContactPhase::Stay;
            e.trigger = p.trigger;
            e.removal = false;
            e.hasImpulses = p.hasImpulses;
            e.normal = p.normal;
            e.points.clear();
            if (p.trigger) continue;  // triggers carry no contact points
            if (e.points.capacity() == 0) e.points = takePointStorage();
            const auto first = points.begin() + p.firstPoint;
            e.points.assign(first, first + p.pointCount);
        }
    // Fewer events than last step: keep the storage of the rest.
    for (std::size_t k = used; k < events.size(); ++k)
        if (events[k].points.capacity() > 0) spare_.push_back(std::move(events[k].points));
    events.resize(used);
}

void ContactTracker::matchSwappedCapacities() {
    const auto match = [](auto&... buffers) {
        const std::size_t most = std::max({buffers.capacity()...});
        (buffers.reserve(most), ...);  // a no-op on the one that has it, and once the others do
    };
    match(active_, next_, exits_);
    match(listed_, sorting_, lastSorted_);
    // diffFewChanges' scratch holds at most a listing (and lastListing_ is one).
    match(listed_, lastListing_, added_);
    keptIndex_.reserve(listed_.capacity());
    decisions_.reserve(listed_.capacity());
}

ContactTracker::Unlisted ContactTracker::unlisted(const Active& old, std::vector<TouchingRange>& touching,
                                                  const AsleepQuery& asleep, const NearQuery& near) {
    const BodyId a = idOf(old.a), b = idOf(old.b);
    if (asleep && (asleep(a) || asleep(b))) return Unlisted::Sleeps;  // the contact persists silently
    if (old.trigger || !near) return Unlisted::Exits;
    const std::size_t listed = touching.size();
    if (!near(a, b, touching) || touching.size() == listed) {
        touching.resize(listed);
        return Unlisted::Exits;
    }
    touching.resize(listed + 1);  // one contact per pair
    TouchingRange& contact = touching.back();
    if (contact.bodyB < contact.bodyA) {  // the order the tracker keeps, whatever the query wrote
        std::swap(contact.bodyA, contact.bodyB);
        contact.normal = -contact.normal;
    }
    contact.trigger = false;
    contact.asleep = false;
    return Unlisted::StillTouches;
}

void ContactTracker::walk(std::vector<TouchingRange>& touching, const std::vector<Listed>& sorted,
                          const AsleepQuery& asleep, const NearQuery& near) {
    // Merge walk of the two sorted lists: decide each pair's fate, and carry the touching ones over.
    next_.clear();
    const std::size_t activeCount = active_.size(), sortedCount = sorted.size();  // read once (see diffFewChanges)
    std::size_t i = 0, j = 0;
    while (i < activeCount || j < sortedCount) {
        const bool takeOld = j == sortedCount || (i < activeCount && pairBefore(active_[i], sorted[j]));
        if (takeOld) {  // touching before, not listed now: exit, unless asleep or still touching
            const Active& old = active_[i];
            const Unlisted fate = unlisted(old, touching, asleep, near);
            if (fate == Unlisted::Exits) {
                exits_.push_back(old);
            } else {
                next_.push_back(old);
                if (fate == Unlisted::StillTouches) {
                    const auto contact = static_cast<std::uint32_t>(touching.size() - 1);
                    decisions_.push_back({Outcome::Stay, contact});
                    held_.push_back({old.a, old.b, false, contact});
                }
            }
            ++i;
            continue;
        }
        const Listed& now = sorted[j++];
        const TouchingRange& p = touching[now.index];
        next_.push_back({now.a, now.b, p.trigger});
        const bool touchedBefore = i < activeCount && samePair(active_[i], now);
        if (!touchedBefore) {
            decisions_.push_back({Outcome::Enter, now.index});
        } else {  // stay (triggers report only enter and exit; sleeping pairs nothing)
            ++i;
            if (!p.trigger && !p.asleep) decisions_.push_back({Outcome::Stay, now.index});
        }
    }
    // No pair kept asleep besides (the held pairs join the last listing: listHeld).
    activeIsLastListing_ = next_.size() == sorted.size() + held_.size();
}

void ContactTracker::listHeld() {
    if (held_.empty()) return;
    // In pair order already (both diffs decide in pair order), and absent from the listing.
    lastListing_.insert(lastListing_.end(), held_.begin(), held_.end());
    sorting_.resize(lastSorted_.size() + held_.size());
    std::merge(lastSorted_.begin(), lastSorted_.end(), held_.begin(), held_.end(), sorting_.begin(),
               [](const Listed& x, const Listed& y) { return pairBefore(x, y); });
    lastSorted_.swap(sorting_);
    noteSorted(lastListingUnique_);
}

const std::vector<ContactTracker::Listed>& ContactTracker::sortAnew() {
    lastListing_.assign(listed_.begin(), listed_.end());
    sortListed();
    const std::size_t listedPairs = listed_.size();
    listed_.erase(std::unique(listed_.begin(), listed_.end(),
                              [](const Listed& x, const Listed& y) { return samePair(x, y); }),
                  listed_.end());
    lastSorted_.swap(listed_);
    noteSorted(lastSorted_.size() == listedPairs);
    return lastSorted_;
}

void ContactTracker::noteSorted(bool unique) {
    lastListingUnique_ = unique;
    if (!unique) return;
    sortedSlot_.resize(lastListing_.empty() ? 0 : lastListing_.back().index + 1);
    for (std::uint32_t k = 0; k < lastSorted_.size(); ++k) sortedSlot_[lastSorted_[k].index] = k;
}

void ContactTracker::sortListed() {
    const auto before = [](const Listed& x, const Listed& y) { return samePair(x, y) ? x.index < y.index : pairBefore(x, y); };
    if (std::is_sorted(listed_.begin(), listed_.end(), before)) return;
    if (listed_.size() < 64) {  // a few pairs: a comparison sort beats the radix passes
        std::sort(listed_.begin(), listed_.end(), before);
        return;
    }
    // Piles report thousands of pairs every step: a stable radix sort (byte by byte, least
    // significant first) over the 128 bits of (a, b), skipping the bytes in which every key
    // agrees (body indices and generations use few of their bits). Stable: equal pairs keep
    // their listing order.
    Key orA = 0, andA = ~Key(0), orB = 0, andB = ~Key(0);
    for (const Listed& l : listed_) {
        orA |= l.a;
        andA &= l.a;
        orB |= l.b;
        andB &= l.b;
    }
    sorting_.resize(listed_.size());
    // The trigger flag is the least significant key: collisions first, stably, before the bytes
    // (through the second buffer: std::stable_partition would allocate).
    if (std::any_of(listed_.begin(), listed_.end(), [](const Listed& l) { return l.trigger; })) {
        std::size_t next = 0;
        for (const bool trigger : {false, true})
            for (const Listed& l : listed_)
                if (l.trigger == trigger) sorting_[next++] = l;
        listed_.swap(sorting_);
    }
    for (int digit = 0; digit < 16; ++digit) {
        const bool high = digit >= 8;  // bytes of b first, then of a
        const int shift = 8 * (digit % 8);
        if ((((high ? orA ^ andA : orB ^ andB) >> shift) & 0xFF) == 0) continue;
        const auto byteOf = [&](const Listed& l) { return static_cast<std::size_t>(((high ? l.a : l.b) >> shift) & 0xFF); };
        std::uint32_t start[256] = {};
        for (const Listed& l : listed_) ++start[byteOf(l)];
        std::uint32_t sum = 0;
        for (std::uint32_t& s : start) {
            const std::uint32_t count = s;
            s = sum;
            sum += count;
        }
        for (const Listed& l : listed_) sorting_[start[byteOf(l)]++] = l;
        listed_.swap(sorting_);
    }
}

void ContactTracker::recycle(std::vector<ContactEvent>& events) {
    for (ContactEvent& e : events)
        if (e.points.capacity() > 0) spare_.push_back(std::move(e.points));
    events.clear();
}

std::vector<ContactPoint> ContactTracker::takePointStorage() {
    if (spare_.empty()) {
        std::vector<ContactPoint> fresh;
        fresh.reserve(kPointsPerEvent);
        // Every storage may come back to spare_ (a pile's event count goes up and down from step
        // to step): room for all of them now, so returning one never grows spare_ in a later,
        // steady step. Geometric, so a first step making thousands stays linear.
        if (spare_.capacity() < ++storagesMade_) spare_.reserve(2 * storagesMade_);
        return fresh;
    }
    std::vector<ContactPoint> reused = std::move(spare_.back());
    spare_.pop_back();
    reused.clear();
    return reused;
}

std::vector<ContactEvent> ContactTracker::removeBody(BodyId body) {
    std::vector<ContactEvent> events;
    const Key key = keyOf(body);
    std::erase_if(active_, [&](const Active& a) {
        const bool involved = a.a == key || a.b == key;
        if (involved) events.push_back(exitEvent(idOf(a.a), idOf(a.b), a.trigger, true));
        return involved;
    });
    if (!events.empty()) activeIsLastListing_ = false;
    return events;
}

}  // namespace anyphys
