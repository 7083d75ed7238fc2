// The benchmark scenes through anyphys on every backend, one process, Google Benchmark names:
//   scene/<scene>/<backend>         the main table: each scene of tableScenes() for its full steps
//   workers/<scene>/<backend>/2     drop10000 and pyramid3d with WorldSettings::workers = 2 (the
//                                   1-worker run is the scene/ row); skipped, with the reason,
//                                   on backends that do not list "settings.workers"
//   scaling/<scene>/<backend>       the per-body cost series (drop1000, drop10000, drop50000):
//                                   30 steps of falling untimed, then 30 timed steps of the pile
// Time = wall ms per step; the counters are listed in bench_main.cpp's report() and explained in
// docs/benchmarks.md. A backend that cannot run a scene is skipped with the reason.
#include <string>

#include "bench_main.hpp"
#include "layer_simulation.hpp"

namespace anyphys::bench {
namespace {

void runScene(benchmark::State& state, const std::string& scene, const BackendInfo& backend, int workers,
              bool scaling) {
    const ScenePlan plan = makeScene(scene);
    if (const std::string reason = cannotRun(plan, backend, workers); !reason.empty()) {
        state.SkipWithError(("n/a: " + reason).c_str());
        return;
    }
    for (auto _ : state) {
        LayerSimulation simulation(plan, backend.name, workers);
        const RunResult result = measure(simulation, plan, scaling ? scalingRun() : tableRun(plan));
        report(state, result, simulation.describe());
    }
}

void add(const std::string& name, const std::string& scene, const BackendInfo& backend, int workers, bool scaling) {
    benchmark::RegisterBenchmark(name.c_str(),
                                 [=](benchmark::State& s) { runScene(s, scene, backend, workers, scaling); })
        ->UseManualTime()
        ->Iterations(1)  // one run of hundreds of steps is a sample in itself
        ->Unit(benchmark::kMillisecond);
}

void registerAll() {
    for (const BackendInfo& backend : availableBackends()) {
        for (const std::string& scene : tableScenes())
            add("scene/" + scene + "/" + backend.name, scene, backend, 1, false);
        for (const std::string scene : {"drop10000", "pyramid3d"})
            add("workers/" + scene + "/" + backend.name + "/2", scene, backend, 2, false);
        for (const std::string& scene : scalingScenes())
            add("scaling/" + scene + "/" + backend.name, scene, backend, 1, true);
    }
}

}  // namespace
}  // namespace anyphys::bench

int main(int argc, char** argv) { return anyphys::bench::benchMain(argc, argv, &anyphys::bench::registerAll); }
