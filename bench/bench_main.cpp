#include "bench_main.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "instruction_count.hpp"

namespace anyphys::bench {
namespace {

bool gQuick = false;

}  // namespace

bool quick() { return gQuick; }

RunPlan tableRun(const ScenePlan& plan) {
    const int steps = gQuick ? std::max(30, plan.steps / 5) : plan.steps;
    return {0, steps, std::min(60, steps / 2)};
}

RunPlan scalingRun() { return gQuick ? RunPlan{10, 10, 5} : RunPlan{30, 30, 15}; }

// Under callgrind a run's instruction count is the same every time: one round says it all.
int comparisonRounds() { return gQuick || underValgrind() ? 1 : 3; }

void report(benchmark::State& state, const RunResult& r, const std::string& label) {
    state.SetIterationTime(r.wallMs / 1e3);
    auto& c = state.counters;
    c["bodies"] = r.bodies;
    c["steps"] = r.steps;
    c["wall_ms"] = r.wallMs;
    c["wall_median_ms"] = r.wallMedianMs;
    c["wall_late_ms"] = r.wallLateMs;
    c["cpu_ms"] = r.cpuMs;
    c["cpu_us_per_body"] = 1e3 * r.cpuMs / r.bodies;
    c["wall_us_per_body"] = 1e3 * r.wallMs / r.bodies;
    c["allocs_per_step"] = r.allocsPerStep;
    c["alloc_window"] = r.allocWindow;
    c["penetration_mm"] = 1e3 * r.outcome.penetration;
    c["ground_penetration_mm"] = 1e3 * r.outcome.groundPenetration;
    c["max_speed"] = r.outcome.maxSpeed;
    c["max_move_m"] = r.outcome.maxMove;
    c["moved"] = r.outcome.moved;
    c["nonfinite"] = r.outcome.nonFinite;
    c["settled"] = r.outcome.settled ? 1 : 0;
    state.SetLabel(label);
}

int benchMain(int argc, char** argv, void (*registerAll)()) {
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0)
            gQuick = true;
        else
            args.push_back(argv[i]);
    }
    int count = static_cast<int>(args.size());
    benchmark::Initialize(&count, args.data());
    if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;
    registerAll();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

}  // namespace anyphys::bench
