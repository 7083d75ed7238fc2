// The default task system's cost per parallel section (anyphys/thread_pool.hpp).
//   pool/parallel_for/<workers>/<serial us>: one parallelFor over 4 096 items (about 0.2 ms of
//     arithmetic on one core), after `serial us` of work on the calling thread alone, as a step
//     alternates its serial parts and its parallel sections. 1 worker runs everything on the
//     calling thread; 2 workers pay, on top of half the section, what it takes to get the other
//     thread going and to learn that it is done. The ratio of the two rows of one serial length
//     is the speed-up a section of that size can reach.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "anyphys/thread_pool.hpp"

namespace anyphys {
namespace {

constexpr int kItems = 4096;
constexpr int kMinRange = 256;

/// Keeps the calling thread busy for `us` microseconds, as a step's serial part would.
void serialWork(double us) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double, std::micro>(us);
    while (std::chrono::steady_clock::now() < until) {
    }
}

void parallelSection(benchmark::State& state) {
    const int workers = static_cast<int>(state.range(0));
    const double serialUs = static_cast<double>(state.range(1));
    ThreadPool pool(workers);
    std::vector<double> data(kItems, 1.0);
    const auto section = [&](int begin, int end, int) {
        for (int i = begin; i < end; ++i) {
            double x = data[static_cast<std::size_t>(i)];
            for (int k = 0; k < 20; ++k) x = std::sqrt(x + k);
            data[static_cast<std::size_t>(i)] = x;
        }
    };
    for (auto _ : state) {
        serialWork(serialUs);
        parallelFor(&pool, kItems, kMinRange, section);
    }
    benchmark::DoNotOptimize(data.data());
}

BENCHMARK(parallelSection)
    ->Name("pool/parallel_for")
    ->ArgsProduct({{1, 2}, {0, 10, 50}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace anyphys

BENCHMARK_MAIN();
