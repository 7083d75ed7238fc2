#include "solver/stage_runner.hpp"

#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace anyphys::native {
namespace {

// Short waits spin (a stage lasts microseconds); long ones give the core away.
class Backoff {
public:
    void pause() {
        if (++spins_ < kSpins) {
#if defined(__x86_64__) || defined(__i386__)
            _mm_pause();
#endif
        } else {
            std::this_thread::yield();
        }
    }

private:
    static constexpr int kSpins = 2000;
    int spins_ = 0;
};

}  // namespace

void StageRunner::run(TaskSystem* tasks, const std::vector<Stage>& stages, Work& work) {
    const int workers = tasks ? tasks->workerCount() : 1;
    if (workers <= 1) {
        for (int s = 0; s < static_cast<int>(stages.size()); ++s) {
            if (stages[s].mainOnly) {
                work.runOnMain(s);
                continue;
            }
            for (int b = 0; b < stages[s].blocks; ++b) work.runBlock(s, b, 0);
        }
        return;
    }

    stages_ = &stages;
    work_ = &work;
    workers_ = workers;
    if (counters_.size() < stages.size()) counters_.resize(stages.size());
    int blocks = 0;
    for (std::size_t s = 0; s < stages.size(); ++s) {
        counters_[s].firstBlock = blocks;
        counters_[s].completed.store(0, std::memory_order_relaxed);
        blocks += stages[s].blocks;
    }
    if (claims_.size() < static_cast<std::size_t>(blocks)) claims_.resize(static_cast<std::size_t>(blocks));
    for (int b = 0; b < blocks; ++b) claims_[static_cast<std::size_t>(b)].taken.store(false, std::memory_order_relaxed);
    finished_.store(false, std::memory_order_relaxed);
    openStage_.store(-1, std::memory_order_release);

    void* handle = tasks->enqueue(workers - 1, 1, &StageRunner::helperMain, this);
    for (int s = 0; s < static_cast<int>(stages.size()); ++s) {
        if (stages[s].mainOnly) {
            work.runOnMain(s);
            continue;
        }
        openStage_.store(s, std::memory_order_release);
        claimBlocks(s, 0);
        Backoff backoff;
        while (counters_[s].completed.load(std::memory_order_acquire) < stages[s].blocks) backoff.pause();
    }
    finished_.store(true, std::memory_order_release);
    tasks->finish(handle);
}

void StageRunner::helperMain(int begin, int end, int worker, void* context) {
    (void)begin;
    (void)end;
    static_cast<StageRunner*>(context)->helperLoop(worker);
}

void StageRunner::helperLoop(int worker) {
    int last = -1;
    Backoff backoff;
    while (!finished_.load(std::memory_order_acquire)) {
        const int open = openStage_.load(std::memory_order_acquire);
        if (open == last) {
            backoff.pause();
            continue;
        }
        last = open;
        if (open >= 0) claimBlocks(open, worker);
        backoff = Backoff();
    }
}

void StageRunner::claimBlocks(int index, int worker) {
    Counters& c = counters_[static_cast<std::size_t>(index)];
    const int blocks = (*stages_)[static_cast<std::size_t>(index)].blocks;
    const auto tryRun = [&](int b) {
        Claim& claim = claims_[static_cast<std::size_t>(c.firstBlock + b)];
        // A relaxed look first: a block another worker took costs no write to its cache line.
        if (claim.taken.load(std::memory_order_relaxed) || claim.taken.exchange(true, std::memory_order_relaxed)) return;
        work_->runBlock(index, b, worker);
        c.completed.fetch_add(1, std::memory_order_release);
    };
    const int start = static_cast<int>(static_cast<long long>(worker) * blocks / workers_);
    for (int b = start; b < blocks; ++b) tryRun(b);
    for (int b = start - 1; b >= 0; --b) tryRun(b);
}

}  // namespace anyphys::native
