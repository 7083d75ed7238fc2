// The default task system: every item runs exactly once, ranges that run at the same time have
// different worker indices, and a pool of one runs everything on the calling thread.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "anyphys/thread_pool.hpp"
#include "anyphys/world.hpp"

namespace anyphys {
namespace {

TEST(ThreadPoolTest, EveryItemRunsOnceWithDistinctConcurrentWorkers) {
    for (int workers : {1, 2, 4}) {
        ThreadPool pool(workers);
        ASSERT_EQ(pool.workerCount(), workers);
        constexpr int kItems = 10000;
        std::vector<std::atomic<int>> runs(kItems);
        std::vector<std::atomic<int>> busy(static_cast<std::size_t>(workers));  // ranges running per worker
        std::atomic<bool> overlapped{false};
        auto body = [&](int begin, int end, int worker) {
            ASSERT_GE(worker, 0);
            ASSERT_LT(worker, workers);
            if (busy[static_cast<std::size_t>(worker)].fetch_add(1) != 0) overlapped = true;
            for (int i = begin; i < end; ++i) runs[static_cast<std::size_t>(i)].fetch_add(1);
            std::this_thread::yield();  // let other workers run at the same time
            busy[static_cast<std::size_t>(worker)].fetch_sub(1);
        };
        for (int repeat = 0; repeat < 20; ++repeat) parallelFor(&pool, kItems, 16, body);
        for (int i = 0; i < kItems; ++i) ASSERT_EQ(runs[static_cast<std::size_t>(i)].load(), 20) << "item " << i;
        EXPECT_FALSE(overlapped) << "two ranges ran on one worker index at the same time (" << workers << " workers)";
    }
}

TEST(ThreadPoolTest, SingleWorkerRunsOnTheCallingThread) {
    ThreadPool pool(1);
    const std::thread::id caller = std::this_thread::get_id();
    bool sameThread = true;
    auto body = [&](int, int, int worker) { sameThread = sameThread && worker == 0 && std::this_thread::get_id() == caller; };
    parallelFor(&pool, 100, 1, body);
    EXPECT_TRUE(sameThread);
}

TEST(ThreadPoolTest, WorkerCountIsValidated) {
    WorldSettings s;
    s.workers = 0;
    try {
        World world(s);
        FAIL() << "workers = 0 was accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "WorldSettings.workers: must be in [1, 256], got 0");
    }
}

}  // namespace
}  // namespace anyphys
