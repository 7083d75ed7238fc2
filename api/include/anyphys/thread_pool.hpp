#pragma once
// The default task system: a pool of threads that a world with WorldSettings::workers > 1
// creates for itself; a game may also create one and share it between worlds.
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "anyphys/task_system.hpp"

namespace anyphys {

/// `workers - 1` threads of its own plus the thread that calls finish (worker 0). Ranges are
/// queued in order and taken by whichever worker is free; idle threads sleep on a condition
/// variable, so an idle pool costs nothing.
class ThreadPool final : public TaskSystem {
public:
    /// workers >= 1; 1 runs everything on the calling thread.
    explicit ThreadPool(int workers);
    ~ThreadPool() override;
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int workerCount() const override { return static_cast<int>(threads_.size()) + 1; }
    void* enqueue(int count, int minRange, RangeFn fn, void* context) override;
    void finish(void* handle) override;

private:
    struct Task {
        RangeFn fn = nullptr;
        void* context = nullptr;
        int pending = 0;  // ranges not yet finished (guarded by mutex_)
    };
    struct Range {
        Task* task;
        int begin, end;
    };

    void workerLoop(int worker);
    /// Runs the oldest queued range on `worker` (unlocking while it runs); false when none is queued.
    bool runOne(std::unique_lock<std::mutex>& lock, int worker);

    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable work_;  // a range was queued, or the pool stops
    std::condition_variable done_;  // a range finished
    std::deque<Range> queue_;
    std::deque<Task> tasks_;        // stable addresses while in use; cleared when none is pending
    int unfinishedTasks_ = 0;
    bool stopping_ = false;
};

}  // namespace anyphys
