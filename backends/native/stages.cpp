#include "stages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "collision/queries.hpp"
#include "anyphys/peers/gyroscopic.hpp"
#include "integrators.hpp"
#include "native_world.hpp"

namespace anyphys::native {
namespace {

bool hasGyroscopicBody(const NativeWorld& world, GyroscopicMode mode) {
    // In a plane the gyroscopic term w x Iw has no part about Z: the plane absorbs it.
    if (!world.effects().has(Effect::Gyroscopic) || world.settings().planar) return false;
    return std::any_of(world.bodies().begin(), world.bodies().end(), [&](const NativeBody& b) {
        return b.alive && b.isDynamic() && b.gyroscopic == mode && gyroscopic::isAnisotropic(b.inertia);
    });
}

class ImplicitGyroscopicStage final : public Stage {
public:
    std::string_view name() const override { return "gyroscopic_implicit"; }
    bool needed(const NativeWorld& world) const override { return hasGyroscopicBody(world, GyroscopicMode::Implicit); }
    void run(NativeWorld& world, const StepInfo& step) override {
        for (NativeBody& b : world.bodies()) {
            if (!b.isDynamic() || !b.isActive() || b.constrained || b.gyroscopic != GyroscopicMode::Implicit) continue;
            b.state.angularVelocity =
                gyroscopic::solveImplicit(b.state.angularVelocity, b.state.orientation, b.inertia, step.dt);
        }
    }
};

// Gives the user's force callback the integrator's intermediate states, and collects the forces
// it adds for this one evaluation.
// Kinematic bodies move at constant velocity: their motion is exact, whatever the integrator.
BodyState advanceKinematic(const BodyState& s, double h) {
    BodyState out = s;
    out.position += h * s.linearVelocity;
    out.orientation = rotateBy(s.orientation, s.angularVelocity, h);
    return out;
}

class StageForces final : public ForceStage {
public:
    StageForces(NativeWorld& world, const std::vector<int>& slotOfBody, double stepStart, double time,
                std::span<const BodyState> states, std::vector<Vec3>& forces, std::vector<Vec3>& torques)
        : world_(world), slotOfBody_(slotOfBody), stepStart_(stepStart), time_(time), states_(states),
          forces_(forces), torques_(torques) {}

    double time() const override { return time_; }
    BodyState state(const BodyPeer& peer) const override {
        const auto index = static_cast<const NativeBodyPeer&>(peer).index();
        const int slot = slotOfBody_[index];
        if (slot >= 0) return states_[slot];
        const NativeBody& b = world_.bodies()[index];
        return b.moves() ? advanceKinematic(b.state, time_ - stepStart_) : b.state;
    }
    void addForce(BodyPeer& peer, const Vec3& force) override {
        const int slot = slotOfBody_[static_cast<NativeBodyPeer&>(peer).index()];
        if (slot >= 0) forces_[slot] += force;
    }
    void addTorque(BodyPeer& peer, const Vec3& torque) override {
        const int slot = slotOfBody_[static_cast<NativeBodyPeer&>(peer).index()];
        if (slot >= 0) torques_[slot] += torque;
    }

private:
    NativeWorld& world_;
    const std::vector<int>& slotOfBody_;
    double stepStart_;
    double time_;
    std::span<const BodyState> states_;
    std::vector<Vec3>& forces_;
    std::vector<Vec3>& torques_;
};

class IntegrateStage final : public Stage {
public:
    std::string_view name() const override { return "integrate"; }
    bool needed(const NativeWorld& world) const override {
        return std::any_of(world.bodies().begin(), world.bodies().end(),
                           [](const NativeBody& b) { return b.alive && b.moves(); });
    }

