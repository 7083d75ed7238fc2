#pragma once
// The report's tables, one function each (Markdown on `out`).
#include <ostream>

#include "results.hpp"

namespace anyphys::bench::report {

/// Every scene on every engine: anyphys rows (and 2-worker rows) then the raw engines.
void printScenes(const Results& results, std::ostream& out);
/// Per-body cost of the 10-layer drop at 1 000, 10 000 and 50 000 boxes.
void printScaling(const Results& results, std::ostream& out);
/// Wall time with 1 and 2 workers.
void printWorkers(const Results& results, std::ostream& out);
/// anyphys against the raw engine, best of the rounds.
void printOverhead(const Results& results, std::ostream& out);
/// Heap allocations per steady step, every backend and raw engine on every scene.
void printAllocations(const Results& results, std::ostream& out);
/// What was skipped, grouped by reason.
void printNotRun(const Results& results, std::ostream& out);

}  // namespace anyphys::bench::report
