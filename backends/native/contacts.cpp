#include "contacts.hpp"

#include <algorithm>
#include <cmath>

#include "collision/collide.hpp"
#include "collision/queries.hpp"
#include "native_body.hpp"

namespace anyphys::native {
namespace {

// A pair is at rest for recycling while its relative motion per step moves no point of its shapes
// by this fraction of linearSlop.
constexpr double kRecycleRestFraction = 0.1;
// Recycled manifolds keep their world normal: neither body may have turned by more than this
// (rad, about 1 degree) since the narrow phase, however small the shapes.
constexpr double kRecycleMaxTurn = 0.02;
// A manifold of another key continues an old one whose normal is this close (cosine of 1 mrad):
// the same flat stretch of a mesh, whose merged manifold took another triangle's key.
constexpr double kSameNormalCos = 1.0 - 5e-7;

// Per shape pair: a compound's children may differ in filter and sensor flag.
bool mayTouch(const NativeBody& a, const ShapeSurface& sa, const NativeBody& b, const ShapeSurface& sb) {
    if (!layersCollide(sa.layer, sa.mask, sb.layer, sb.mask)) return false;
    if (sa.trigger || sb.trigger) return a.moves() || b.moves();  // sensors see anything that moves
    return a.isDynamic() || b.isDynamic();                       // something must respond
}

// The old manifold that `fresh` continues: the one of the same key, else (a mesh manifold's key is
// its lowest triangle's, which changes as the shape slides onto other triangles) the one whose
// normal is closest to fresh's within kSameNormalCos. Null if none.
const ContactManifold* predecessor(const std::vector<ContactManifold>& old, const ContactManifold& fresh) {
    for (const ContactManifold& m : old)
        if (m.key == fresh.key) return &m;
    const ContactManifold* best = nullptr;
    double bestCos = kSameNormalCos;
    for (const ContactManifold& m : old)
        if (const double c = m.normal.dot(fresh.normal); c > bestCos) {
            best = &m;
            bestCos = c;
        }
    return best;
}

// Carries accumulated impulses over to the new manifolds: by (manifold key, point id) first;
// a point whose features changed (a resting box rocking by a hair can swap the reference face)
// takes the impulse of the old point nearest to it, if within `matchDistance`. Losing warm
// starts on such flips makes stacks rock and creep.
void warmStartFrom(const std::vector<ContactManifold>& old, ContactManifold& fresh, double matchDistance) {
    if (const ContactManifold* previous = predecessor(old, fresh)) {
        const ContactManifold& m = *previous;
        bool taken[4] = {false, false, false, false};
        bool matched[4] = {false, false, false, false};
        const auto copy = [&](ContactPointState& to, int from) {
            to.normalImpulse = m.points[from].normalImpulse;
            taken[from] = true;
        };
        fresh.frictionImpulse = m.frictionImpulse;
        fresh.twistImpulse = m.twistImpulse;
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
    }
}

// In a planar world a manifold acts in the XY plane:
//  - Its normal is put in the plane. A hull-hull normal can carry a rounding-level z (1e-17);
//    then the friction's second tangent, meant to be the locked Z, has a sliver of in-plane mass,
//    the 2x2 tangent mass inverts to huge entries, and the impulse along Z (which moves nothing)
//    fills the friction cone, leaving none along the plane: a planar stone arch slid apart.
//  - The points of a face come in pairs at z = +h and -h with the same x and y; they act as one
//    constraint (no body can tilt about X or Y), and solving both doubles the stiffness and the
//    cost. One point per (x, y) is kept, at z = 0, the deeper one's separation and the lower
//    feature id (so warm starting matches step to step).
void flattenPlanarManifold(Manifold& m, double tolerance) {
    m.normal.z() = 0.0;
    m.normal.normalize();
    int kept = 0;
    for (int i = 0; i < m.pointCount; ++i) {
        ManifoldPoint p = m.points[i];
        p.point.z() = 0.0;
        int same = -1;
        for (int k = 0; k < kept && same < 0; ++k)
            if ((m.points[k].point - p.point).squaredNorm() <= tolerance * tolerance) same = k;
        if (same < 0) {
            m.points[kept++] = p;
            continue;
        }
        ManifoldPoint& q = m.points[same];
        q.separation = std::min(q.separation, p.separation);
        q.id = std::min(q.id, p.id);
    }
    m.pointCount = kept;
}

// Two balls closing fast were held apart along the normal between them at the step start,
// though they meet later along another: a glancing hit (the line of centres 30 deg off the paths)
// sent a ball off 0.7 deg at 1 m/s each, 7.4 deg at 3 m/s and 19 deg at 10 m/s (now within
// 0.01 deg at all three, energy kept). A speculative contact of two spheres (its point's
// separation > 0) takes the normal of the moment within the step they meet, or, if they miss,
// of their closest approach, along which they do not close at all (so a near miss is not pushed
// apart). The centres move in straight lines over the step; turning does not move a sphere's
// surface. The solver anchors each sphere at its centre (contactAnchor), so a normal off the line
// of centres still gives no moment.
void aimAtImpact(Manifold& m, const Vec3& centerA, const Vec3& velocityA, double radiusA, const Vec3& centerB,
                 const Vec3& velocityB, double radiusB, double dt) {
    if (m.pointCount != 1 || !(m.points[0].separation > 0.0)) return;
    const Vec3 d = centerB - centerA, v = velocityB - velocityA;
    const double reach = radiusA + radiusB, vv = v.squaredNorm(), dv = d.dot(v);
    if (!(dv < 0.0) || !(vv > 0.0)) return;  // not closing: the step-start normal is the one
    // |d + v t| = reach at the earlier root, if they meet within the step; else the closest
    // approach within the step.
    const double discriminant = dv * dv - vv * (d.squaredNorm() - reach * reach);
    double t = std::min(-dv / vv, dt);
    if (discriminant >= 0.0) t = std::min(t, (-dv - std::sqrt(discriminant)) / vv);
    const Vec3 apart = d + t * v;
    const double length = apart.norm();
    if (!(length > 0.0)) return;
    m.normal = apart / length;
    const double separation = m.normal.dot(d) - reach;  // along the new normal, at the step start
    m.points[0].separation = separation;
    m.points[0].point = centerA + (radiusA + 0.5 * separation) * m.normal;
}

std::uint64_t bodyPairKey(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
}

}  // namespace

void ContactManager::excludePair(std::uint32_t a, std::uint32_t b) {
    if (excluded_[bodyPairKey(a, b)]++ > 0) return;
    for (std::uint32_t slot = 0; slot < slots_.size(); ++slot) {
        const Contact& c = slots_[slot];
        if (c.alive && bodyPairKey(c.bodyA, c.bodyB) == bodyPairKey(a, b)) destroy(slot);
    }
}

void ContactManager::includePair(std::uint32_t a, std::uint32_t b) {
    const auto it = excluded_.find(bodyPairKey(a, b));
    if (it != excluded_.end() && --it->second == 0) excluded_.erase(it);
}

bool ContactManager::excludes(std::uint32_t a, std::uint32_t b) const {
    return !excluded_.empty() && excluded_.contains(bodyPairKey(a, b));
}

void ContactManager::addPair(std::uint64_t keyA, std::uint64_t keyB, const NativeBodies& bodies,
                             const MaterialTable& materials) {
    if (keyB < keyA) std::swap(keyA, keyB);
    const std::uint32_t ia = proxyBody(keyA), ib = proxyBody(keyB);
    if (ia == ib) return;
    const NativeBody &a = bodies[ia], &b = bodies[ib];
    const ShapeSurface &sa = a.surfaces[proxyShape(keyA)], &sb = b.surfaces[proxyShape(keyB)];
    if (!mayTouch(a, sa, b, sb)) return;
    if (excludes(ia, ib)) return;
    const std::pair key{keyA, keyB};
    if (index_.contains(key)) return;  // already in contact
    std::uint32_t slot;
    if (!free_.empty()) {
        slot = free_.back();
        free_.pop_back();
    } else {
        slot = static_cast<std::uint32_t>(slots_.size());
        slots_.emplace_back();
    }
    if (spareNodes_.empty()) {
        index_.emplace(key, slot);
    } else {
        PairIndex::node_type node = std::move(spareNodes_.back());
        spareNodes_.pop_back();
        node.key() = key;
        node.mapped() = slot;
        index_.insert(std::move(node));
    }
    Contact& c = slots_[slot];
    c.alive = true;
    c.bodyA = ia;
    c.bodyB = ib;
    c.shapeA = proxyShape(keyA);
    c.shapeB = proxyShape(keyB);
    c.proxyA = a.proxies[static_cast<std::size_t>(c.shapeA)];
    c.proxyB = b.proxies[static_cast<std::size_t>(c.shapeB)];
    // Planes and meshes have no useful box.
    const auto boxable = [](const Shape& s) { return s.type != ShapeType::Plane && s.type != ShapeType::Mesh; };
    c.boxed = boxable(a.shapes[static_cast<std::size_t>(c.shapeA)]) && boxable(b.shapes[static_cast<std::size_t>(c.shapeB)]);
    const auto round = [](const Shape& s) { return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule; };
    c.flatPair = !round(a.shapes[static_cast<std::size_t>(c.shapeA)]) && !round(b.shapes[static_cast<std::size_t>(c.shapeB)]);
    c.trigger = sa.trigger || sb.trigger;
    c.touching = false;
    c.separated = false;
    c.manifolds.clear();
    c.collideCache = {};
    const ContactMaterial& m = materials.get(sa.material, sb.material);
    c.friction = m.friction;
    c.restitution = m.restitution;
}

void ContactManager::collideContact(Contact& c, NativeBodies& bodies, const BroadPhase& broadPhase,
                                    double speculativeDistance, double linearSlop, double dt, bool planar,
                                    Scratch& scratch) const {
    const NativeBody &a = bodies[c.bodyA], &b = bodies[c.bodyB];
    if (!a.isActive() && !b.isActive()) return;  // at rest (asleep or static): keep what we had
    if (!broadPhase.testOverlap(c.proxyA, c.proxyB)) {
        c.separated = true;
        return;
    }
    const Shape &sa = a.shapes[c.shapeA], &sb = b.shapes[c.shapeB];  // read only past the early-outs
    if (c.trigger) {
        c.touching = overlap(sa, shapeWorldPose(sa, a.pose()), sb, shapeWorldPose(sb, b.pose()));
        c.manifolds.clear();
        return;
    }
    const double closing = (b.state.linearVelocity - a.state.linearVelocity).norm() * dt;
    const double margin = speculativeDistance + closing;
    // Neighbours whose fat bounds overlap but whose tight bounds are farther apart than the
    // margin cannot have a point: skip the narrow phase. The bodies' tight bounds were computed
    // at these poses by the broad-phase update this step.
    if (c.boxed && !a.bounds[c.shapeA].fattened(margin).overlaps(b.bounds[c.shapeB])) {
        c.manifolds.clear();
        c.touching = false;
        return;
    }
    if (c.recyclable && recycle(c, a, b, linearSlop, dt)) return;
    const Transform xfA = shapeWorldPose(sa, a.pose()), xfB = shapeWorldPose(sb, b.pose());
    scratch.found.clear();
    collide(sa, xfA, sb, xfB, margin, scratch.found, &c.collideCache);
    if (sa.type == ShapeType::Sphere && sb.type == ShapeType::Sphere && scratch.found.size() == 1) {
        const auto velocityAt = [](const NativeBody& body, const Vec3& point) {
            return Vec3(body.state.linearVelocity + body.state.angularVelocity.cross(point - body.state.position));
        };
        aimAtImpact(scratch.found[0], xfA.position, velocityAt(a, xfA.position), sa.radius, xfB.position,
                    velocityAt(b, xfB.position), sb.radius, dt);
    }
    if (planar)
        for (Manifold& m : scratch.found) flattenPlanarManifold(m, 0.1 * linearSlop);
    // The new manifolds replace the old in place (no allocation once the capacity is there);
    // the old ones are kept aside for warm starting.
    scratch.previous.assign(c.manifolds.begin(), c.manifolds.end());
    c.manifolds.resize(scratch.found.size());
    bool touching = false;
    for (std::size_t k = 0; k < scratch.found.size(); ++k) {
        const Manifold& m = scratch.found[k];
        ContactManifold& cm = c.manifolds[k];
        cm = ContactManifold{};
        cm.normal = m.normal;
        cm.key = m.key;
        cm.pointCount = m.pointCount;
        for (int i = 0; i < m.pointCount; ++i) {
            cm.points[i].geometry = m.points[i];
            touching = touching || m.points[i].separation < linearSlop;
        }
        warmStartFrom(scratch.previous, cm, speculativeDistance);
        // The solver's anchors, found here where the shapes are at hand, so the solver's prepare
        // stage needs no shapes.
        for (int i = 0; i < cm.pointCount; ++i) {
            ContactPointState& p = cm.points[i];
            p.anchorA = contactAnchor(sa, a.state.orientation, p.geometry.point - a.state.position, -cm.normal);
            p.anchorB = contactAnchor(sb, b.state.orientation, p.geometry.point - b.state.position, cm.normal);
            p.baseSeparation = p.geometry.separation;
        }
    }
    c.touching = touching;
    // Pairs of flat shapes (boxes, hulls, planes) may be recycled from here (recycle). Round
    // shapes anchor on their cores (contactAnchor) and a mesh keeps a manifold per triangle: the
    // narrow phase runs for them every step.
    const auto flat = [](const Shape& s) {
        return s.type == ShapeType::Box || s.type == ShapeType::Convex || s.type == ShapeType::Plane;
    };
    c.recyclable = flat(sa) && flat(sb);
    c.cachedQA = a.state.orientation;
    c.cachedQB = b.state.orientation;
    c.cachedRelQ = a.state.orientation.conjugate() * b.state.orientation;
    c.cachedRelP = a.state.orientation.conjugate() * (b.state.position - a.state.position);
    const auto reach = [](const NativeBody& body, int shape) {
        if (!body.moves()) return 0.0;
        const Aabb& box = body.bounds[static_cast<std::size_t>(shape)];
        return box.extents().norm() + (box.center() - body.state.position).norm();
    };
    c.extent = std::max(reach(a, c.shapeA), reach(b, c.shapeB));
}

bool ContactManager::recycle(Contact& c, const NativeBody& a, const NativeBody& b, double linearSlop, double dt) const {
    // Resting: the bodies' relative speed at the shapes' farthest point moves it under a tenth of
    // linearSlop per step (a rocking or tipping body gets a new manifold every step).
    const double relativeSpeed = (b.state.linearVelocity - a.state.linearVelocity).norm() +
                                 c.extent * (b.state.angularVelocity - a.state.angularVelocity).norm();
    if (relativeSpeed * dt >= kRecycleRestFraction * linearSlop) return false;
    // Nearly where the narrow phase left them: no point of the shapes has moved by linearSlop, by
    // either body turning (the kept normal turns with neither) or by the pair's relative motion.
    const auto turned = [](const Quat& now, const Quat& then) { return 2.0 * (now * then.conjugate()).vec().norm(); };
    const double turnedA = turned(a.state.orientation, c.cachedQA), turnedB = turned(b.state.orientation, c.cachedQB);
    if (std::max(turnedA, turnedB) >= kRecycleMaxTurn) return false;
    const Quat relativeQ = a.state.orientation.conjugate() * b.state.orientation;
    const Vec3 relativeP = a.state.orientation.conjugate() * (b.state.position - a.state.position);
    const double moved = std::max({c.extent * turnedA, c.extent * turnedB,
                                   (relativeP - c.cachedRelP).norm() + c.extent * turned(relativeQ, c.cachedRelQ)});
    if (moved >= linearSlop) return false;
    const Quat turnA = a.state.orientation * c.cachedQA.conjugate(), turnB = b.state.orientation * c.cachedQB.conjugate();
    const Vec3 centers = b.state.position - a.state.position;
    bool touching = false;
    for (ContactManifold& m : c.manifolds)
        for (int i = 0; i < m.pointCount; ++i) {
            ContactPointState& p = m.points[i];
            // The anchors found (on a common point) turned with their bodies: the separation
            // moves as the solver's does within a step; the anchors themselves stay as found.
            const Vec3 rA = turnA * p.anchorA, rB = turnB * p.anchorB;
            p.geometry.separation = p.baseSeparation + m.normal.dot(centers + rB - rA);
            p.geometry.point = 0.5 * ((a.state.position + rA) + (b.state.position + rB));
            touching = touching || p.geometry.separation < linearSlop;
        }
    c.touching = touching;
    return true;
}

// Inlined: an out-of-line function whose only effect is a prefetch hint counts as pure to GCC,
// and its calls were dropped.
[[gnu::always_inline]] inline void ContactManager::prefetchAhead(std::size_t slot, const NativeBodies& bodies) const {
    if (slot + kSlotsAhead < slots_.size()) prefetchBytes(&slots_[slot + kSlotsAhead], kCacheLine);
    if (slot + kBodiesAhead >= slots_.size()) return;
    if (const Contact& next = slots_[slot + kBodiesAhead]; next.alive) {
        prefetchBytes(&bodies[next.bodyA], kBodyBytesRead);
        prefetchBytes(&bodies[next.bodyB], kBodyBytesRead);
    }
}

void ContactManager::update(NativeBodies& bodies, const BroadPhase& broadPhase, double speculativeDistance,
                            double linearSlop, double dt, bool planar, std::vector<std::uint32_t>& toWake,
                            TaskSystem* tasks) {
    const int workers = tasks ? tasks->workerCount() : 1;
    if (static_cast<int>(scratch_.size()) < workers) scratch_.resize(static_cast<std::size_t>(workers));
    // Fixed chunks of slots, each on any worker, each sorting its contacts into its own lists
    // while their slots are in cache; the lists are then taken in chunk order, so everything
    // comes out in slot order whatever the workers.
    constexpr std::size_t kSlotsPerChunk = 128;
    const std::size_t chunkCount = (slots_.size() + kSlotsPerChunk - 1) / kSlotsPerChunk;
    if (chunks_.size() < chunkCount) chunks_.resize(chunkCount);
    auto narrowPhase = [&](int begin, int end, int worker) {
        Scratch& scratch = scratch_[static_cast<std::size_t>(worker)];
        for (int chunk = begin; chunk < end; ++chunk) {
            ChunkLists& lists = chunks_[static_cast<std::size_t>(chunk)];
            lists.separated.clear();
            lists.candidates.clear();
            lists.wake.clear();
            const std::size_t first = static_cast<std::size_t>(chunk) * kSlotsPerChunk;
            const std::size_t last = std::min(slots_.size(), first + kSlotsPerChunk);
            for (std::size_t slot = first; slot < last; ++slot) {
                prefetchAhead(slot, bodies);
                Contact& c = slots_[slot];
                if (!c.alive) continue;
                collideContact(c, bodies, broadPhase, speculativeDistance, linearSlop, dt, planar, scratch);
                classify(c, static_cast<std::uint32_t>(slot), bodies, lists);
            }
        }
    };
    parallelFor(tasks, static_cast<int>(chunkCount), 1, narrowPhase);
    // Any worker may meet the largest pair next step: every worker's scratch keeps the largest
    // capacity any needed, so a steady world never allocates here.
    std::size_t found = 0, previous = 0;
    for (const Scratch& s : scratch_) {
        found = std::max(found, s.found.capacity());
        previous = std::max(previous, s.previous.capacity());
    }
    for (Scratch& s : scratch_) {
        s.found.reserve(found);
        s.previous.reserve(previous);
    }

    touchCandidates_.clear();
    for (std::size_t chunk = 0; chunk < chunkCount; ++chunk) {
        const ChunkLists& lists = chunks_[chunk];
        for (std::uint32_t slot : lists.separated) destroy(slot);
        touchCandidates_.insert(touchCandidates_.end(), lists.candidates.begin(), lists.candidates.end());
        toWake.insert(toWake.end(), lists.wake.begin(), lists.wake.end());
    }
}

void ContactManager::classify(const Contact& c, std::uint32_t slot, const NativeBodies& bodies,
                              ChunkLists& lists) {
    if (c.separated) {
        lists.separated.push_back(slot);
        return;
    }
    if (c.trigger || !c.manifolds.empty()) lists.candidates.push_back(slot);
    // A moving body about to hit a sleeping one wakes it (and so its island) as soon as their
    // manifold has points, speculative ones included: otherwise the solver would treat the
    // sleeper as immovable for the step of the impact.
    if (c.trigger || c.manifolds.empty()) return;
    const NativeBody &a = bodies[c.bodyA], &b = bodies[c.bodyB];
    if (!a.isActive() && !b.isActive()) return;
    if (!a.awake && a.moves()) lists.wake.push_back(c.bodyA);
    if (!b.awake && b.moves()) lists.wake.push_back(c.bodyB);
}

void ContactManager::destroy(std::uint32_t slot) {
    Contact& c = slots_[slot];
    if (auto node = index_.extract({proxyKey(c.bodyA, c.shapeA), proxyKey(c.bodyB, c.shapeB)})) spareNodes_.push_back(std::move(node));
    c.alive = false;
    c.manifolds.clear();
    free_.push_back(slot);
}

void ContactManager::removeBody(std::uint32_t body) {
    for (std::uint32_t slot = 0; slot < slots_.size(); ++slot) {
        const Contact& c = slots_[slot];
        if (c.alive && (c.bodyA == body || c.bodyB == body)) destroy(slot);
    }
}

void ContactManager::clear() {
    for (std::uint32_t slot = 0; slot < slots_.size(); ++slot)
        if (slots_[slot].alive) destroy(slot);
    touchCandidates_.clear();
}

}  // namespace anyphys::native
