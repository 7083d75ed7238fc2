#include "contacts.hpp"

#include <algorithm>

#include "collision/collide.hpp"
#include "collision/queries.hpp"
#include "native_body.hpp"

namespace anyphys::native {
namespace {

bool mayTouch(const NativeBody& a, const NativeBody& b) {
    if (!layersCollide(a.layer, a.mask, b.layer, b.mask)) return false;
    if (a.trigger || b.trigger) return a.moves() || b.moves();  // sensors see anything that moves
    return a.isDynamic() || b.isDynamic();                       // something must respond
}

// Carries accumulated impulses over to the new manifolds: by (manifold key, point id) first;
// a point whose features changed (a resting box rocking by a hair can swap the reference face)
// takes the impulse of the old point nearest to it, if within `matchDistance`. Losing warm
// starts on such flips makes stacks rock and creep.
void warmStartFrom(const std::vector<ContactManifold>& old, ContactManifold& fresh, double matchDistance) {
    for (const ContactManifold& m : old) {
        if (m.key != fresh.key) continue;
        bool taken[4] = {false, false, false, false};
        bool matched[4] = {false, false, false, false};
        const auto copy = [&](ContactPointState& to, int from) {
            to.normalImpulse = m.points[from].normalImpulse;
            to.tangentImpulse[0] = m.points[from].tangentImpulse[0];
            to.tangentImpulse[1] = m.points[from].tangentImpulse[1];
            taken[from] = true;
        };
        for (int i = 0; i < fresh.pointCount; ++i)
            for (int j = 0; j < m.pointCount && !matched[i]; ++j)
                if (!taken[j] && m.points[j].geometry.id == fresh.points[i].geometry.id) {
                    copy(fresh.points[i], j);
                    matched[i] = true;
                }
        for (int i = 0; i < fresh.pointCount; ++i) {
            if (matched[i]) continue;
            int best = -1;
            double bestDistance = matchDistance;
            for (int j = 0; j < m.pointCount; ++j) {
                const double d = (m.points[j].geometry.point - fresh.points[i].geometry.point).norm();
                if (!taken[j] && d < bestDistance) {
                    best = j;
                    bestDistance = d;
                }
            }
            if (best >= 0) copy(fresh.points[i], best);
        }
        return;
    }
}

}  // namespace

void ContactManager::addPair(std::uint64_t keyA, std::uint64_t keyB, const std::vector<NativeBody>& bodies,
                             const MaterialTable& materials) {
    if (keyB < keyA) std::swap(keyA, keyB);
    const std::uint32_t ia = proxyBody(keyA), ib = proxyBody(keyB);
    if (ia == ib) return;
    const NativeBody &a = bodies[ia], &b = bodies[ib];
    if (!mayTouch(a, b)) return;
    auto [it, inserted] = contacts_.try_emplace({keyA, keyB});
    if (!inserted) return;
    Contact& c = it->second;
    c.bodyA = ia;
    c.bodyB = ib;
    c.shapeA = proxyShape(keyA);
    c.shapeB = proxyShape(keyB);
    c.trigger = a.trigger || b.trigger;
    const ContactMaterial& m = materials.get(a.material, b.material);
    c.friction = m.friction;
    c.restitution = m.restitution;
}

void ContactManager::update(std::vector<NativeBody>& bodies, const BroadPhase& broadPhase, double speculativeDistance,
                            double linearSlop, double dt, std::vector<std::uint32_t>& toWake) {
    for (auto it = contacts_.begin(); it != contacts_.end();) {
        Contact& c = it->second;
        NativeBody &a = bodies[c.bodyA], &b = bodies[c.bodyB];
        const bool activeA = a.isActive(), activeB = b.isActive();
        if (!activeA && !activeB) {  // at rest (asleep or static): keep what we had
            ++it;
            continue;
        }
        const int proxyA = a.proxies[c.shapeA], proxyB = b.proxies[c.shapeB];
        if (!broadPhase.testOverlap(proxyA, proxyB)) {
            it = contacts_.erase(it);
            continue;
        }
        const Shape &sa = a.shapes[c.shapeA], &sb = b.shapes[c.shapeB];
        const Transform xfA = shapeWorldPose(sa, a.pose()), xfB = shapeWorldPose(sb, b.pose());
        if (c.trigger) {
            c.touching = overlap(sa, xfA, sb, xfB);
            c.manifolds.clear();
        } else {
            scratch_.clear();
            const double closing = (b.state.linearVelocity - a.state.linearVelocity).norm() * dt;
            collide(sa, xfA, sb, xfB, speculativeDistance + closing, scratch_);
            std::vector<ContactManifold> fresh;
            fresh.reserve(scratch_.size());
            bool touching = false;
            for (const Manifold& m : scratch_) {
                ContactManifold cm;
                cm.normal = m.normal;
                cm.key = m.key;
                cm.pointCount = m.pointCount;
                for (int i = 0; i < m.pointCount; ++i) {
                    cm.points[i].geometry = m.points[i];
                    touching = touching || m.points[i].separation < linearSlop;
                }
                warmStartFrom(c.manifolds, cm, speculativeDistance);
                fresh.push_back(cm);
            }
            c.manifolds = std::move(fresh);
            c.touching = touching;
        }
        // A moving body about to hit a sleeping one wakes it (and so its island) as soon as
        // their manifold has points, speculative ones included: otherwise the solver would
        // treat the sleeper as immovable for the step of the impact.
        if (!c.trigger && !c.manifolds.empty()) {
            if (!a.awake && a.moves()) toWake.push_back(c.bodyA);
            if (!b.awake && b.moves()) toWake.push_back(c.bodyB);
        }
        ++it;
    }
}

void ContactManager::removeBody(std::uint32_t body) {
    for (auto it = contacts_.begin(); it != contacts_.end();)
        it = (it->second.bodyA == body || it->second.bodyB == body) ? contacts_.erase(it) : std::next(it);
}

}  // namespace anyphys::native
