#include "anyphys/listeners/contact_tracker.hpp"

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
    // Normalise order (A < B, normal from A to B) and keep the first report of each pair.
    std::map<std::pair<BodyId, BodyId>, TouchingPair> now;
    for (auto& p : touching) {
        if (p.bodyA == p.bodyB) continue;  // a body never touches itself
        if (p.bodyB < p.bodyA) {
            std::swap(p.bodyA, p.bodyB);
            p.normal = -p.normal;
        }
        now.try_emplace({p.bodyA, p.bodyB}, std::move(p));
    }
    const auto sleeping = [&](const std::pair<BodyId, BodyId>& key) {
        return asleep && (asleep(key.first) || asleep(key.second));
    };

    std::vector<ContactEvent> exits, enters, stays;
    for (auto it = active_.begin(); it != active_.end();) {
        if (now.count(it->first) || sleeping(it->first)) {
            ++it;  // still touching, or asleep: a sleeping contact persists silently
            continue;
        }
        exits.push_back(exitEvent(it->first.first, it->first.second, it->second.trigger, false));
        it = active_.erase(it);
    }
    for (auto& [key, pair] : now) {
        auto [it, isNew] = active_.try_emplace(key, Active{pair.trigger});
        if (isNew) {
            enters.push_back(touchEvent(std::move(pair), ContactPhase::Enter));
        } else {
            it->second.trigger = pair.trigger;
            // Triggers report only enter and exit; sleeping pairs report nothing while asleep.
            if (!pair.trigger && !sleeping(key)) stays.push_back(touchEvent(std::move(pair), ContactPhase::Stay));
        }
    }

    // Each list is already in (bodyA, bodyB) order because both maps iterate sorted.
    std::vector<ContactEvent> events = std::move(exits);
    events.reserve(events.size() + enters.size() + stays.size());
    for (auto& e : enters) events.push_back(std::move(e));
    for (auto& e : stays) events.push_back(std::move(e));
    return events;
}

std::vector<ContactEvent> ContactTracker::removeBody(BodyId body) {
    std::vector<ContactEvent> events;
    for (auto it = active_.begin(); it != active_.end();) {
        const auto& [a, b] = it->first;
        if (a == body || b == body) {
            events.push_back(exitEvent(a, b, it->second.trigger, true));
            it = active_.erase(it);
        } else {
            ++it;
        }
    }
    return events;
}

}  // namespace anyphys
