#include "raw_benchmarks.hpp"

#include <algorithm>
#include <limits>

#include "../bench_main.hpp"
#include "../instruction_count.hpp"
#include "../layer_simulation.hpp"

namespace anyphys::bench {
namespace {

void rawRow(benchmark::State& state, const std::string& scene, const RawFactory& make) {
    const ScenePlan plan = makeScene(scene);
    for (auto _ : state) {
        const std::unique_ptr<Simulation> simulation = make(plan);
        const RunResult result = measure(*simulation, plan, tableRun(plan));
        report(state, result, simulation->describe());
    }
}

struct Best {
    double cpuMs = std::numeric_limits<double>::infinity();
    double wallMs = std::numeric_limits<double>::infinity();
    RunResult last;

    void add(const RunResult& r) {
        cpuMs = std::min(cpuMs, r.cpuMs);
        wallMs = std::min(wallMs, r.wallMs);
        last = r;
    }
};

// Under callgrind (scripts/overhead_instructions.sh) a counted step is a hundred times slower:
// the first four fifths of the run go uncounted and uninstrumented, and the last fifth, where the
// pile has landed and its contacts persist, is counted. Otherwise the whole run is timed.
RunPlan overheadRun(const ScenePlan& plan) {
    RunPlan run = tableRun(plan);
    if (!underValgrind()) return run;
    run.warmupSteps = run.steps - std::max(run.steps / 5, 1);
    run.steps -= run.warmupSteps;
    run.allocWindow = std::min(run.allocWindow, run.steps);
    return run;
}

void overhead(benchmark::State& state, const std::string& scene, const std::string& backend, const RawFactory& make) {
    const ScenePlan plan = makeScene(scene);
    const RunPlan run = overheadRun(plan);
    const int rounds = comparisonRounds();
    const std::string row = "overhead/" + scene + "/" + backend;
    for (auto _ : state) {
        Best layer, listening, pointsOnly, raw;
        std::string described;
        std::size_t eventsPerStep = 0;
        constexpr int kSides = 4;
        for (int round = 0; round < rounds; ++round) {
            // Rotate which goes first, so none always meets a warm or a cold cache.
            for (int k = 0; k < kSides; ++k) {
                switch ((k + round) % kSides) {
                    case 0: {
                        LayerSimulation simulation(plan, backend);
                        layer.add(measure(simulation, plan, run));
                        dumpInstructionCount(row + " anyphys");
                        break;
                    }
                    case 1: {
                        LayerSimulation simulation(plan, backend, 1, Listening::Everything);
                        listening.add(measure(simulation, plan, run));
                        eventsPerStep = simulation.events().events / static_cast<std::size_t>(run.steps);
                        dumpInstructionCount(row + " listening");
                        break;
                    }
                    case 2: {
                        LayerSimulation simulation(plan, backend, 1, Listening::WithoutImpulses);
                        pointsOnly.add(measure(simulation, plan, run));
                        dumpInstructionCount(row + " points");
                        break;
                    }
                    default: {
                        const std::unique_ptr<Simulation> simulation = make(plan);
                        raw.add(measure(*simulation, plan, run));
                        described = simulation->describe();
                        dumpInstructionCount(row + " raw");
                    }
                }
            }
        }
        state.SetIterationTime(layer.wallMs / 1e3);
        auto& c = state.counters;
        c["rounds"] = rounds;
        c["steps"] = run.steps;
        c["bodies"] = plan.count();
        c["anyphys_cpu_ms"] = layer.cpuMs;
        c["raw_cpu_ms"] = raw.cpuMs;
        c["overhead_pct"] = 100.0 * (layer.cpuMs / raw.cpuMs - 1.0);
        c["anyphys_wall_ms"] = layer.wallMs;
        c["raw_wall_ms"] = raw.wallMs;
        c["overhead_wall_pct"] = 100.0 * (layer.wallMs / raw.wallMs - 1.0);
        c["listening_cpu_ms"] = listening.cpuMs;
        c["listening_overhead_pct"] = 100.0 * (listening.cpuMs / raw.cpuMs - 1.0);
        c["listening_events_per_step"] = static_cast<double>(eventsPerStep);
        c["points_cpu_ms"] = pointsOnly.cpuMs;
        c["points_overhead_pct"] = 100.0 * (pointsOnly.cpuMs / raw.cpuMs - 1.0);
        c["anyphys_penetration_mm"] = 1e3 * layer.last.outcome.penetration;
        c["raw_penetration_mm"] = 1e3 * raw.last.outcome.penetration;
        c["anyphys_settled"] = layer.last.outcome.settled ? 1 : 0;
        c["raw_settled"] = raw.last.outcome.settled ? 1 : 0;
        c["anyphys_allocs_per_step"] = layer.last.allocsPerStep;
        c["raw_allocs_per_step"] = raw.last.allocsPerStep;
        state.SetLabel(described + ", best of " + std::to_string(rounds));
    }
}

}  // namespace

void registerRaw(const RawEngine& engine) {
    for (const std::string& scene : engine.scenes)
        benchmark::RegisterBenchmark(("raw/" + scene + "/" + engine.name).c_str(),
                                     [scene, make = engine.make](benchmark::State& s) { rawRow(s, scene, make); })
            ->UseManualTime()
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
    for (const std::string& scene : engine.overheadScenes)
        benchmark::RegisterBenchmark(
            ("overhead/" + scene + "/" + engine.name).c_str(),
            [scene, name = engine.name, make = engine.make](benchmark::State& s) { overhead(s, scene, name, make); })
            ->UseManualTime()
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
}

}  // namespace anyphys::bench