    void run(NativeWorld& world, const StepInfo& step) override {
        gather(world);
        const Effects effects = world.effects();
        const bool gravity = effects.has(Effect::Gravity);
        const bool damping = effects.has(Effect::Damping);
        const bool explicitGyro = hasGyroscopicBody(world, GyroscopicMode::Explicit);
        const bool userForces = effects.has(Effect::UserForces);
        const bool hook = userForces && static_cast<bool>(world.forceHook());
        const Vec3 g = world.settings().gravity;
        auto& bodies = world.bodies();
        const bool semiImplicit = world.settings().integrator == Integrator::SemiImplicitEuler;

        // Accelerations of the bodies dynamic_[offset + i] at the integrator's states.
        const auto accelerationsAt = [&](std::size_t offset, double t, std::span<const BodyState> states,
                                         std::span<Acceleration> out) {
            if (hook) {
                std::fill(hookForces_.begin(), hookForces_.end(), Vec3::Zero());
                std::fill(hookTorques_.begin(), hookTorques_.end(), Vec3::Zero());
                StageForces stage(world, slotOfBody_, step.time, t, states, hookForces_, hookTorques_);
                world.forceHook()(stage);
            }
            for (std::size_t i = 0; i < states.size(); ++i) {
                const NativeBody& b = bodies[dynamic_[offset + i]];
                Acceleration& a = out[i];
                a = Acceleration{};
                const BodyState& s = states[i];
                if (gravity) a.linear += b.gravityScale * g;
                Vec3 torque = Vec3::Zero();
                if (userForces) {
                    a.linear += b.invMass * b.force;
                    torque += b.torque;
                }
                if (hook) {
                    a.linear += b.invMass * hookForces_[i];
                    torque += hookTorques_[i];
                }
                if (userForces) {
                    if (b.planar) {
                        // I_zz about world Z does not change as the body turns about Z.
                        a.angular += b.worldInverseInertia() * torque;
                    } else {
                        const Quat& q = s.orientation;
                        a.angular += q * b.invInertia.cwiseProduct(q.conjugate() * torque);
                    }
                }
                if (explicitGyro && b.gyroscopic == GyroscopicMode::Explicit)
                    a.angular += gyroscopic::acceleration(s.angularVelocity, s.orientation, b.inertia);
                if (damping) {  // else applied as factors around the step
                    if (!dampingAsFactor(b.linearDamping, step.dt, semiImplicit)) a.linear -= b.linearDamping * s.linearVelocity;
                    if (!dampingAsFactor(b.angularDamping, step.dt, semiImplicit))
                        a.angular -= b.angularDamping * s.angularVelocity;
                }
            }
        };
        // Bodies in [begin, end) on one worker. Without a force callback every body's forces are
        // its own, so ranges integrate independently; the callback sees all bodies at once (it
        // may couple them, and runs on the calling thread), so then there is one range.
        TaskSystem* tasks = world.taskSystem();
        const int workers = tasks ? tasks->workerCount() : 1;
        if (static_cast<int>(scratch_.size()) < workers) scratch_.resize(static_cast<std::size_t>(workers));
        const auto integrateRange = [&](int begin, int end, int worker) {
            const auto offset = static_cast<std::size_t>(begin);
            const auto accelerations = [&](double t, std::span<const BodyState> states, std::span<Acceleration> out) {
                accelerationsAt(offset, t, states, out);
            };
            integrate(world.settings().integrator, step.time, step.dt,
                      std::span<BodyState>(states_).subspan(offset, static_cast<std::size_t>(end - begin)), accelerations,
                      scratch_[static_cast<std::size_t>(worker)]);
        };
        // Semi-implicit Euler takes damping as the contact solver does, half its exact factor
        // before the step and half after; the other integrators only stiff damping, whole, before.
        const double firstShare = semiImplicit ? 0.5 : 1.0;
        if (damping) applyDampingFactors(bodies, step.dt, firstShare, semiImplicit);
        const int count = static_cast<int>(states_.size());
        constexpr int kMinBodiesPerRange = 256;
        if (hook)
            integrateRange(0, count, 0);
        else
            parallelFor(tasks, count, kMinBodiesPerRange, integrateRange);
        if (damping && semiImplicit) applyDampingFactors(bodies, step.dt, 1.0 - firstShare, semiImplicit);
        for (std::size_t i = 0; i < dynamic_.size(); ++i) bodies[dynamic_[i]].state = states_[i];
        for (NativeBody& b : bodies)
            if (b.type == BodyType::Kinematic && b.isActive() && !b.constrained) b.state = advanceKinematic(b.state, step.dt);
    }

private:
    // Damping dv/dt = -c v inside an explicit integrator is stable only while c h stays below
    // about 2 (a body damped at 150 1/s at 60 Hz grows 1.5x per step) and accurate only well
    // below that. For the higher-order integrators it stays in the acceleration up to c h = 0.1,
    // where they keep their order; beyond, the velocity is scaled by the exact decay exp(-c h)
    // before the step: stable for any c, and exact when damping is the only force. Semi-implicit
    // Euler, first order anyway, always takes the exact factor (split around the step), so a
    // damped body decays as exp(-c t) whether it is free or in contact: as a force its decay was
    // (1 - c h) per step, 14 % short of exp(-c t) after 2 s at c = 3 1/s and 60 Hz.
    static constexpr double kMaxExplicitDampingStep = 0.1;
    /// Whether damping at rate c acts as a velocity factor rather than as a force in the integrator.
    static bool dampingAsFactor(double c, double h, bool semiImplicit) { return semiImplicit || c * h > kMaxExplicitDampingStep; }

