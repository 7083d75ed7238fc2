#pragma once
// The native constraint solver: moves the bodies that have constraints this step. Two methods,
// selected by WorldSettings::solver, share one set of staged functions over arrays:
//  - soft step (default, after Box2D v3): per substep integrate velocities, warm start, solve
//    soft contacts with bias, integrate positions, relax without bias;
//  - projected Gauss-Seidel: per substep integrate velocities, warm start, solve (contacts with
//    Baumgarte bias, joints without), integrate positions, correct the joints' positions.
//  Joints run before the contacts in each pass (warm_start_joints, solve_joints, relax_joints).
// Both then apply restitution and store the impulses for the next step's warm start.
//
// The stages of a step, in order (each a range function over arrays, run by StageRunner):
//   prepare_contacts                      once: anchors, masses, warm-start impulses
//   [force_callback]                      each substep, when the user set one (main thread)
//   integrate_velocities                  each substep
//   warm_start  (per colour)              each substep
//   solve       (per colour)              each substep, `iterations` passes
//   integrate_positions                   each substep
//   correct_joints                        each substep, `iterations` passes (PGS with joints only)
//   relax       (per colour)              each substep, backend option relaxIterations passes
//                                         (default `iterations` on soft step, none on PGS)
//   restitution (per colour)              kRestitutionRounds rounds, when some material bounces
//   store_impulses                        once
//   finalize_bodies                       once: poses and velocities back to the bodies
// Constraints are coloured (ConstraintGraph) and grouped eight to a WideContact (a PlanarContact in
// a planar world: 3 degrees of freedom per body), so the colour stages run in SIMD lanes and on
// several workers with identical results.
#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

#include "large_pages.hpp"
#include "pipeline.hpp"
#include "solver/constraint_graph.hpp"
#include "solver/contact_constraint.hpp"
#include "solver/joint_solver.hpp"
#include "solver/planar_contact.hpp"
#include "solver/solver_body.hpp"
#include "solver/stage_runner.hpp"

namespace anyphys::native {

class NativeWorld;
struct NativeBody;

class StepSolver final : private StageRunner::Work {
public:
    /// Gathers this step's constraints (manifolds with points of non-trigger contacts with an
    /// awake dynamic body) in contact order, numbers the awake bodies they move in world order and
    /// marks them `constrained` so the free-body integrator leaves them to the solver.
    void collect(NativeWorld& world);
    /// No constraints this step (nothing awake).
    void clear();
    bool empty() const { return lanes_.empty() && jointList_.empty(); }
    /// Advances the constrained bodies over the whole step.
    void solve(NativeWorld& world, const StepInfo& step);

    /// Stage names of the last solve, in order (tests, docs).
    std::vector<const char*> lastStageNames() const;

private:
    enum class StageKind : std::uint8_t {
        PrepareContacts,
        ForceCallback,
        IntegrateVelocities,
        WarmStartJoints,
        WarmStart,
        SolveJoints,
        Solve,
        IntegratePositions,
        CorrectJoints,
        RelaxJoints,
        Relax,
        Restitution,
        RestitutionJoints,
        StoreImpulses,
        ReportJoints,
        FinalizeBodies,
    };
    struct StagePlan {
        StageKind kind;
        int color = 0;      // colour stages
        int substep = 0;    // or the restitution stage's round
        bool endOfSubstep = false;  // the last pass of a substep (its impulses count for events)
        int items = 0;      // bodies, or wide constraints
        int blockSize = 1;
    };

    void buildBodies(NativeWorld& world, const StepInfo& step);
    /// One solver body and its state from world body `index`.
    void buildBody(std::uint32_t index, const NativeBody& nb, SolverBody& sb, SolverState& s, const Vec3& gravity,
                   bool userForces, bool damping, bool gyroscopic) const;
    void buildConstraints();
    void planStages(const NativeWorld& world);
    void addStage(StageKind kind, int items, int color = 0, int substep = 0, bool endOfSubstep = false);

