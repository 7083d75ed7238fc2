#pragma once
// Runs a list of stages on the world's workers, one stage after another, each stage split into
// blocks that must not depend on one another (disjoint bodies, or disjoint constraints). This is
// the shape of Box2D v3's solver: one long task per worker instead of one task per stage, so a
// step of ~100 stages pays ~100 cheap syncs on atomics, not ~100 trips through a scheduler.
//
// The calling thread (worker 0) drives: it opens a stage, claims blocks like everyone else, and
// opens the next stage once every block is done. Helpers spin waiting for a stage, claim blocks
// until none is left, and wait for the next. Nothing ever waits for a helper that has not
// started: if the task system runs them late, or never in parallel, worker 0 does all the work
// and the late helpers find the run over. Every stage has its own counters, so a helper that
// falls behind can only find a stage with no blocks left, never claim a block of the wrong one.
#include <atomic>
#include <cstdint>
#include <vector>

#include "anyphys/task_system.hpp"

namespace anyphys::native {

class StageRunner {
public:
    /// The work: runs block `block` of stage `stage` on worker `worker`.
    class Work {
    public:
        virtual ~Work() = default;
        virtual void runBlock(int stage, int block, int worker) = 0;
        /// A stage with mainOnly set: run on the calling thread, whole (user callbacks).
        virtual void runOnMain(int stage) = 0;
    };

    struct Stage {
        int blocks = 0;         // independent pieces of work
        bool mainOnly = false;  // run by worker 0 alone (e.g. the user's force callback)
    };

    /// Runs every stage in order; returns when all are done. `tasks` null or with one worker:
    /// everything runs on the calling thread without atomics.
    void run(TaskSystem* tasks, const std::vector<Stage>& stages, Work& work);

private:
    struct Counters {
        std::atomic<int> completed{0};
        int firstBlock = 0;  // this stage's blocks in claims_
        Counters() = default;
        Counters(const Counters&) {}  // only resized while no worker runs
    };
    struct Claim {
        std::atomic<bool> taken{false};
        Claim() = default;
        Claim(const Claim&) {}  // only resized while no worker runs
    };

    static void helperMain(int begin, int end, int worker, void* context);
    void helperLoop(int worker);
    /// Claims and runs blocks of stage `index` until none is left. Worker k of n starts at block
    /// k * blocks / n and works forward, then takes what is left before its start backward:
    /// consecutive stages hand a worker the same slice of bodies and constraints, so their
    /// cache lines stay in its core's cache instead of moving between cores every stage.
    void claimBlocks(int index, int worker);

    const std::vector<Stage>* stages_ = nullptr;
    Work* work_ = nullptr;
    std::vector<Counters> counters_;
    std::vector<Claim> claims_;  // one per block of every stage
    std::atomic<int> openStage_{-1};   // the stage helpers may work on
    std::atomic<bool> finished_{false};
    int workers_ = 1;
};

}  // namespace anyphys::native
