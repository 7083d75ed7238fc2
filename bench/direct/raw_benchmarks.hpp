#pragma once
// Registration shared by the raw-engine programs (ode_scenes.cpp, bullet_scenes.cpp,
// box2d_scenes.cpp):
//   raw/<scene>/<engine>        the scene written directly against the engine, one run, with the
//                               same counters as the anyphys rows (bench_main.cpp's report())
//   overhead/<scene>/<engine>   anyphys on backend <engine> (effects derived, so events on: the
//                               touching pairs tracked, no one reading the events), the same with
//                               a listener reading every event, that listener without impulses,
//                               and the raw version, in turn, comparisonRounds() times each, in
//                               this one process; the fastest run of each counts (the least
//                               disturbed on a shared machine). Counters:
//                               anyphys_cpu_ms, raw_cpu_ms and overhead_pct = 100 (anyphys / raw -
//                               1), CPU time per step; the same in wall time; listening_cpu_ms and
//                               listening_overhead_pct, with listening_events_per_step;
//                               points_cpu_ms and points_overhead_pct, the listener with
//                               settings.contactImpulses false (events without impulses); each
//                               side's penetration and settled, to show they simulate the same thing.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "../simulation.hpp"

namespace anyphys::bench {

using RawFactory = std::function<std::unique_ptr<Simulation>(const ScenePlan&)>;

struct RawEngine {
    std::string name;                          ///< the anyphys backend driving the same engine
    std::vector<std::string> scenes;           ///< raw/ rows
    std::vector<std::string> overheadScenes;   ///< overhead/ comparisons
    RawFactory make;
};

void registerRaw(const RawEngine& engine);

}  // namespace anyphys::bench
