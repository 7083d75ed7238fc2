#pragma once
// What every benchmark program shares: the run lengths (full or --quick) and main().
#include <benchmark/benchmark.h>

#include <string>

#include "measure.hpp"

namespace anyphys::bench {

/// True when the program was started with --quick (a fifth of each scene's steps, shorter
/// windows, one overhead round): a check that the instruments work, not a measurement.
bool quick();

/// A scene run as reported in the main table: the scene's steps, allocations counted over the
/// last 60 of them (after the warm-up the rest of the run provides).
RunPlan tableRun(const ScenePlan& plan);

/// The per-body cost series: 30 untimed steps (the layers fall and land), then 30 timed steps of
/// the pile.
RunPlan scalingRun();

/// Rounds of every side-by-side comparison (anyphys against the raw engine, 2 workers against 1,
/// effects on against off): the two alternate, and the fastest run of each counts.
int comparisonRounds();

/// Sets the manual time (wall seconds per step) and the counters of one run.
void report(benchmark::State& state, const RunResult& result, const std::string& label);

/// Strips --quick, runs registerAll() and the benchmarks Google Benchmark's flags select.
int benchMain(int argc, char** argv, void (*registerAll)());

}  // namespace anyphys::bench
