#pragma once
// The special-effect tables (anyphys_bench_effects, effects_cost.cpp), medians over the program's
// repetitions where it ran with --benchmark_repetitions.
#include <ostream>

#include "results.hpp"

namespace anyphys::bench::report {

/// The pile with no special effect: World::step against its bare backend peer.
void printNoEffects(const Results& results, std::ostream& out);
/// Each effect's cost per step on each backend.
void printEffectCosts(const Results& results, std::ostream& out);

}  // namespace anyphys::bench::report
