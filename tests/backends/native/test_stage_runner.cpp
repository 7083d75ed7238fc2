// StageRunner (solver/stage_runner.hpp): every block of every stage runs exactly once, a stage's
// blocks only after every block of the stage before, and main-only stages on the calling thread,
// whatever the workers and however late a task system starts them.
#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "anyphys/thread_pool.hpp"
#include "late_reverse_tasks.hpp"
#include "solver/stage_runner.hpp"

namespace anyphys::native {
namespace {

/// Counts each block's runs and notes every order the runner must keep that it broke.
class RecordingWork final : public StageRunner::Work {
public:
    explicit RecordingWork(const std::vector<StageRunner::Stage>& stages)
        : stages_(stages), done_(stages.size()), first_(stages.size() + 1, 0) {
        for (std::size_t s = 0; s < stages.size(); ++s) first_[s + 1] = first_[s] + stages[s].blocks;
        runs_ = std::make_unique<std::atomic<int>[]>(static_cast<std::size_t>(first_.back()));
    }

    void runBlock(int stage, int block, int worker) override {
        if (stages_[static_cast<std::size_t>(stage)].mainOnly) ++wrongPlace_;
        if (worker < 0) ++wrongPlace_;
        noteOrder(stage);
        runs_[static_cast<std::size_t>(first_[static_cast<std::size_t>(stage)] + block)].fetch_add(1);
        done_[static_cast<std::size_t>(stage)].fetch_add(1, std::memory_order_release);
    }

    void runOnMain(int stage) override {
        if (!stages_[static_cast<std::size_t>(stage)].mainOnly || std::this_thread::get_id() != caller_) ++wrongPlace_;
        noteOrder(stage);
        ++mainRuns_;
        done_[static_cast<std::size_t>(stage)].store(stages_[static_cast<std::size_t>(stage)].blocks,
                                                     std::memory_order_release);
    }

    int runsOf(int stage, int block) const {
        return runs_[static_cast<std::size_t>(first_[static_cast<std::size_t>(stage)] + block)].load();
    }
    int outOfOrder() const { return outOfOrder_.load(); }
    int wrongPlace() const { return wrongPlace_.load(); }
    int mainRuns() const { return mainRuns_; }

private:
    /// Stage `stage` may start only once every block of the stage before is done.
    void noteOrder(int stage) {
        if (stage == 0) return;
        const auto before = static_cast<std::size_t>(stage - 1);
        if (done_[before].load(std::memory_order_acquire) != stages_[before].blocks) ++outOfOrder_;
    }

    const std::vector<StageRunner::Stage>& stages_;
    std::vector<std::atomic<int>> done_;  // blocks finished, per stage
    std::vector<int> first_;               // each stage's first block in runs_
    std::unique_ptr<std::atomic<int>[]> runs_;
    std::atomic<int> outOfOrder_{0};
    std::atomic<int> wrongPlace_{0};
    int mainRuns_ = 0;  // main thread only
    std::thread::id caller_ = std::this_thread::get_id();
};

/// Stages of 0 to 12 blocks, one of them main-only (a force callback's place in a substep).
std::vector<StageRunner::Stage> mixedStages() {
    std::vector<StageRunner::Stage> stages;
    for (int s = 0; s < 60; ++s) stages.push_back({(s * 7) % 13, s == 17});
    return stages;
}

void expectEveryBlockOnceInOrder(TaskSystem* tasks, const std::string& what) {
    const std::vector<StageRunner::Stage> stages = mixedStages();
    StageRunner runner;
    for (int round = 0; round < 20; ++round) {  // the runner's buffers are reused from run to run
        RecordingWork work(stages);
        runner.run(tasks, stages, work);
        for (int s = 0; s < static_cast<int>(stages.size()); ++s)
            for (int b = 0; b < stages[static_cast<std::size_t>(s)].blocks; ++b)
                ASSERT_EQ(work.runsOf(s, b), stages[static_cast<std::size_t>(s)].mainOnly ? 0 : 1)
                    << what << ", round " << round << ": stage " << s << " block " << b;
        EXPECT_EQ(work.mainRuns(), 1) << what;
        EXPECT_EQ(work.outOfOrder(), 0) << what << ": a stage started before the one before it was done";
        EXPECT_EQ(work.wrongPlace(), 0) << what << ": a main-only stage ran elsewhere, or a block of it ran";
    }
}

TEST(StageRunner, EveryBlockRunsOnceAfterTheStageBefore) {
    expectEveryBlockOnceInOrder(nullptr, "no task system");
    for (int workers : {1, 2, 3, 4}) {
        ThreadPool pool(workers);
        expectEveryBlockOnceInOrder(&pool, std::to_string(workers) + " workers");
    }
}

TEST(StageRunner, HelpersThatStartAfterTheWorkIsDoneFindNothingLeft) {
    for (int workers : {2, 4}) {
        anyphys::test::LateReverseTasks tasks(workers);  // not native::test, which a unity batch may hold
        expectEveryBlockOnceInOrder(&tasks, std::to_string(workers) + " late helpers");
    }
}

}  // namespace
}  // namespace anyphys::native
