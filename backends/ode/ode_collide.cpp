// Collision: the space's near callback turns touching geom pairs into ODE contact joints with
// the layer's resolved materials, and remembers them for the layer's contact events.
#include <algorithm>
#include <tuple>
#include <utility>

#include "ode_math.hpp"
#include "ode_tuning.hpp"
#include "ode_world.hpp"

namespace anyphys::ode {

void OdeWorld::nearCallback(void* self, dGeomID o1, dGeomID o2) { static_cast<OdeWorld*>(self)->collidePair(o1, o2); }

void OdeWorld::collidePair(dGeomID o1, dGeomID o2) {
    auto* a = static_cast<OdeBody*>(dGeomGetData(o1));
    auto* b = static_cast<OdeBody*>(dGeomGetData(o2));
    // Something must respond: a dynamic body, or a sensor and something moving.
    const bool trigger = a->isTrigger() || b->isTrigger();
    if (trigger ? !(a->moves() || b->moves()) : !(a->isDynamic() || b->isDynamic())) return;
    if (!a->isActive() && !b->isActive()) return;  // asleep (or asleep on something static)
    if (!layersCollide(a->layer(), a->mask(), b->layer(), b->mask())) return;
    if (!collidable(o1, o2)) return;
    // ODE's normals point into geom 1: make that a dynamic body, whose joint feedback is read.
    if (!a->isDynamic()) {
        std::swap(o1, o2);
        std::swap(a, b);
    }
    // Collide into a stack buffer and keep only the points found: most candidate pairs from the
    // broad phase have none, and clearing room for the maximum in the list would cost more.
    dContact found[kMaxContactsPerPair];
    const int n = dCollide(o1, o2, trigger ? 1 : kMaxContactsPerPair, &found[0].geom, sizeof(dContact));
    if (n <= 0) return;
    const std::size_t first = contacts_.size();
    contacts_.insert(contacts_.end(), found, found + n);
    pairs_.push_back({a, b, trigger, static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(n)});
}

void OdeWorld::collide() {
    pairs_.clear();
    contacts_.clear();
    feedbackValid_ = false;
    dSpaceCollide(space_, this, &OdeWorld::nearCallback);
}

void OdeWorld::createContactJoints() {
    const bool friction = effects_.has(Effect::Friction);
    const bool restitution = effects_.has(Effect::Restitution);
    const bool events = effects_.has(Effect::Events);
    // Feedback (the joints' forces) only when events report impulses; sized once, so the
    // pointers handed to ODE stay valid through the step.
    if (events) feedback_.resize(contacts_.size());
    feedbackValid_ = events;
    for (const PairRecord& p : pairs_) {
        if (p.trigger) continue;  // sensors never collide
        // Exactly the layer's resolved pair values; ODE's own mixing is never used.
        const ContactMaterial& m = materials_.get(p.a->material(), p.b->material());
        dSurfaceParameters surface{};
        if (friction && m.friction > 0) {
            // Approx1: mu scales the normal force (Coulomb), on two tangent directions.
            surface.mode |= dContactApprox1;
            surface.mu = m.friction;
        }
        if (restitution && m.restitution > 0) {
            surface.mode |= dContactBounce;
            surface.bounce = m.restitution;
            surface.bounce_vel = settings_.restitutionThreshold;  // slower impacts do not bounce
            surface.mode |= dContactSoftCFM;  // rigid, so softness does not absorb the rebound
            surface.soft_cfm = std::min(cfm_, kBounceCfm);
        }
        for (std::uint32_t i = p.first; i < p.first + p.count; ++i) {
            dContact& c = contacts_[i];
            c.surface = surface;
            const dJointID joint = dJointCreateContact(world_, contactGroup_, &c);
            dJointAttach(joint, p.a->id(), p.b->id());
            if (events) dJointSetFeedback(joint, &feedback_[i]);
        }
    }
}

void OdeWorld::collectContacts(std::vector<PeerContact>& out) {
    const std::size_t start = out.size();
    out.reserve(start + pairs_.size());
    // ODE reports each joint's constraint force averaged over the ODE step; over the anyphys step
    // the normal impulse is that force along the normal times dt (with substeps: the last
    // substep's force held for the whole step). The feedback array outlives the joints.
    const bool haveImpulses = feedbackValid_ && feedback_.size() >= contacts_.size();
    const auto impulse = [&](std::uint32_t i) {
        return haveImpulses ? std::max(0.0, dCalcVectorDot3(feedback_[i].f1, contacts_[i].geom.normal)) * lastDt_ : 0.0;
    };
    for (const PairRecord& p : pairs_) {
        if (!p.a->isActive() && !p.b->isActive()) continue;  // both asleep: the layer keeps the pair
        if (p.trigger) {
            out.push_back({p.a->userData(), p.b->userData(), true, Vec3::Zero(), {}});
            continue;
        }
        // ODE's normal points into body a; the layer's from A to B.
        PeerContact pc{p.a->userData(), p.b->userData(), false, -toVec3(contacts_[p.first].geom.normal), {}};
        pc.points.reserve(p.count);
        for (std::uint32_t i = p.first; i < p.first + p.count; ++i)
            pc.points.push_back({toVec3(contacts_[i].geom.pos), contacts_[i].geom.depth, impulse(i)});
        out.push_back(std::move(pc));
    }
    if (multiShapeBodies_ == 0) return;
    // A body of several geoms meets another in several geom pairs: one report per body pair.
    const auto key = [](const PeerContact& c) { return std::minmax(c.bodyA, c.bodyB); };
    std::stable_sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end(),
                     [&](const PeerContact& x, const PeerContact& y) { return key(x) < key(y); });
    std::size_t kept = start;
    for (std::size_t i = start; i < out.size(); ++i) {
        if (kept > start && key(out[kept - 1]) == key(out[i]) && out[kept - 1].trigger == out[i].trigger) {
            PeerContact& merged = out[kept - 1];
            merged.points.insert(merged.points.end(), out[i].points.begin(), out[i].points.end());
            continue;
        }
        if (kept != i) out[kept] = std::move(out[i]);
        ++kept;
    }
    out.resize(kept);
}

}  // namespace anyphys::ode