    void applyDampingFactors(const NativeBodies& bodies, double h, double share, bool semiImplicit) {
        for (std::size_t i = 0; i < dynamic_.size(); ++i) {
            const NativeBody& b = bodies[dynamic_[i]];
            if (b.linearDamping > 0.0 && dampingAsFactor(b.linearDamping, h, semiImplicit))
                states_[i].linearVelocity *= std::exp(-share * b.linearDamping * h);
            if (b.angularDamping > 0.0 && dampingAsFactor(b.angularDamping, h, semiImplicit))
                states_[i].angularVelocity *= std::exp(-share * b.angularDamping * h);
        }
    }

    // Copies the dynamic bodies' states into one contiguous array the integrator works on.
    void gather(NativeWorld& world) {
        const auto& bodies = world.bodies();
        dynamic_.clear();
        slotOfBody_.assign(bodies.size(), -1);
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            // Free bodies only: constrained ones are moved by the contact solver, asleep ones not at all.
            if (!bodies[i].isDynamic() || !bodies[i].isActive() || bodies[i].constrained) continue;
            slotOfBody_[i] = static_cast<int>(dynamic_.size());
            dynamic_.push_back(i);
        }
        states_.resize(dynamic_.size());
        for (std::size_t i = 0; i < dynamic_.size(); ++i) states_[i] = bodies[dynamic_[i]].state;
        hookForces_.resize(dynamic_.size());
        hookTorques_.resize(dynamic_.size());
    }

    std::vector<std::size_t> dynamic_;
    std::vector<int> slotOfBody_;
    std::vector<BodyState> states_;
    std::vector<Vec3> hookForces_;
    std::vector<Vec3> hookTorques_;
    std::vector<IntegratorScratch> scratch_;  // one per worker
};

class ClearForcesStage final : public Stage {
public:
    std::string_view name() const override { return "clear_forces"; }
    bool needed(const NativeWorld& world) const override { return world.effects().has(Effect::UserForces); }
    void run(NativeWorld& world, const StepInfo&) override {
        for (NativeBody& b : world.bodies()) {
            b.force.setZero();
            b.torque.setZero();
        }
    }
};

bool hasContacts(const NativeWorld& world) { return world.effects().has(Effect::Contacts); }

bool hasJoints(const NativeWorld& world) { return world.effects().has(Effect::Joints); }
bool hasConstraints(const NativeWorld& world) { return hasContacts(world) || hasJoints(world); }

// Broad phase and narrow phase, once per step.
class CollideStage final : public Stage {
public:
    std::string_view name() const override { return "collide"; }
    bool needed(const NativeWorld& world) const override { return hasContacts(world); }
    void run(NativeWorld& world, const StepInfo& step) override {
        if (!world.anyActive()) return;
        auto& bodies = world.bodies();
        world.updateAllProxies(step.dt);
        world.broadPhase().updatePairs(
            [&](std::uint64_t a, std::uint64_t b) { world.contactManager().addPair(a, b, bodies, world.materials()); },
            world.taskSystem());
        toWake_.clear();
        const WorldSettings& s = world.settings();
        world.contactManager().update(bodies, world.broadPhase(), s.speculativeDistance, s.linearSlop, step.dt, s.planar,
                                      toWake_, world.taskSystem());
        for (std::uint32_t i : toWake_) world.wakeBody(i);
    }

private:
    std::vector<std::uint32_t> toWake_;
};

// The step's constraints (contacts with points, joints with an awake body), before the free
// bodies are integrated: the bodies they hold are the solver's to move.
class CollectStage final : public Stage {
public:
    std::string_view name() const override { return "collect_constraints"; }
    bool needed(const NativeWorld& world) const override { return hasConstraints(world); }
    void run(NativeWorld& world, const StepInfo&) override {
        if (world.anyActive())
            world.solver().collect(world);
        else
            world.solver().clear();
    }
};

class SolveStage final : public Stage {
public:
    std::string_view name() const override { return "solve_constraints"; }
    bool needed(const NativeWorld& world) const override { return hasConstraints(world); }
    void run(NativeWorld& world, const StepInfo& step) override { world.solver().solve(world, step); }
};

// Time of impact against static geometry for bodies that moved far for their size this step:
// they stop where they would first have touched, keeping their velocity, and the next step's
// contact handles the impact. A fast small body cannot pass through a thin wall.
class ContinuousStage final : public Stage {
public:
    std::string_view name() const override { return "continuous"; }
    bool needed(const NativeWorld& world) const override {
        return hasContacts(world) && world.effects().has(Effect::ContinuousCollision);
    }
    void run(NativeWorld& world, const StepInfo&) override {
        auto& bodies = world.bodies();
        TaskSystem* tasks = world.taskSystem();
        const int workers = tasks ? tasks->workerCount() : 1;
        stops_.reset(workers);
        // The sweeps only read (the moving body, the static ones, the trees): any body on any worker.
        const auto sweepRange = [&](int begin, int end, int worker) {
            for (int i = begin; i < end; ++i) {
                const double first = firstImpact(world, static_cast<std::uint32_t>(i));
                if (first < 1.0) stops_.of(worker).push_back({static_cast<std::uint32_t>(i), first});
            }
        };
        constexpr int kMinBodiesPerRange = 256;
        parallelFor(tasks, static_cast<int>(bodies.size()), kMinBodiesPerRange, sweepRange);
        // Stopped in body order, whatever the workers: the tree comes out the same every run.
        std::vector<Stop>& all = stops_.joined();
        std::sort(all.begin(), all.end(), [](const Stop& x, const Stop& y) { return x.body < y.body; });
        for (const Stop& stop : all) {
            NativeBody& b = bodies[stop.body];
            const Vec3 travel = b.state.position - b.stepStartPosition;
            const Quat end = b.state.orientation;
            b.state.position = b.stepStartPosition + stop.first * travel;
            b.state.orientation = b.stepStartOrientation.slerp(stop.first, end);
            world.updateProxies(stop.body, Vec3::Zero());
        }
    }

private:
    struct Stop {
        std::uint32_t body;
        double first;  // fraction of the step's motion before it would first touch a static body
    };

