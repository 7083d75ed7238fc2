#pragma once
// One timed run of a simulation: wall and CPU time per step, allocations in the last steps, and
// the outcome of the scene.
#include "simulation.hpp"

namespace anyphys::bench {

struct RunPlan {
    int warmupSteps = 0;   ///< untimed steps first (the per-body cost series skips the fall)
    int steps = 0;         ///< timed steps
    int allocWindow = 0;   ///< allocations are counted over the last this many timed steps
};

struct RunResult {
    int bodies = 0;
    int steps = 0;
    double wallMs = 0.0;        ///< mean wall time per step
    double wallMedianMs = 0.0;  ///< median wall time per step
    double wallLateMs = 0.0;    ///< mean wall time per step over the second half
    double cpuMs = 0.0;         ///< process CPU time per step (every thread of the process)
    double allocsPerStep = -1;  ///< heap allocations per step over the window; -1 when not counted
    int allocWindow = 0;
    Outcome outcome;
};

RunResult measure(Simulation& simulation, const ScenePlan& plan, const RunPlan& run);

}  // namespace anyphys::bench
