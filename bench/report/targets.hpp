#pragma once
// The targets, each checked on this run's figures: PASS, FAIL, SKIPPED (the backend does
// not offer what the target measures) or MISSING (not measured in this run).
#include <ostream>

#include "results.hpp"

namespace anyphys::bench::report {

/// Prints one line per target; returns the number of FAILs.
int printTargets(const Results& results, std::ostream& out);

}  // namespace anyphys::bench::report
