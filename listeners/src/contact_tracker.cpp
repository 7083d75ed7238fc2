#include "anyphys/listeners/contact_tracker.hpp"

#include <algorithm>
#include <utility>

namespace anyphys {

namespace {

ContactEvent exitEvent(BodyId a, BodyId b, bool trigger, bool removal) {
    ContactEvent e;
    e.bodyA = a;
    e.bodyB = b;
    e.phase = ContactPhase::Exit;
    e.trigger = trigger;
    e.removal = removal;
    return e;
}

ContactEvent touchEvent(TouchingPair&& p, ContactPhase phase) {
    ContactEvent e;
    e.bodyA = p.bodyA;
    e.bodyB = p.bodyB;
    e.phase = phase;
    e.trigger = p.trigger;
    e.hasImpulses = p.hasImpulses;
    e.normal = p.normal;
    if (!p.trigger) e.points = std::move(p.points);  // triggers carry no contact points
    return e;
}

}  // namespace

std::vector<ContactEvent> ContactTracker::update(std::vector<TouchingPair> touching, const AsleepQuery& asleep) {
    // Normalise order (A < B, normal from A to B), sort, and keep the first report of each pair.
    std::erase_if(touching, [](const TouchingPair& p) { return p.bodyA == p.bodyB; });  // never itself
    for (TouchingPair& p : touching)
        if (p.bodyB < p.bodyA) {
            std::swap(p.bodyA, p.bodyB);
            p.normal = -p.normal;
        }
    const auto keyOf = [](const TouchingPair& p) { return PairKey{p.bodyA, p.bodyB}; };
    std::stable_sort(touching.begin(), touching.end(),
                     [&](const TouchingPair& x, const TouchingPair& y) { return keyOf(x) < keyOf(y); });
    touching.erase(std::unique(touching.begin(), touching.end(),
                               [&](const TouchingPair& x, const TouchingPair& y) { return keyOf(x) == keyOf(y); }),
                   touching.end());
    const auto sleeping = [&](const PairKey& key) { return asleep && (asleep(key.first) || asleep(key.second)); };

    // Merge walk of the two sorted lists; each output list comes out in (bodyA, bodyB) order.
    std::vector<ContactEvent> exits, enters, stays;
    std::vector<Active> next;
    next.reserve(touching.size() + active_.size());
    std::size_t i = 0, j = 0;
    while (i < active_.size() || j < touching.size()) {
        const bool takeOld = j == touching.size() || (i < active_.size() && active_[i].key < keyOf(touching[j]));
        const bool takeNew = i == active_.size() || (j < touching.size() && keyOf(touching[j]) < active_[i].key);
        if (takeOld) {  // touching before, not now: exit, unless asleep (the contact persists silently)
            const Active& old = active_[i++];
            if (sleeping(old.key)) next.push_back(old);
            else exits.push_back(exitEvent(old.key.first, old.key.second, old.trigger, false));
        } else if (takeNew) {
            TouchingPair& p = touching[j++];
            next.push_back({keyOf(p), p.trigger});
            enters.push_back(touchEvent(std::move(p), ContactPhase::Enter));
        } else {  // both: stay (triggers report only enter and exit; sleeping pairs nothing)
            TouchingPair& p = touching[j++];
            ++i;
            next.push_back({keyOf(p), p.trigger});
            if (!p.trigger && !sleeping(next.back().key)) stays.push_back(touchEvent(std::move(p), ContactPhase::Stay));
        }
    }
    active_ = std::move(next);

    std::vector<ContactEvent> events = std::move(exits);
    events.reserve(events.size() + enters.size() + stays.size());
    for (auto& e : enters) events.push_back(std::move(e));
    for (auto& e : stays) events.push_back(std::move(e));
    return events;
}

std::vector<ContactEvent> ContactTracker::removeBody(BodyId body) {
    std::vector<ContactEvent> events;
    std::erase_if(active_, [&](const Active& a) {
        const bool involved = a.key.first == body || a.key.second == body;
        if (involved) events.push_back(exitEvent(a.key.first, a.key.second, a.trigger, true));
        return involved;
    });
    return events;
}

}  // namespace anyphys
