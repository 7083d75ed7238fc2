#include "solver/step_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "anyphys/peers/gyroscopic.hpp"
#include "anyphys/peers/joint_push.hpp"
#include "anyphys/task_system.hpp"
#include "native_world.hpp"
#include "solver/body_integration.hpp"
#include "solver/prefetch.hpp"
#include "solver/restitution_math.hpp"
#include "solver/state_runs.hpp"

namespace anyphys::native {
namespace {

/// When the stored velocity of a body in free flight is the true velocity: the integrator's
/// velocity lags (semi-implicit Euler: a leapfrog, its velocity belongs half a step before its
/// position) or leads (explicit Euler) by this much; the others keep them in step.
double velocityTimeOffset(Integrator integrator, double dt) {
    switch (integrator) {
        case Integrator::SemiImplicitEuler: return -0.5 * dt;
        case Integrator::ExplicitEuler: return 0.5 * dt;
        default: return 0.0;
    }
}

// Where a constraint comes in the solver's visiting order (ConstraintGraph): a hash of the
// bodies, shapes and manifold, the same every step the constraint lives.
std::uint32_t orderKey(const Contact& c, const ContactManifold& m) {
    std::uint64_t x = (std::uint64_t(c.bodyA) << 32 | c.bodyB) ^
                      ((std::uint64_t(std::uint32_t(c.shapeA)) << 40 | std::uint64_t(std::uint32_t(c.shapeB)) << 20 | m.key) *
                       0x9E3779B97F4A7C15ull);
    // A 64-bit finaliser (MurmurHash3's): every input bit moves every output bit.
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    x ^= x >> 33;
    return static_cast<std::uint32_t>(x >> 32);
}

// Blocks per worker for stages split among workers: enough to even out uneven blocks, few
// enough that claiming stays cheap.
constexpr int kBlocksPerWorker = 4;
constexpr int kMinWideBlock = 4;    // wide constraints
constexpr int kMinBodyBlock = 64;   // bodies

// Joints' stiffness, apart from the contacts' (as Box2D v3 keeps jointHertz apart from
// contactHertz): twice this, capped like the contacts. Tied to contactHertz, contacts stiff
// enough for small boxes (90 Hz) made joints ring: a ragdoll pile's joints opened to 12 cm.
constexpr double kJointHertz = 60.0;
constexpr double kJointDampingRatio = 2.0;

}  // namespace

void StepSolver::collect(NativeWorld& world) {
    for (std::uint32_t body : bodyOrder_) solverIndex_[body] = kStaticBody;
    lanes_.clear();
    bodyOrder_.clear();
    auto& bodies = world.bodies();
    if (solverIndex_.size() < bodies.size()) solverIndex_.resize(bodies.size(), kStaticBody);
    std::size_t enlisted = 0;  // solverIndex_ marks them, numbered at the end
    const auto enlist = [&](std::uint32_t index) {
        NativeBody& body = bodies[index];
        if (!body.moves() || !body.awake || body.constrained) return;
        body.constrained = true;
        solverIndex_[index] = 0;  // numbered below
        ++enlisted;
    };
    jointList_.clear();
    const bool joints = world.effects().has(Effect::Joints);
    for (std::uint32_t j = 0; joints && j < world.joints().size(); ++j) {
        const NativeJoint& joint = world.joints()[j];
        if (!joint.alive) continue;
        const auto awakeDynamic = [&](std::uint32_t body) {
            return body != kWorldBody && bodies[body].isDynamic() && bodies[body].awake;
        };
        if (!awakeDynamic(joint.bodyA) && !awakeDynamic(joint.bodyB)) continue;
        jointList_.push_back(j);
        if (joint.bodyA != kWorldBody) enlist(joint.bodyA);
        enlist(joint.bodyB);
    }
    if (world.effects().has(Effect::Contacts)) {
        world.contactManager().forEachTouchCandidate(bodies, [&](Contact& contact) {
            if (contact.trigger || contact.manifolds.empty()) return;
            const NativeBody &a = bodies[contact.bodyA], &b = bodies[contact.bodyB];
            if (!((a.isDynamic() && a.awake) || (b.isDynamic() && b.awake))) return;
            for (ContactManifold& m : contact.manifolds)
                if (m.pointCount > 0)
                    lanes_.push_back({&m, static_cast<std::int32_t>(contact.bodyA), static_cast<std::int32_t>(contact.bodyB),
                                      contact.friction, contact.restitution, orderKey(contact, m), contact.flatPair});
            enlist(contact.bodyA);
            enlist(contact.bodyB);
        });
    }
    // Solver bodies numbered in world order, not in the order constraints named them: bodies
    // created together (a grid's layer, a pyramid's row) are mostly neighbours, and the colours
    // visit their constraints in body order (ConstraintGraph), so the passes read the state
    // array nearly in sequence. The numbering changes no result: every stage treats bodies
    // alike whatever their index.
    bodyOrder_.reserve(enlisted);
    for (std::uint32_t index = 0; bodyOrder_.size() < enlisted; ++index) {
        if (solverIndex_[index] == kStaticBody) continue;
        solverIndex_[index] = static_cast<std::int32_t>(bodyOrder_.size());
        bodyOrder_.push_back(index);
    }
}

void StepSolver::clear() {
    for (std::uint32_t body : bodyOrder_) solverIndex_[body] = kStaticBody;
    lanes_.clear();
    jointList_.clear();
    bodyOrder_.clear();
}

std::vector<const char*> StepSolver::lastStageNames() const {
    std::vector<const char*> names;
    for (const StagePlan& p : plan_) {
        switch (p.kind) {
            case StageKind::PrepareContacts: names.push_back("prepare_contacts"); break;
            case StageKind::WarmStartJoints: names.push_back("warm_start_joints"); break;
            case StageKind::SolveJoints: names.push_back("solve_joints"); break;
            case StageKind::RelaxJoints: names.push_back("relax_joints"); break;
            case StageKind::ReportJoints: names.push_back("report_joints"); break;
            case StageKind::ForceCallback: names.push_back("force_callback"); break;
            case StageKind::IntegrateVelocities: names.push_back("integrate_velocities"); break;
            case StageKind::WarmStart: names.push_back("warm_start"); break;
            case StageKind::Solve: names.push_back("solve"); break;
            case StageKind::IntegratePositions: names.push_back("integrate_positions"); break;
            case StageKind::CorrectJoints: names.push_back("correct_joints"); break;
            case StageKind::Relax: names.push_back("relax"); break;
            case StageKind::Restitution: names.push_back("restitution"); break;
            case StageKind::RestitutionJoints: names.push_back("restitution_joints"); break;
            case StageKind::StoreImpulses: names.push_back("store_impulses"); break;
            case StageKind::FinalizeBodies: names.push_back("finalize_bodies"); break;
        }
    }
    return names;
}

void StepSolver::buildBodies(NativeWorld& world, const StepInfo& step) {
    const WorldSettings& settings = world.settings();
    const Effects effects = world.effects();
    const Vec3 gravity = effects.has(Effect::Gravity) ? settings.gravity : Vec3::Zero();
    const bool userForces = effects.has(Effect::UserForces);
    const bool damping = effects.has(Effect::Damping);
    // In a plane the gyroscopic term w x Iw has no part about Z: the plane absorbs it.
    const bool gyroscopic = effects.has(Effect::Gyroscopic) && !settings.planar;
    const std::size_t n = bodyOrder_.size();
    bodies_.resize(n);
    states_.resize(n);
    auto& worldBodies = world.bodies();
    // Each body on its own: split among the workers like the other body stages.
    auto buildRange = [&](int begin, int end, int) {
        for (int i = begin; i < end; ++i)
            buildBody(bodyOrder_[i], worldBodies[bodyOrder_[i]], bodies_[i], states_[i], gravity, userForces, damping, gyroscopic);
    };
    parallelFor(world.taskSystem(), static_cast<int>(n), kMinBodyBlock, buildRange);
    (void)step;
}

void StepSolver::buildBody(std::uint32_t index, const NativeBody& nb, SolverBody& sb, SolverState& s, const Vec3& gravity,
                           bool userForces, bool damping, bool gyroscopic) const {
    sb = SolverBody{};
    sb.body = index;
    sb.dynamic = nb.isDynamic();
    sb.position0 = nb.state.position;
    sb.orientation0 = nb.state.orientation;
    if (sb.dynamic) {
        sb.invMass = nb.invMass * nb.linearFreedom();
        sb.invInertia = nb.worldInverseInertia();
        sb.inertia = nb.inertia;
        sb.linearAcceleration = nb.gravityScale * gravity;
        if (userForces) {
            sb.linearAcceleration += sb.invMass.cwiseProduct(nb.force);
            sb.angularAcceleration = sb.invInertia * nb.torque;
        }
        if (nb.fall.fellLastStep()) sb.bounceAcceleration = sb.linearAcceleration;
        if (damping) {  // exact decay of dv/dt = -c v over half a substep: stable for any c
            sb.linearHalfDampingFactor = std::exp(-0.5 * nb.linearDamping * h_);
            sb.angularHalfDampingFactor = std::exp(-0.5 * nb.angularDamping * h_);
        }
        if (gyroscopic && gyroscopic::isAnisotropic(nb.inertia)) sb.gyroscopic = nb.gyroscopic;
    }
    s = SolverState{};
    for (int k = 0; k < 3; ++k) {
        s.v[k] = nb.state.linearVelocity[k];
        s.w[k] = nb.state.angularVelocity[k];
    }
}

// Springs step their stiffness explicitly only while the body's springs together stay well inside
// explicit stepping's stable range, so each spring needs the count on its busiest body.
void StepSolver::countSpringsPerBody() {
    const auto sprung = [](const JointConstraint& c) { return c.joint->def.spring.has_value(); };
    if (std::none_of(joints_.begin(), joints_.end(), sprung)) return;  // each keeps its count of 1
    springsPerBody_.assign(bodies_.size(), 0);
    const auto count = [&](std::int32_t body) {
        if (body != kStaticBody && springsPerBody_[static_cast<std::size_t>(body)] < UINT16_MAX)
            ++springsPerBody_[static_cast<std::size_t>(body)];
    };
    for (const JointConstraint& c : joints_)
        if (sprung(c)) {
            count(c.a);
            count(c.b);
        }
    for (JointConstraint& c : joints_) {
        const auto on = [&](std::int32_t body) { return body == kStaticBody ? 0 : int(springsPerBody_[static_cast<std::size_t>(body)]); };
        c.springsOnBusierBody = std::max(1, std::max(on(c.a), on(c.b)));
    }
}

void StepSolver::buildConstraints() {
    const bool joints = !jointList_.empty();  // only the joint passes read SolverBody::contacted
    for (ContactLane& lane : lanes_) {
        lane.bodyA = solverIndex_[static_cast<std::uint32_t>(lane.bodyA)];
        lane.bodyB = solverIndex_[static_cast<std::uint32_t>(lane.bodyB)];
        if (joints)
            for (std::int32_t body : {lane.bodyA, lane.bodyB})
                if (body != kStaticBody) bodies_[static_cast<std::size_t>(body)].contacted = true;
    }
    graph_.build(lanes_, bodies_);
    joints_.clear();
    for (std::uint32_t j : jointList_) {
        NativeJoint& joint = world_->joints()[j];
        JointConstraint c;
        c.joint = &joint;
        const auto side = [&](std::uint32_t body, std::int32_t& index, Transform& fixed) {
            if (body == kWorldBody) return;  // identity pose
            index = solverIndex_[body];
            fixed = world_->bodies()[body].pose();  // used when the body is not a solver body (static)
        };
        side(joint.bodyA, c.a, c.fixedA);
        side(joint.bodyB, c.b, c.fixedB);
        for (std::int32_t body : {c.a, c.b})
            if (body != kStaticBody) bodies_[static_cast<std::size_t>(body)].jointed = true;
        joints_.push_back(c);
    }
    countSpringsPerBody();
    const auto& colors = graph_.colors();
    const std::size_t colorCount = colors.size();
    colorFirstWide_.resize(colorCount);
    colorWideCount_.resize(colorCount);
    int total = 0;
    for (std::size_t c = 0; c < colorCount; ++c) {
        const bool overflow = graph_.hasOverflow() && c + 1 == colorCount;
        colorFirstWide_[c] = total;
        // Overflow constraints may share bodies: one to a WideContact, solved in order.
        colorWideCount_[c] = overflow ? colors[c].laneCount : (colors[c].laneCount + wide::kLanes - 1) / wide::kLanes;
        total += colorWideCount_[c];
    }
    wideCount_ = total;
    if (planarWorld_) {
        planar_.resize(static_cast<std::size_t>(total));
        planarCold_.resize(static_cast<std::size_t>(total));
        planarWarm_.resize(static_cast<std::size_t>(total));
    } else {
        wide_.resize(static_cast<std::size_t>(total));
        wideCold_.resize(static_cast<std::size_t>(total));
        wideWarm_.resize(static_cast<std::size_t>(total));
    }
    wideSource_.resize(static_cast<std::size_t>(total));
    for (std::size_t c = 0; c < colorCount; ++c) {
        const bool overflow = graph_.hasOverflow() && c + 1 == colorCount;
        const int perWide = overflow ? 1 : wide::kLanes;
        for (int k = 0; k < colorWideCount_[c]; ++k) {
            const int first = colors[c].firstLane + k * perWide;
            wideSource_[colorFirstWide_[c] + k] = {first, std::min(perWide, colors[c].firstLane + colors[c].laneCount - first)};
        }
    }
}

void StepSolver::addStage(StageKind kind, int items, int color, int substep, bool endOfSubstep) {
    // Joints are few and solved one after another: one block, on whichever worker takes it.
    const bool jointStage = kind == StageKind::WarmStartJoints || kind == StageKind::SolveJoints ||
                            kind == StageKind::CorrectJoints || kind == StageKind::RelaxJoints ||
                            kind == StageKind::RestitutionJoints || kind == StageKind::ReportJoints;
    if (jointStage) {
        plan_.push_back({kind, color, substep, endOfSubstep, items, std::max(items, 1)});
        stages_.push_back({items > 0 ? 1 : 0, false});
        return;
    }
    const bool wideStage = kind != StageKind::IntegrateVelocities && kind != StageKind::IntegratePositions &&
                           kind != StageKind::FinalizeBodies && kind != StageKind::ForceCallback;
    const bool serial = wideStage && graph_.hasOverflow() && color + 1 == static_cast<int>(colorWideCount_.size()) &&
                        kind != StageKind::PrepareContacts && kind != StageKind::StoreImpulses;
    int blockSize = std::max(items, 1);
    if (workers_ > 1 && !serial) {
        const int minBlock = wideStage ? kMinWideBlock : kMinBodyBlock;
        blockSize = std::max(minBlock, (items + workers_ * kBlocksPerWorker - 1) / (workers_ * kBlocksPerWorker));
    }
    const int blocks = kind == StageKind::ForceCallback ? 1 : (items + blockSize - 1) / blockSize;
    plan_.push_back({kind, color, substep, endOfSubstep, items, blockSize});
    stages_.push_back({blocks, kind == StageKind::ForceCallback});
}

void StepSolver::planStages(const NativeWorld& world) {
    const WorldSettings& settings = world.settings();
    const int substeps = *settings.substeps, iterations = *settings.iterations;
    const int relaxIterations = world.relaxIterations();
    const bool hook = world.forceHook() && world.effects().has(Effect::UserForces);
    const int bodies = static_cast<int>(bodies_.size()), wide = wideCount_;
    const int colors = static_cast<int>(colorWideCount_.size());
    plan_.clear();
    stages_.clear();
    addStage(StageKind::PrepareContacts, wide);
    // Colours in order: contacts with static bodies come last (ConstraintGraph). Passes do not
    // alternate direction: measured on a 40-row pyramid, alternating let it slide apart.
    // Joints first in every pass: contacts then have the last word.
    const int joints = static_cast<int>(joints_.size());
    const auto pass = [&](StageKind kind, int sub, bool last) {
        if (joints > 0) addStage(kind == StageKind::Solve ? StageKind::SolveJoints : StageKind::RelaxJoints, joints, 0, sub, last);
        for (int c = 0; c < colors; ++c) addStage(kind, colorWideCount_[c], c, sub, last);
    };
    for (int sub = 0; sub < substeps; ++sub) {
        if (hook) addStage(StageKind::ForceCallback, 1, 0, sub);
        addStage(StageKind::IntegrateVelocities, bodies);
        if (joints > 0) addStage(StageKind::WarmStartJoints, joints);
        for (int c = 0; c < colors; ++c) addStage(StageKind::WarmStart, colorWideCount_[c], c);
        // The substep's last pass, solve or relax, leaves the impulses the events report.
        for (int it = 0; it < iterations; ++it) pass(StageKind::Solve, sub, relaxIterations == 0 && it + 1 == iterations);
        addStage(StageKind::IntegratePositions, bodies);
        // PGS's joints take back their position errors here, one pass per velocity pass
        // (joint_solver.hpp); the soft step's do it softly in the solve passes.
        if (joints > 0 && *settings.solver == Solver::ProjectedGaussSeidel)
            for (int it = 0; it < iterations; ++it) addStage(StageKind::CorrectJoints, joints);
        for (int it = 0; it < relaxIterations; ++it) pass(StageKind::Relax, sub, it + 1 == relaxIterations);
    }
    // Each round of the restitution stage ends with the joints of the bodies in a bounce
    // (solveJointsInBounce), so a bounce reaches through a joint as it does through a resting contact.
    if (restitution_)
        for (int round = 0; round < kRestitutionRounds; ++round) {
            for (int c = 0; c < colors; ++c) addStage(StageKind::Restitution, colorWideCount_[c], c, round);
            if (joints > 0) addStage(StageKind::RestitutionJoints, joints, 0, round);
        }
    addStage(StageKind::StoreImpulses, wide);
    if (joints > 0) addStage(StageKind::ReportJoints, joints);
    addStage(StageKind::FinalizeBodies, bodies);
}

void StepSolver::solve(NativeWorld& world, const StepInfo& step) {
    if (empty()) return;
    const WorldSettings& settings = world.settings();
    const Effects effects = world.effects();
    world_ = &world;
    step_ = step;
    const int substeps = *settings.substeps;
    h_ = step.dt / substeps;
    workers_ = world.taskSystem() ? world.taskSystem()->workerCount() : 1;

    // Stiffness capped: a spring stiffer than the substeps resolve makes unconverged Gauss-Seidel
    // ring. The cap gives each period of the contact spring at least five substeps, but is not
    // below half the step rate, where a single substep would leave stacks too soft to stand.
    // Box2D v3's bound, a quarter of the substep rate, let piles ring for ever at 4 substeps of a
    // 60 Hz step (60 Hz contacts): a dropped 3 x 3 x 10 grid kept its fastest box at 0.12 m/s
    // after 10 s; at 48 Hz it rests (NativeContactStiffness). Contacts with static bodies are
    // twice as stiff (as Box2D v3), so piles do not sink into the ground.
    const double stepRate = 1.0 / step.dt;
    const double maxHertz = std::max(0.2 * substeps * stepRate, 0.5 * stepRate);
    const double hertz = std::min(settings.contactHertz, maxHertz);
    prepareParams_.dynamicSoftness = makeSoftness(hertz, settings.contactDampingRatio, h_);
    prepareParams_.staticSoftness = makeSoftness(2.0 * hertz, settings.contactDampingRatio, h_);
    // Between moving bodies, contacts that carry more than their pair's weight stiffen, up to the
    // same cap (contactSoftness): ten 2 cm cubes stood 184 mm off true at 60 Hz, 1.9 mm so.
    prepareParams_.load = {hertz, maxHertz, settings.contactDampingRatio, h_,
                           effects.has(Effect::Gravity) ? settings.gravity.norm() : 0.0};
    prepareParams_.speculativeDistance = settings.speculativeDistance;
    prepareParams_.linearSlop = settings.linearSlop;
    prepareParams_.velocityTimeOffset = velocityTimeOffset(settings.integrator, step.dt);
    prepareParams_.stepTime = step.dt;
    prepareParams_.substep = h_;
    prepareParams_.warmStart = true;
    solveParams_.invH = 1.0 / h_;
    solveParams_.pushMaxVelocity = settings.contactPushMaxVelocity;
    solveParams_.soft = *settings.solver != Solver::ProjectedGaussSeidel;
    solveParams_.baumgarte = settings.baumgarte;
    solveParams_.linearSlop = settings.linearSlop;
    solveParams_.friction = effects.has(Effect::Friction);
    solveParams_.restitutionThreshold = settings.restitutionThreshold;
    restitution_ = effects.has(Effect::Restitution);
    bounceFound_.store(false, std::memory_order_relaxed);
    // Joints hold their position errors as stiffly as contacts with static bodies at the default
    // contactHertz (Box2D v3's joint softness), damped a little more, whatever contactHertz is.
    jointParams_.h = h_;
    jointParams_.invH = 1.0 / h_;
    jointParams_.soft = solveParams_.soft;
    jointParams_.softness = makeSoftness(2.0 * std::min(kJointHertz, maxHertz), kJointDampingRatio, h_);
    jointParams_.baumgarte = settings.baumgarte;
    // The soft step closes a joint anchor's position error no faster than this (joint_push.hpp);
    // a hinge wrenched 120 degrees opens 13 mm on its way back instead of 10.
    jointParams_.anchorPushMaxVelocity = kJointPushMaxVelocity;

    planarWorld_ = settings.planar;
    buildBodies(world, step);
    if (restitution_) bounceSupports_.assign(bodies_.size(), Vec3::Zero());  // nothing holds a body yet
    buildConstraints();
    // A core's cache on the machines measured (2 MB here, 1 to 2 MB on most desktops): the
    // 1 000-box drop's records (0.7 MB) fit, the 10 000-box drop's (7 MB) do not.
    constexpr std::size_t kRecordsInCache = std::size_t(2) << 20;
    const std::size_t recordBytes = planarWorld_ ? sizeof(PlanarContact) : sizeof(WideContact);
    solveParams_.prefetchRecords = static_cast<std::size_t>(wideCount_) * recordBytes > kRecordsInCache;
    planStages(world);
    runner_.run(world.taskSystem(), stages_, *this);
}

void StepSolver::runBlock(int stage, int block, int worker) {
    (void)worker;
    const StagePlan& p = plan_[static_cast<std::size_t>(stage)];
    const int begin = block * p.blockSize, end = std::min(p.items, begin + p.blockSize);
    const int count = end - begin;
    const int first = p.color < static_cast<int>(colorFirstWide_.size()) ? colorFirstWide_[p.color] + begin : 0;
    if (planarWorld_ && runPlanarBlock(p, first, begin, end)) return;
    // Only colour stages address a slice of the constraint arrays: the others also run in a world
    // with no contact at all, where data() is null and null + offset is undefined.
    const auto colour = [&] { return wide_.data() + first; };
    const auto warm = [&] { return wideWarm_.data() + first; };
    switch (p.kind) {
        case StageKind::PrepareContacts:
            for (int w = begin; w < end; ++w) {
                if (w + kRecordsAhead < end) prefetchPrepare(w + kRecordsAhead);
                ContactLane lanes[wide::kLanes];
                const int n = gatherLanes(w, lanes);
                prepareContacts(wide_[w], wideCold_[w], lanes, n, bodies_.data(), states_.data(), prepareParams_);
            }
            summarizeImpulses(wide_.data() + begin, wideWarm_.data() + begin, count);
            break;
        case StageKind::IntegrateVelocities: integrateVelocities(bodies_.data(), states_.data(), begin, end, h_); break;
        case StageKind::WarmStart: warmStartContacts(warm(), count, states_.data()); break;
        case StageKind::Solve:
            solveContacts(colour(), warm(), count, states_.data(), solveParams_, true, p.endOfSubstep);
            break;
        case StageKind::IntegratePositions: integratePositions(states_.data(), begin, end, h_); break;
        case StageKind::Relax:
            solveContacts(colour(), warm(), count, states_.data(), solveParams_, false, p.endOfSubstep);
            break;
        case StageKind::Restitution:
            if (skipRestitutionRound(p)) break;
            if (applyRestitution(colour(), wideCold_.data() + first, count, states_.data(), bounceSupports_.data(), solveParams_))
                noteBounce();
            break;
        case StageKind::StoreImpulses: storeImpulses(wide_.data() + begin, wideCold_.data() + begin, count); break;
        case StageKind::FinalizeBodies: finalizeBodies(begin, end); break;
        case StageKind::WarmStartJoints:
            for (const JointConstraint& c : joints_) warmStartJoint(c, bodies_.data(), states_.data(), jointParams_);
            break;
        case StageKind::SolveJoints:
            for (const JointConstraint& c : joints_)
                solveJoint(c, bodies_.data(), states_.data(), jointParams_, true, p.endOfSubstep);
            break;
        case StageKind::CorrectJoints:
            for (const JointConstraint& c : joints_) correctJointPosition(c, bodies_.data(), states_.data(), jointParams_);
            break;
        case StageKind::RelaxJoints:
            for (const JointConstraint& c : joints_)
                solveJoint(c, bodies_.data(), states_.data(), jointParams_, false, p.endOfSubstep);
            break;
        case StageKind::RestitutionJoints: solveJointsInBounce(p); break;
        case StageKind::ReportJoints:
            restoreJointImpulses();
            for (const JointConstraint& c : joints_) reportJoint(c, bodies_.data(), states_.data(), step_.dt);
            break;
        case StageKind::ForceCallback: break;  // main thread only
    }
}

// A bounce found after the substeps changes a jointed body's velocity without its joints: a
// pendulum's bob bouncing off a wall with e = 1 had its speed reversed but kept its turn (the
// contact pushes through its centre), and the next step's joint passes then took 1.2 % of its
// energy at each bounce. Each round of the restitution stage therefore ends with a relax pass
// (rigid, no bias) over the joints holding a body in the bounce; the rounds alternate the two until
// both hold. What these passes add is the bounce's, not a load: it is not warm-started next step
// (a pendulum would be kicked by it again) nor reported, as the contacts keep the stage's impulses
// apart.
void StepSolver::solveJointsInBounce(const StagePlan& p) {
    if (skipRestitutionRound(p)) return;
    const auto inBounce = [&](std::int32_t body) { return wide::stateOf(states_.data(), body).inBounce != 0.0; };
    for (std::size_t k = 0; k < joints_.size(); ++k) {
        const JointConstraint& c = joints_[k];
        if (!inBounce(c.a) && !inBounce(c.b)) continue;
        if (!jointsInBounce_) {  // the first joint pass of the step keeps the impulses to restore
            jointImpulsesBeforeBounce_.resize(joints_.size());
            for (std::size_t j = 0; j < joints_.size(); ++j) jointImpulsesBeforeBounce_[j] = joints_[j].joint->impulse;
            jointsInBounce_ = true;
        }
        solveJoint(c, bodies_.data(), states_.data(), jointParams_, false, false);
    }
}

void StepSolver::restoreJointImpulses() {
    if (!jointsInBounce_) return;
    for (std::size_t j = 0; j < joints_.size(); ++j) joints_[j].joint->impulse = jointImpulsesBeforeBounce_[j];
    jointsInBounce_ = false;
}

void StepSolver::prefetchPrepare(int w) const {
    const WideSource& src = wideSource_[static_cast<std::size_t>(w)];
    for (int k = 0; k < src.count; ++k) {
        const ContactLane& lane = lanes_[graph_.lanes()[static_cast<std::size_t>(src.first + k)]];
        prefetchBytes(lane.manifold, sizeof(ContactManifold));
        for (const std::int32_t body : {lane.bodyA, lane.bodyB})
            if (body != kStaticBody) prefetchBytes(&bodies_[static_cast<std::size_t>(body)], sizeof(SolverBody));
    }
}

int StepSolver::gatherLanes(int w, ContactLane (&lanes)[wide::kLanes]) const {
    const WideSource& src = wideSource_[static_cast<std::size_t>(w)];
    for (int k = 0; k < src.count; ++k) lanes[k] = lanes_[graph_.lanes()[static_cast<std::size_t>(src.first + k)]];
    return src.count;
}

bool StepSolver::runPlanarBlock(const StagePlan& p, int first, int begin, int end) {
    const int count = end - begin;
    const auto colour = [&] { return planar_.data() + first; };  // as in runBlock
    const auto warm = [&] { return planarWarm_.data() + first; };
    switch (p.kind) {
        case StageKind::PrepareContacts:
            for (int w = begin; w < end; ++w) {
                if (w + kRecordsAhead < end) prefetchPrepare(w + kRecordsAhead);
                ContactLane lanes[wide::kLanes];
                const int n = gatherLanes(w, lanes);
                preparePlanarContacts(planar_[w], planarCold_[w], lanes, n, bodies_.data(), states_.data(), prepareParams_);
            }
            summarizePlanarImpulses(planar_.data() + begin, planarWarm_.data() + begin, count);
            return true;
        case StageKind::WarmStart: warmStartPlanarContacts(warm(), count, states_.data()); return true;
        case StageKind::Solve:
            solvePlanarContacts(colour(), warm(), count, states_.data(), solveParams_, true, p.endOfSubstep);
            return true;
        case StageKind::Relax:
            solvePlanarContacts(colour(), warm(), count, states_.data(), solveParams_, false, p.endOfSubstep);
            return true;
        case StageKind::Restitution:
            if (!skipRestitutionRound(p) && applyPlanarRestitution(colour(), planarCold_.data() + first, count, states_.data(),
                                                                     bounceSupports_.data(), solveParams_))
                noteBounce();
            return true;
        case StageKind::StoreImpulses:
            storePlanarImpulses(planar_.data() + begin, planarCold_.data() + begin, count);
            return true;
        default: return false;  // body and joint stages are shared with 3D worlds
    }
}

void StepSolver::runOnMain(int stage) {
    const StagePlan& p = plan_[static_cast<std::size_t>(stage)];
    if (p.kind == StageKind::ForceCallback) applyForceCallback(p.substep);
}

void StepSolver::finalizeBodies(int begin, int end) {
    auto& worldBodies = world_->bodies();
    for (int i = begin; i < end; ++i) {
        const SolverBody& sb = bodies_[i];
        const SolverState& s = states_[i];
        BodyState& state = worldBodies[sb.body].state;
        state.position = sb.position0 + Vec3(s.dp[0], s.dp[1], s.dp[2]);
        state.orientation = (Quat(s.dq[0], s.dq[1], s.dq[2], s.dq[3]) * sb.orientation0).normalized();
        state.linearVelocity = Vec3(s.v[0], s.v[1], s.v[2]);
        state.angularVelocity = Vec3(s.w[0], s.w[1], s.w[2]);
    }
}

void StepSolver::applyForceCallback(int substep) {
    // The callback reads the bodies' current states: bring them up to date first.
    finalizeBodies(0, static_cast<int>(bodies_.size()));
    world_->evaluateForceHook(step_.time + substep * h_);
    const Effects effects = world_->effects();
    const Vec3 gravity = effects.has(Effect::Gravity) ? world_->settings().gravity : Vec3::Zero();
    for (SolverBody& sb : bodies_) {
        if (!sb.dynamic) continue;
        const NativeBody& nb = world_->bodies()[sb.body];
        sb.linearAcceleration = nb.gravityScale * gravity + sb.invMass.cwiseProduct(nb.force + world_->hookForce(sb.body));
        sb.angularAcceleration = sb.invInertia * (nb.torque + world_->hookTorque(sb.body));
    }
}

}  // namespace anyphys::native
