#pragma once
// The default task system: a pool of threads that a world with WorldSettings::workers > 1
// creates for itself; a game may also create one and share it between worlds.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "anyphys/task_system.hpp"

namespace anyphys {

/// `workers - 1` threads of its own plus the thread that calls finish (worker 0). Ranges are
/// queued in order and taken by whichever worker is free; idle threads spin briefly, then sleep
/// on a condition variable, so an idle pool costs nothing. Queue and task records are reused:
/// once warm, an enqueue allocates nothing. One thread at a time may enqueue and finish (the stepping thread).
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
    /// Unlocks and spins until a range is queued or finished, or kSpinTime has passed, then
    /// locks again. A step opens its parallel sections tens of microseconds apart, and waking a
    /// thread asleep on a condition variable takes about as long (bench/thread_pool.cpp).
    void spinForChange(std::unique_lock<std::mutex>& lock);
    static constexpr std::chrono::microseconds kSpinTime{50};

    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable work_;  // a range was queued, or the pool stops
    std::condition_variable done_;  // a range finished
    std::vector<Range> queue_;      // ranges not yet taken: [head_, end)
    std::size_t head_ = 0;
    std::vector<std::unique_ptr<Task>> tasks_;  // every task record made (stable addresses)
    std::vector<Task*> freeTasks_;              // records not in use
    bool stopping_ = false;
    std::atomic<std::uint64_t> changes_{0};  // ranges queued and finished so far (for spinForChange)
};

}  // namespace anyphys
