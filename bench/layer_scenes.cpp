// The benchmark scenes through anyphys on every backend, one process, Google Benchmark names:
//   scene/<scene>/<backend>         the main table: each scene of tableScenes() for its full steps
//   workers/<scene>/<backend>/2     drop10000 and pyramid3d with WorldSettings::workers = 2 against
//                                   1, alternating, comparisonRounds() runs each, the fastest of
//                                   each counting (counters speedup, one_worker_wall_ms); skipped,
//                                   with the reason, on backends that do not list "settings.workers"
//   scaling/<scene>/<backend>       the per-body cost series (drop1000, drop10000, drop50000):
//                                   30 steps of falling untimed, then 30 timed steps of the pile;
//                                   comparisonRounds() runs, the one of least CPU time counting
// Time = wall ms per step; the counters are listed in bench_main.cpp's report() and explained in
// docs/benchmarks.md. A backend that cannot run a scene is skipped with the reason.
#include <utility>
#include <functional>
#include <limits>
#include <string>

#include "bench_main.hpp"
#include "layer_simulation.hpp"

namespace anyphys::bench {
namespace {

/// Of identical runs offered in turn, the one of least `time` (CPU or wall ms per step): the
/// least disturbed by other load on a shared machine.
struct FastestRun {
    double RunResult::*time;
    RunResult run;
    std::string described;

    explicit FastestRun(double RunResult::*key) : time(key) { run.*time = std::numeric_limits<double>::infinity(); }
    void offer(const RunResult& r, const LayerSimulation& simulation) {
        if (r.*time >= run.*time) return;
        run = r;
        described = simulation.describe();
    }
};

void runScene(benchmark::State& state, const std::string& scene, const BackendInfo& backend, int workers,
              bool scaling) {
    const ScenePlan plan = makeScene(scene);
    if (const std::string reason = cannotRun(plan, backend, workers); !reason.empty()) {
        state.SkipWithError(("n/a: " + reason).c_str());
        return;
    }
    // A scaling row times 30 steps: 75 ms at 1 000 bodies, which a moment of other load on this
    // machine visibly inflates. Its runs are identical, so the least CPU time of a few is the cost.
    const int rounds = scaling ? comparisonRounds() : 1;
    for (auto _ : state) {
        FastestRun fastest(&RunResult::cpuMs);
        for (int round = 0; round < rounds; ++round) {
            LayerSimulation simulation(plan, backend.name, workers);
            fastest.offer(measure(simulation, plan, scaling ? scalingRun() : tableRun(plan)), simulation);
        }
        const std::string& described = fastest.described;
        report(state, fastest.run, rounds > 1 ? described + ", best of " + std::to_string(rounds) : described);
        state.counters["rounds"] = rounds;
    }
}

// This machine's speed drifts by a quarter over minutes: one 1-worker run and one 2-worker run
// minutes apart can give any verdict. Alternating them, and keeping each one's fastest run, gives
// the same answer run after run.
void runWorkers(benchmark::State& state, const std::string& scene, const BackendInfo& backend, int workers) {
    const ScenePlan plan = makeScene(scene);
    if (const std::string reason = cannotRun(plan, backend, workers); !reason.empty()) {
        state.SkipWithError(("n/a: " + reason).c_str());
        return;
    }
    const RunPlan run = tableRun(plan);
    const int rounds = comparisonRounds();
    for (auto _ : state) {
        FastestRun oneWorker(&RunResult::wallMs), moreWorkers(&RunResult::wallMs);
        for (int round = 0; round < rounds; ++round)
            for (const bool one : {round % 2 == 0, round % 2 != 0}) {  // which goes first alternates too
                LayerSimulation simulation(plan, backend.name, one ? 1 : workers);
                (one ? oneWorker : moreWorkers).offer(measure(simulation, plan, run), simulation);
            }
        report(state, moreWorkers.run, moreWorkers.described + ", best of " + std::to_string(rounds));
        state.counters["rounds"] = rounds;
        state.counters["one_worker_wall_ms"] = oneWorker.run.wallMs;
        state.counters["speedup"] = oneWorker.run.wallMs / moreWorkers.run.wallMs;
    }
}

void add(const std::string& name, std::function<void(benchmark::State&)> body) {
    benchmark::RegisterBenchmark(name.c_str(), std::move(body))
        ->UseManualTime()
        ->Iterations(1)  // one run of hundreds of steps is a sample in itself
        ->Unit(benchmark::kMillisecond);
}

void registerAll() {
    for (const BackendInfo& backend : availableBackends()) {
        for (const std::string& scene : tableScenes())
            add("scene/" + scene + "/" + backend.name, [=](benchmark::State& s) { runScene(s, scene, backend, 1, false); });
        for (const std::string scene : {"drop10000", "pyramid3d"})
            add("workers/" + scene + "/" + backend.name + "/2", [=](benchmark::State& s) { runWorkers(s, scene, backend, 2); });
        for (const std::string& scene : scalingScenes())
            add("scaling/" + scene + "/" + backend.name, [=](benchmark::State& s) { runScene(s, scene, backend, 1, true); });
    }
}

}  // namespace
}  // namespace anyphys::bench

int main(int argc, char** argv) { return anyphys::bench::benchMain(argc, argv, &anyphys::bench::registerAll); }
