#include "anyphys/thread_pool.hpp"

#include <algorithm>
#include <chrono>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace anyphys {

ThreadPool::ThreadPool(int workers) {
    for (int w = 1; w < std::max(workers, 1); ++w) threads_.emplace_back([this, w] { workerLoop(w); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    work_.notify_all();
    for (std::thread& t : threads_) t.join();
}

void* ThreadPool::enqueue(int count, int minRange, RangeFn fn, void* context) {
    if (count <= 0) return nullptr;
    if (threads_.empty()) {
        fn(0, count, 0, context);
        return nullptr;
    }
    // About four ranges per worker balance uneven ranges without much queue traffic.
    const int workers = workerCount();
    const int size = std::max({minRange, 1, (count + 4 * workers - 1) / (4 * workers)});
    {
        std::lock_guard lock(mutex_);
        if (freeTasks_.empty()) {
            tasks_.push_back(std::make_unique<Task>());
            freeTasks_.push_back(tasks_.back().get());
        }
        Task& task = *freeTasks_.back();
        freeTasks_.pop_back();
        task.fn = fn;
        task.context = context;
        for (int begin = 0; begin < count; begin += size) {
            queue_.push_back({&task, begin, std::min(count, begin + size)});
            ++task.pending;
        }
        changes_.fetch_add(1, std::memory_order_release);
        work_.notify_all();
        return &task;
    }
}

bool ThreadPool::runOne(std::unique_lock<std::mutex>& lock, int worker) {
    if (head_ == queue_.size()) return false;
    const Range range = queue_[head_++];
    if (head_ == queue_.size()) {  // drained: start over at the front, keeping the storage
        queue_.clear();
        head_ = 0;
    }
    lock.unlock();
    range.task->fn(range.begin, range.end, worker, range.task->context);
    lock.lock();
    changes_.fetch_add(1, std::memory_order_release);
    if (--range.task->pending == 0) done_.notify_all();
    return true;
}

void ThreadPool::spinForChange(std::unique_lock<std::mutex>& lock) {
    using Clock = std::chrono::steady_clock;
    const std::uint64_t seen = changes_.load(std::memory_order_relaxed);
    lock.unlock();
    const Clock::time_point until = Clock::now() + kSpinTime;
    for (unsigned spin = 1; changes_.load(std::memory_order_acquire) == seen; ++spin) {
#if defined(__x86_64__) || defined(__i386__)
        _mm_pause();
#endif
        if (spin % 64 == 0 && Clock::now() > until) break;  // a clock read costs more than a pause
    }
    lock.lock();
}

void ThreadPool::finish(void* handle) {
    if (!handle) return;
    Task& task = *static_cast<Task*>(handle);
    std::unique_lock lock(mutex_);
    // Help while waiting: the calling thread is worker 0.
    while (task.pending > 0) {
        if (runOne(lock, 0)) continue;
        spinForChange(lock);  // the last ranges are usually about to finish
        if (task.pending > 0 && head_ == queue_.size())
            done_.wait(lock, [&] { return task.pending == 0 || head_ < queue_.size(); });
    }
    freeTasks_.push_back(&task);
}

void ThreadPool::workerLoop(int worker) {
    std::unique_lock lock(mutex_);
    while (true) {
        if (!stopping_ && head_ == queue_.size()) spinForChange(lock);  // the step's next section is near
        work_.wait(lock, [&] { return stopping_ || head_ < queue_.size(); });
        if (stopping_) return;
        runOne(lock, worker);
    }
}

}  // namespace anyphys
