#include "native_world.hpp"

#include <algorithm>
#include <limits>

#include "anyphys/peers/resolved_settings.hpp"
#include "collision/mesh_data.hpp"
#include "collision/queries.hpp"
#include "stages.hpp"

namespace anyphys::native {
namespace {

// Fat bounds exceed tight ones by this much, so bodies at rest or moving slowly keep their
// proxies (and broad-phase pairs) for many steps.
constexpr double kAabbMargin = 0.1;

// Planes are static: the narrow phase reads them in world form (n . x = offset).
void placePlane(Shape& s, const Transform& bodyPose) {
    const Transform xf = shapeWorldPose(s, bodyPose);
    s.normal = xf.orientation * s.planeNormalLocal;
    s.offset = s.planeOffsetLocal + s.normal.dot(xf.position);
}

// A native shape from the layer's shape at a static or moving body's pose.
Shape makeShape(const PeerShape& ps, const Transform& bodyPose) {
    Shape s;
    s.type = ps.def.type;
    s.radius = ps.def.radius;
    s.halfExtents = ps.def.halfExtents;
    s.halfHeight = ps.def.halfHeight;
    s.hull = ps.hull;
    s.local = ps.local;
    if (s.type == ShapeType::Mesh) s.mesh = MeshData::build(ps.def);
    if (s.type == ShapeType::Plane) {
        s.planeNormalLocal = ps.def.normal.normalized();
        s.planeOffsetLocal = ps.def.offset / ps.def.normal.norm();
        placePlane(s, bodyPose);
    }
    return s;
}

// How far a shape's centre lies inside its surface at the least: moving less than half of this
// per step cannot tunnel through anything.
double coreExtent(const Shape& s) {
    switch (s.type) {
        case ShapeType::Sphere:
        case ShapeType::Capsule: return s.radius;
        case ShapeType::Box: return s.halfExtents.minCoeff();
        case ShapeType::Convex: {
            double inner = std::numeric_limits<double>::infinity();
            for (std::size_t f = 0; f < s.hull->faceNormals.size(); ++f)
                inner = std::min(inner, s.hull->faceOffsets[f] - s.hull->faceNormals[f].dot(s.hull->centroid));
            return inner;
        }
        default: return 0.0;
    }
}

}  // namespace

NativeWorld::NativeWorld(const WorldSettings& settings)
    : settings_(settings), stages_(makePipeline()), broadPhase_(kAabbMargin) {
    // The layer resolved them (withBackendDefaults); refuse settings that skipped it.
    const Solver solver = resolvedSolver(settings_);
    resolvedSubsteps(settings_);
    const int iterations = resolvedIterations(settings_);
    const int relaxByDefault = solver == Solver::ProjectedGaussSeidel ? 0 : iterations;
    relaxIterations_ = static_cast<int>(backendOption(settings_, "relaxIterations", relaxByDefault));
}

NativeWorld::~NativeWorld() = default;

std::unique_ptr<BodyPeer> NativeWorld::createBody(const BodyPeerDef& peerDef) {
    const BodyDef& def = peerDef.def;
    std::uint32_t index;
    if (!freeSlots_.empty()) {
        index = freeSlots_.back();
        freeSlots_.pop_back();
        bodies_[index] = NativeBody{};
    } else {
        index = static_cast<std::uint32_t>(bodies_.size());
        bodies_.emplace_back();
    }
    NativeBody& body = bodies_[index];
    body.type = def.type;
    body.state = {def.position, def.orientation.normalized(), def.linearVelocity, def.angularVelocity};
    if (def.type == BodyType::Dynamic) {
        body.invMass = 1.0 / peerDef.mass.mass;
        body.inertia = peerDef.mass.inertia;
        body.invInertia = peerDef.mass.inertia.cwiseInverse();
        body.planar = settings_.planar;
    }
    body.linearDamping = def.linearDamping;
    body.angularDamping = def.angularDamping;
    body.gravityScale = def.gravityScale;
    body.gyroscopic = def.gyroscopic;
    body.userData = peerDef.userData;
    body.trigger = summarize(peerDef.shapes).allTriggers;
    body.allowSleep = def.allowSleep;
    body.awake = def.type != BodyType::Static && def.isAwake;  // static bodies are never simulated
    if (body.awake) ++awakeBodies_;
    if (peerDef.shapes.size() > 1) ++multiShapeBodies_;
    body.stepStartPosition = body.state.position;
    body.stepStartOrientation = body.state.orientation;
    body.coreExtent = std::numeric_limits<double>::infinity();
    for (const PeerShape& ps : peerDef.shapes) {
        body.shapes.push_back(makeShape(ps, body.pose()));
        body.surfaces.push_back({ps.material, ps.layer, ps.mask, ps.isTrigger});
        body.coreExtent = std::min(body.coreExtent, coreExtent(body.shapes.back()));
        const Shape& s = body.shapes.back();
        const int shapeIndex = static_cast<int>(body.shapes.size()) - 1;
        body.bounds.push_back(computeAabb(s, shapeWorldPose(s, body.pose())));
        body.proxies.push_back(broadPhase_.createProxy(body.bounds.back(), proxyKey(index, shapeIndex),
                                                       def.type == BodyType::Static));
    }
    auto peer = std::make_unique<NativeBodyPeer>(*this, index);
    body.peer = peer.get();
    pipelineDirty_ = true;
    return peer;
}

void NativeWorld::destroyBody(BodyPeer& peer) {
    const std::uint32_t index = static_cast<NativeBodyPeer&>(peer).index();
    NativeBody& body = bodies_[index];
    // Bodies resting on this one must not hang in the air.
    contacts_.forEach([&](const Contact& contact) {
        if (contact.touching && (contact.bodyA == index || contact.bodyB == index))
            wakeBody(contact.bodyA == index ? contact.bodyB : contact.bodyA);
    });
    contacts_.removeBody(index);
    for (int proxy : body.proxies) broadPhase_.destroyProxy(proxy);
    if (body.awake && body.moves()) --awakeBodies_;
    if (body.shapes.size() > 1) --multiShapeBodies_;
    if (const auto island = sleepingIslands_.find(body.sleepingIsland); island != sleepingIslands_.end()) {
        auto& members = island->second;
        members.erase(std::remove(members.begin(), members.end(), index), members.end());
        // An island whose last member is gone goes too: kept, the map grew by one entry for every
        // sleeping pile removed (the soak run's resident memory crept up 2 MiB in 1e6 steps).
        if (members.empty()) sleepingIslands_.erase(island);
    }
    body = NativeBody{};
    body.alive = false;
    freeSlots_.push_back(index);
    pipelineDirty_ = true;
}

std::unique_ptr<JointPeer> NativeWorld::createJoint(const JointPeerDef& def) {
    std::uint32_t index;
    if (!freeJoints_.empty()) {
        index = freeJoints_.back();
        freeJoints_.pop_back();
    } else {
        index = static_cast<std::uint32_t>(joints_.size());
        joints_.emplace_back();
    }
    NativeJoint& joint = joints_[index];
    joint = NativeJoint{};
    joint.alive = true;
    joint.def = def;
    joint.bodyA = def.bodyA ? static_cast<NativeBodyPeer*>(def.bodyA)->index() : kWorldBody;
    joint.bodyB = static_cast<NativeBodyPeer*>(def.bodyB)->index();
    if (!def.collideConnected && joint.bodyA != kWorldBody) contacts_.excludePair(joint.bodyA, joint.bodyB);
    wakeJoint(index);
    pipelineDirty_ = true;
    return std::make_unique<NativeJointPeer>(*this, index);
}

void NativeWorld::destroyJoint(JointPeer& peer) {
    const std::uint32_t index = static_cast<NativeJointPeer&>(peer).index();
    NativeJoint& joint = joints_[index];
    wakeJoint(index);  // the bodies it held must move again
    if (!joint.def.collideConnected && joint.bodyA != kWorldBody) {
        contacts_.includePair(joint.bodyA, joint.bodyB);
        // Overlapping bodies must meet again although neither proxy moves.
        for (int proxy : bodies_[joint.bodyB].proxies) broadPhase_.touchProxy(proxy);
    }
    joint = NativeJoint{};
    freeJoints_.push_back(index);
    pipelineDirty_ = true;
}

void NativeWorld::wakeJoint(std::uint32_t index) {
    const NativeJoint& joint = joints_[index];
    if (joint.bodyA != kWorldBody) wakeBody(joint.bodyA);
    wakeBody(joint.bodyB);
}

void NativeWorld::setEffects(Effects effects) {
    effects_ = effects;
    pipelineDirty_ = true;
}

void NativeWorld::setForceHook(ForceHook hook) {
    forceHook_ = std::move(hook);
    pipelineDirty_ = true;
}

void NativeWorld::setMaterialTable(const MaterialTable& table) {
    materials_ = table;
    contacts_.forEach([&](Contact& c) {
        const ContactMaterial& m =
            materials_.get(bodies_[c.bodyA].surfaces[c.shapeA].material, bodies_[c.bodyB].surfaces[c.shapeB].material);
        c.friction = m.friction;
        c.restitution = m.restitution;
    });
}

void NativeWorld::rebuildPipelineIfNeeded() {
    if (!pipelineDirty_) return;
    active_.clear();
    for (const auto& stage : stages_)
        if (stage->needed(*this)) active_.push_back(stage.get());
    pipelineDirty_ = false;
}

std::vector<std::string> NativeWorld::activeStageNames() {
    rebuildPipelineIfNeeded();
    std::vector<std::string> names;
    for (const Stage* stage : active_) names.emplace_back(stage->name());
    return names;
}

void NativeWorld::step(double time, double dt) {
    rebuildPipelineIfNeeded();
    const Vec3 gravity = effects_.has(Effect::Gravity) ? settings_.gravity : Vec3::Zero();
    const bool bounces = effects_.has(Effect::Restitution);
    const auto dot = [](const Vec3& x, const Vec3& y) { return x.dot(y); };
    anyActive_ = awakeBodies_ > 0;  // counts exactly the bodies isActive() accepts
    // Each body on its own: a walk over every body, split among the workers.
    const auto startBodies = [&](int begin, int end, int) {
        for (int i = begin; i < end; ++i) {
            NativeBody& b = bodies_[static_cast<std::size_t>(i)];
            if (!b.isActive()) continue;
            if (bounces) b.fall.note(fallNotedLastStep_, b.state.linearVelocity, b.gravityScale * gravity, lastStepDt_, dot);
            b.stepStartPosition = b.state.position;
            b.stepStartOrientation = b.state.orientation;
            b.constrained = false;
        }
    };
    constexpr int kMinBodiesPerRange = 256;
    parallelFor(tasks_, static_cast<int>(bodies_.size()), kMinBodiesPerRange, startBodies);
    for (Stage* stage : active_) stage->run(*this, {time, dt});
    lastStepDt_ = dt;
    fallNotedLastStep_ = bounces;
}

void NativeWorld::evaluateForceHook(double time) {
    hookForces_.assign(bodies_.size(), Vec3::Zero());
    hookTorques_.assign(bodies_.size(), Vec3::Zero());
    if (!forceHook_ || !effects_.has(Effect::UserForces)) return;
    // The hook sees current states and adds forces per body.
    class CurrentStage final : public ForceStage {
    public:
        CurrentStage(NativeWorld& w, double t) : world_(w), time_(t) {}
        double time() const override { return time_; }
        BodyState state(const BodyPeer& p) const override {
            return world_.bodies()[static_cast<const NativeBodyPeer&>(p).index()].state;
        }
        void addForce(BodyPeer& p, const Vec3& f) override { world_.hookForces_[static_cast<NativeBodyPeer&>(p).index()] += f; }
        void addTorque(BodyPeer& p, const Vec3& t) override {
            world_.hookTorques_[static_cast<NativeBodyPeer&>(p).index()] += t;
        }

    private:
        NativeWorld& world_;
        double time_;
    } stage(*this, time);
    forceHook_(stage);
}

void NativeWorld::wakeBody(std::uint32_t index) {
    NativeBody& body = bodies_[index];
    if (!body.alive || body.type == BodyType::Static) return;
    body.sleepTime = 0.0;
    if (body.awake) return;
    if (body.sleepingIsland >= 0) {
        const auto it = sleepingIslands_.find(body.sleepingIsland);
        if (it != sleepingIslands_.end()) {
            const std::vector<std::uint32_t> members = std::move(it->second);
            sleepingIslands_.erase(it);
            for (std::uint32_t m : members) {
                bodies_[m].stepStartPosition = bodies_[m].state.position;
                bodies_[m].stepStartOrientation = bodies_[m].state.orientation;
                setAwakeFlag(bodies_[m], true);
                bodies_[m].sleepTime = 0.0;
                bodies_[m].sleepingIsland = -1;
            }
        }
    }
    setAwakeFlag(body, true);
    body.sleepingIsland = -1;
    body.stepStartPosition = body.state.position;  // woken mid-step: its motion starts now
    body.stepStartOrientation = body.state.orientation;
}

void NativeWorld::sleepBody(std::uint32_t index) { sleepIsland({index}); }

void NativeWorld::setAwakeFlag(NativeBody& body, bool awake) {
    if (body.awake == awake) return;
    body.awake = awake;
    if (body.moves()) awakeBodies_ += awake ? 1 : -1;
}

void NativeWorld::sleepIsland(const std::vector<std::uint32_t>& members) {
    const int id = nextIslandId_++;
    for (std::uint32_t m : members) {
        NativeBody& b = bodies_[m];
        if (!b.alive || b.type == BodyType::Static) continue;
        setAwakeFlag(b, false);
        b.constrained = false;  // flags are reset each step only for awake bodies
        b.sleepingIsland = id;
        b.state.linearVelocity.setZero();
        b.state.angularVelocity.setZero();
        b.force.setZero();
        b.torque.setZero();
    }
    sleepingIslands_[id] = members;
}

void NativeWorld::updateProxies(std::uint32_t index, const Vec3& displacement) {
    NativeBody& body = bodies_[index];
    // The proxy must cover where the shape will be by the end of the step (its bounds swept
    // along the predicted displacement), or a fast body meets a neighbour before the broad
    // phase has paired them.
    for (std::size_t i = 0; i < body.shapes.size(); ++i) {
        const Aabb now = computeAabb(body.shapes[i], shapeWorldPose(body.shapes[i], body.pose()));
        body.bounds[i] = now;
        const Aabb swept = now.merged({now.min + displacement, now.max + displacement});
        broadPhase_.moveProxy(body.proxies[i], swept, displacement);
    }
}

void NativeWorld::updateAllProxies(double dt) {
    const int workers = tasks_ ? tasks_->workerCount() : 1;
    proxyMoves_.reset(workers);
    const auto findMoves = [&](int begin, int end, int worker) {
        auto& moves = proxyMoves_.of(worker);
        for (int i = begin; i < end; ++i) {
            NativeBody& body = bodies_[static_cast<std::size_t>(i)];  // this worker's bodies only
            if (!body.isActive()) continue;
            const Vec3 displacement = dt * body.state.linearVelocity;
            for (std::size_t s = 0; s < body.shapes.size(); ++s) {
                // Cover where the shape will be by the end of the step (see updateProxies); the
                // tight bounds are kept for the narrow phase's early-out.
                const Aabb now = computeAabb(body.shapes[s], shapeWorldPose(body.shapes[s], body.pose()));
                body.bounds[s] = now;
                const Aabb swept = now.merged({now.min + displacement, now.max + displacement});
                Aabb fat;
                if (broadPhase_.needsMove(body.proxies[s], swept, displacement, fat)) moves.push_back({body.proxies[s], fat});
            }
        }
    };
    constexpr int kMinBodiesPerRange = 256;
    parallelFor(tasks_, static_cast<int>(bodies_.size()), kMinBodiesPerRange, findMoves);
    // Moved in proxy order, whatever the workers: the tree comes out the same every run.
    std::vector<ProxyMove>& all = proxyMoves_.joined();
    std::sort(all.begin(), all.end());
    for (const ProxyMove& move : all) broadPhase_.setFatAabb(move.proxy, move.fat);
}

void NativeWorld::bodyTeleported(std::uint32_t index) {
    NativeBody& body = bodies_[index];
    if (body.type == BodyType::Static) {
        for (Shape& s : body.shapes)
            if (s.type == ShapeType::Plane) placePlane(s, body.pose());
        // Contacts with this body must be re-evaluated: wake whatever touches it.
        contacts_.forEach([&](const Contact& contact) {
            if (contact.bodyA == index || contact.bodyB == index)
                wakeBody(contact.bodyA == index ? contact.bodyB : contact.bodyA);
        });
    } else {
        wakeBody(index);
    }
    updateProxies(index, Vec3::Zero());
}

void NativeWorld::findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const {
    for (const NativeBody& b : bodies_)
        if (b.alive && b.moves() && !limits.admit(b.state)) out.push_back(b.userData);
}

void NativeWorld::reportContacts(ContactReport& out) {
    if (!anyActive_) return;  // everything at rest: asleep pairs are the layer's to keep
    const std::size_t candidates = contacts_.touchCandidateCount();
    constexpr std::size_t kContactsPerChunk = 512;
    const std::size_t chunks = (candidates + kContactsPerChunk - 1) / kContactsPerChunk;
    // The reported pairs among touch candidates [begin, end).
    const auto visit = [&](std::size_t begin, std::size_t end, auto&& onPair) {
        contacts_.forEachTouchCandidateIn(begin, end, bodies_, [&](const Contact& c) {
            const NativeBody &a = bodies_[c.bodyA], &b = bodies_[c.bodyB];
            if (!a.isActive() && !b.isActive()) return;  // both at rest: the layer keeps the pair
            if (c.trigger ? c.touching : !c.manifolds.empty()) onPair(c, a, b);
        });
    };
    const auto visitChunk = [&](std::size_t chunk, auto&& onPair) {
        const std::size_t begin = chunk * kContactsPerChunk;
        visit(begin, std::min(candidates, begin + kContactsPerChunk), onPair);
    };
    const auto pointsOf = [](const Contact& c) {
        std::size_t n = 0;
        if (!c.trigger)
            for (const ContactManifold& m : c.manifolds) n += static_cast<std::size_t>(m.pointCount);
        return n;
    };
    const auto asleep = [](const NativeBody& b) { return b.moves() && !b.awake; };
    // Writes contact c's pair at out.pairs[pair] and its points from out.points[point] on; returns
    // the index after its last point.
    const auto writePair = [&](const Contact& c, const NativeBody& a, const NativeBody& b, std::size_t pair, std::size_t point) {
        ContactReport::Pair& p = out.pairs[pair];
        p = {a.userData, b.userData, c.trigger, asleep(a) || asleep(b), false, Vec3::Zero(), static_cast<std::uint32_t>(point), 0};
        if (c.trigger) return point;
        p.normal = c.manifolds.front().normal;
        // The impulse over the whole step (all substeps), so impulse / dt is the mean force.
        for (const ContactManifold& m : c.manifolds)
            for (int i = 0; i < m.pointCount; ++i, ++p.pointCount)
                out.points[point++] = {m.points[i].geometry.point, -m.points[i].geometry.separation, m.points[i].stepImpulse};
        return point;
    };
    if (!tasks_ || tasks_->workerCount() <= 1) {
        // One worker: one walk, appending (the buffers keep their capacity from step to step). The
        // walk waits on memory (each contact, both bodies, the manifolds), and a second one missed
        // the caches again: on the 5 050-box planar pyramid the report was 8 % of a step.
        visit(0, candidates, [&](const Contact& c, const NativeBody& a, const NativeBody& b) {
            const std::size_t pair = out.pairs.size(), point = out.points.size();
            out.pairs.resize(pair + 1);
            out.points.resize(point + pointsOf(c));
            writePair(c, a, b, pair, point);
        });
    } else {
        // Several: in two passes over fixed chunks of the contacts that may touch, each chunk on any
        // worker: count each chunk's pairs and points, then write them at the chunk's offsets. The
        // report is in slot order whatever the workers, the same as one worker's.
        reportChunks_.assign(chunks + 1, ReportChunk{out.pairs.size(), out.points.size()});
        auto count = [&](int begin, int end, int) {
            for (int chunk = begin; chunk < end; ++chunk) {
                ReportChunk& n = reportChunks_[static_cast<std::size_t>(chunk) + 1];
                n = {};
                visitChunk(static_cast<std::size_t>(chunk), [&](const Contact& c, const NativeBody&, const NativeBody&) {
                    ++n.pairs;
                    n.points += pointsOf(c);
                });
            }
        };
        parallelFor(tasks_, static_cast<int>(chunks), 1, count);
        for (std::size_t k = 1; k <= chunks; ++k) {
            reportChunks_[k].pairs += reportChunks_[k - 1].pairs;
            reportChunks_[k].points += reportChunks_[k - 1].points;
        }
        out.pairs.resize(reportChunks_[chunks].pairs);
        out.points.resize(reportChunks_[chunks].points);
        auto write = [&](int begin, int end, int) {
            for (int chunk = begin; chunk < end; ++chunk) {
                std::size_t pair = reportChunks_[static_cast<std::size_t>(chunk)].pairs;
                std::size_t point = reportChunks_[static_cast<std::size_t>(chunk)].points;
                visitChunk(static_cast<std::size_t>(chunk), [&](const Contact& c, const NativeBody& a, const NativeBody& b) {
                    point = writePair(c, a, b, pair++, point);
                });
            }
        };
        parallelFor(tasks_, static_cast<int>(chunks), 1, write);
    }
    out.sleepKnown = true;
    // A body of several shapes meets another in several shape pairs: one report per body pair.
    if (multiShapeBodies_ > 0) out.mergeRepeatedPairs();
}

std::vector<PeerRayHit> NativeWorld::raycast(const Vec3& origin, const Vec3& direction, double maxDistance,
                                             bool closestOnly, std::uint32_t mask) {
    std::vector<PeerRayHit> hits;
    broadPhase_.rayCast(origin, direction, maxDistance, [&](std::uint64_t key, double clip) {
        const NativeBody& b = bodies_[proxyBody(key)];
        const ShapeSurface& surface = b.surfaces[proxyShape(key)];
        if (surface.trigger || (surface.layer & mask) == 0) return clip;
        const Shape& s = b.shapes[proxyShape(key)];
        const auto hit = native::raycast(s, shapeWorldPose(s, b.pose()), origin, direction, clip);
        if (!hit) return clip;
        if (closestOnly) hits.clear();
        hits.push_back({b.userData, hit->point, hit->normal, hit->distance});
        return closestOnly ? hit->distance : clip;
    });
    std::sort(hits.begin(), hits.end(), [](const PeerRayHit& x, const PeerRayHit& y) { return x.distance < y.distance; });
    return hits;
}

std::vector<std::uint64_t> NativeWorld::overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                                std::uint32_t mask) {
    std::vector<std::uint64_t> found;
    for (const PeerShape& ps : shapes) {
        const Shape query = makeShape(ps, pose);
        const Transform xf = shapeWorldPose(query, pose);
        broadPhase_.query(computeAabb(query, xf), [&](std::uint64_t key) {
            const NativeBody& b = bodies_[proxyBody(key)];
            const ShapeSurface& surface = b.surfaces[proxyShape(key)];
            if (surface.trigger || (surface.layer & mask) == 0) return true;
            const Shape& s = b.shapes[proxyShape(key)];
            if (native::overlap(query, xf, s, shapeWorldPose(s, b.pose()))) found.push_back(b.userData);
            return true;
        });
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
}

}  // namespace anyphys::native