    void runBlock(int stage, int block, int worker) override;
    void runOnMain(int stage) override;
    /// The contact stages of a planar world; false for the stages it shares with 3D worlds.
    bool runPlanarBlock(const StagePlan& p, int first, int begin, int end);
    /// The contact lanes that wide constraint `w` packs, copied into `lanes`; returns their count.
    int gatherLanes(int w, ContactLane (&lanes)[wide::kLanes]) const;
    /// Asks for what preparing WideContact w will read: its lanes' manifolds and solver bodies.
    void prefetchPrepare(int w) const;
    /// Writes solver poses and velocities back to the world's bodies.
    void finalizeBodies(int begin, int end);
    /// Fills each joint's springsOnBusierBody.
    void countSpringsPerBody();
    /// Solver-body forces from the user's callback at the current states.
    void applyForceCallback(int substep);

    // Per step, reused (no allocation once sizes are stable).
    LargeVector<ContactLane> lanes_;          // by contact order; bodies are world indices until solve
    std::vector<std::uint32_t> jointList_;    // joint slots with an awake dynamic body, in slot order
    std::vector<JointConstraint> joints_;
    std::vector<std::uint16_t> springsPerBody_;  // per solver body: sprung joints on it (buildConstraints)
    std::vector<std::uint32_t> bodyOrder_;    // world index of each solver body
    std::vector<std::int32_t> solverIndex_;   // per world body: solver index or kStaticBody
    LargeVector<SolverBody> bodies_;
    LargeVector<SolverState> states_;
    std::vector<Vec3> bounceSupports_;        // per solver body: the restitution stage's shock propagation
    ConstraintGraph graph_;
    LargeVector<WideContact> wide_;       // 3D worlds
    LargeVector<WideContactCold> wideCold_;  // beside wide_: what only prepare, restitution and store read
    LargeVector<WideWarmStart> wideWarm_;    // beside wide_: the impulses as velocity changes, for the warm start
    LargeVector<PlanarContact> planar_;   // planar worlds: the same constraints with 3 degrees of freedom
    LargeVector<PlanarContactCold> planarCold_;  // beside planar_
    LargeVector<PlanarWarmStart> planarWarm_;    // beside planar_: as wideWarm_
    int wideCount_ = 0;                   // of whichever is in use
    bool planarWorld_ = false;
    struct WideSource {
        int first = 0;  // into graph_.lanes()
        int count = 0;  // lanes used (1 to 4)
    };
    std::vector<WideSource> wideSource_;
    std::vector<int> colorFirstWide_, colorWideCount_;
    std::vector<StagePlan> plan_;
    std::vector<StageRunner::Stage> stages_;
    StageRunner runner_;
    int workers_ = 1;

    // What the current solve works with.
    NativeWorld* world_ = nullptr;
    StepInfo step_;
    double h_ = 0.0;
    ContactPrepareParams prepareParams_;
    ContactSolveParams solveParams_;
    JointSolveParams jointParams_;
    bool restitution_ = false;
    // The joints' accumulated impulses as the relax passes left them, kept while the restitution
    // stage's joint passes add the bounce's share, and put back after it (restoreJointImpulses).
    std::vector<std::array<double, kRowCount>> jointImpulsesBeforeBounce_;
    bool jointsInBounce_ = false;  // a restitution joint pass ran this step
    void solveJointsInBounce(const StagePlan& p);
    void restoreJointImpulses();
    /// Some row of the restitution stage's first round bounced or held. When none did, no body was
    /// marked in a bounce and the later rounds would find nothing either: they are skipped, so a
    /// world whose materials bounce pays one round while nothing does. Written by any worker in
    /// the first round, read after it (the stages' barrier orders them).
    std::atomic<bool> bounceFound_{false};
    void noteBounce() { bounceFound_.store(true, std::memory_order_relaxed); }
    bool skipRestitutionRound(const StagePlan& p) const {
        return p.substep > 0 && !bounceFound_.load(std::memory_order_relaxed);
    }
};

}  // namespace anyphys::native
