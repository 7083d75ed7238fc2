#include "measure.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>

#include "alloc_counter.hpp"
#include "instruction_count.hpp"

namespace anyphys::bench {
namespace {

double wallMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> values) {
    const std::size_t n = values.size();
    std::sort(values.begin(), values.end());
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

RunResult measure(Simulation& simulation, const ScenePlan& plan, const RunPlan& run) {
    for (int i = 0; i < run.warmupSteps; ++i) simulation.step();
    const int steps = std::max(run.steps, 1);
    const int windowStart = steps - std::clamp(run.allocWindow, 1, steps);
    std::vector<double> stepMs(static_cast<std::size_t>(steps));  // allocated before the window opens
    std::uint64_t allocsAtWindow = 0;
    const double cpuStart = processCpuMs();
    startCountingInstructions();
    for (int i = 0; i < steps; ++i) {
        if (i == windowStart) allocsAtWindow = heapAllocations();
        const double t0 = wallMs();
        simulation.step();
        stepMs[static_cast<std::size_t>(i)] = wallMs() - t0;
    }
    stopCountingInstructions();
    const std::uint64_t allocsAtEnd = heapAllocations();
    const double cpuMs = processCpuMs() - cpuStart;

    RunResult r;
    r.bodies = plan.count();
    r.steps = steps;
    r.allocWindow = steps - windowStart;
    double total = 0.0, late = 0.0;
    for (int i = 0; i < steps; ++i) {
        total += stepMs[static_cast<std::size_t>(i)];
        if (i >= steps / 2) late += stepMs[static_cast<std::size_t>(i)];
    }
    r.wallMs = total / steps;
    r.wallLateMs = late / (steps - steps / 2);
    r.wallMedianMs = median(stepMs);
    r.cpuMs = cpuMs / steps;
    if (countingAllocations())
        r.allocsPerStep = static_cast<double>(allocsAtEnd - allocsAtWindow) / r.allocWindow;
    std::vector<BoxState> boxes;
    simulation.readBoxes(boxes);
    r.outcome = assess(plan, boxes);
    return r;
}

}  // namespace anyphys::bench