    /// The fraction of body i's motion this step before it first meets a static body it was not
    /// touching at the start; 1 when it meets none or moved too little to tunnel.
    static double firstImpact(const NativeWorld& world, std::uint32_t i) {
        const auto& bodies = world.bodies();
        const NativeBody& b = bodies[i];
        if (!b.isActive() || !b.isDynamic() || b.trigger || b.shapes.empty()) return 1.0;
        const Vec3 travel = b.state.position - b.stepStartPosition;
        if (travel.norm() < 0.5 * b.coreExtent) return 1.0;  // the speculative margin covers it
        const double target = world.settings().linearSlop;
        const Transform start{b.stepStartPosition, b.stepStartOrientation}, end = b.pose();
        double first = 1.0;
        for (std::size_t k = 0; k < b.shapes.size(); ++k) {
            const Shape& shape = b.shapes[k];
            const ShapeSurface& mine = b.surfaces[k];
            if (mine.trigger) continue;  // a sensor child never stops the body
            const Transform from = shapeWorldPose(shape, start), to = shapeWorldPose(shape, end);
            const Aabb swept = computeAabb(shape, from).merged(computeAabb(shape, to));
            world.broadPhase().query(swept, [&](std::uint64_t key) {
                const NativeBody& other = bodies[proxyBody(key)];
                if (proxyBody(key) == i || other.type != BodyType::Static) return true;
                // A joint that keeps the pair apart from contacts keeps it from sweeps too.
                if (world.contactManager().excludes(i, proxyBody(key))) return true;
                const ShapeSurface& theirs = other.surfaces[proxyShape(key)];
                if (theirs.trigger || !layersCollide(mine.layer, mine.mask, theirs.layer, theirs.mask)) return true;
                const Shape& fixed = other.shapes[proxyShape(key)];
                // Already touching at the start: the contact solver owns that pair (a body
                // sliding fast along the ground must not be frozen in place).
                const double t = timeOfImpact(shape, from, to, fixed, shapeWorldPose(fixed, other.pose()), target);
                if (t > 0.0) first = std::min(first, t);
                return true;
            });
        }
        return first;
    }

    PerWorkerLists<Stop> stops_;
};

// Islands of touching bodies fall asleep together once all of them have rested long enough.
class SleepStage final : public Stage {
public:
    std::string_view name() const override { return "sleep"; }
    bool needed(const NativeWorld& world) const override { return world.effects().has(Effect::Sleeping); }
    void run(NativeWorld& world, const StepInfo& step) override {
        if (!world.anyActive()) return;  // all asleep already
        auto& bodies = world.bodies();
        const WorldSettings& s = world.settings();
        parent_.resize(bodies.size());
        for (std::uint32_t i = 0; i < bodies.size(); ++i) {
            parent_[i] = i;
            NativeBody& b = bodies[i];
            if (!b.isActive() || !b.isDynamic()) continue;
            const bool resting = b.allowSleep && b.state.linearVelocity.norm() < s.sleepLinearVelocity &&
                                 b.state.angularVelocity.norm() < s.sleepAngularVelocity;
            b.sleepTime = resting ? b.sleepTime + step.dt : 0.0;
        }
        world.contactManager().forEachTouchCandidate(bodies, [&](const Contact& c) {
            if (c.trigger || !c.touching) return;
            NativeBody &a = bodies[c.bodyA], &b = bodies[c.bodyB];
            const bool da = a.isActive() && a.isDynamic(), db = b.isActive() && b.isDynamic();
            if (da && db) unite(c.bodyA, c.bodyB);
            // A moving kinematic body keeps what it touches awake.
            if (da && isMovingKinematic(b)) a.sleepTime = 0.0;
            if (db && isMovingKinematic(a)) b.sleepTime = 0.0;
        });
        // Jointed bodies sleep and wake together.
        for (const NativeJoint& j : world.joints()) {
            if (!j.alive || j.bodyA == kWorldBody) continue;
            const NativeBody &a = bodies[j.bodyA], &b = bodies[j.bodyB];
            if (a.isActive() && a.isDynamic() && b.isActive() && b.isDynamic()) unite(j.bodyA, j.bodyB);
        }
        islandRest_.assign(bodies.size(), std::numeric_limits<double>::infinity());
        for (std::uint32_t i = 0; i < bodies.size(); ++i)
            if (bodies[i].isActive() && bodies[i].isDynamic())
                islandRest_[find(i)] = std::min(islandRest_[find(i)], bodies[i].sleepTime);
        members_.clear();
        for (std::uint32_t i = 0; i < bodies.size(); ++i)
            if (bodies[i].isActive() && bodies[i].isDynamic() && islandRest_[find(i)] >= s.timeToSleep)
                members_[find(i)].push_back(i);
        for (const auto& [root, island] : members_) world.sleepIsland(island);
    }

private:
    static bool isMovingKinematic(const NativeBody& b) {
        return b.alive && b.type == BodyType::Kinematic &&
               (!b.state.linearVelocity.isZero(0) || !b.state.angularVelocity.isZero(0));
    }
    std::uint32_t find(std::uint32_t i) {
        while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
        return i;
    }
    void unite(std::uint32_t a, std::uint32_t b) { parent_[find(a)] = find(b); }

    std::vector<std::uint32_t> parent_;
    std::vector<double> islandRest_;
    std::map<std::uint32_t, std::vector<std::uint32_t>> members_;
};

}  // namespace

std::unique_ptr<Stage> makeImplicitGyroscopicStage() { return std::make_unique<ImplicitGyroscopicStage>(); }
std::unique_ptr<Stage> makeIntegrateStage() { return std::make_unique<IntegrateStage>(); }
std::unique_ptr<Stage> makeClearForcesStage() { return std::make_unique<ClearForcesStage>(); }

std::vector<std::unique_ptr<Stage>> makePipeline() {
    std::vector<std::unique_ptr<Stage>> stages;
    stages.push_back(std::make_unique<CollideStage>());
    stages.push_back(std::make_unique<CollectStage>());
    stages.push_back(makeImplicitGyroscopicStage());
    stages.push_back(makeIntegrateStage());
    stages.push_back(std::make_unique<SolveStage>());
    stages.push_back(std::make_unique<ContinuousStage>());
    stages.push_back(std::make_unique<SleepStage>());
    stages.push_back(makeClearForcesStage());
    return stages;
}

}  // namespace anyphys::native
