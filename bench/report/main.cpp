// anyphys_bench_report FILE.json...: reads the benchmark programs' Google Benchmark JSON output
// (scripts/bench.sh writes it) and prints the Markdown report: the scene table, the per-body
// cost, the 2-worker speed-up, the wrapper overhead, the allocations per steady step, what was
// not run and why, and the targets with PASS / FAIL. Exits 0 whatever the verdicts
// (benchmarks are not tests); 2 when a file cannot be read.
#include <exception>
#include <iostream>

#include "results.hpp"
#include "tables.hpp"
#include "targets.hpp"

int main(int argc, char** argv) {
    using namespace anyphys::bench::report;
    if (argc < 2) {
        std::cerr << "usage: anyphys_bench_report FILE.json...\n";
        return 2;
    }
    Results results;
    try {
        for (int i = 1; i < argc; ++i) results.load(argv[i]);
    } catch (const std::exception& e) {
        std::cerr << "anyphys_bench_report: " << e.what() << '\n';
        return 2;
    }
    std::ostream& out = std::cout;
    out << "### Scenes (time per step; outcome at the end of the run)\n\n";
    printScenes(results, out);
    out << "\n### Per-body cost (the 10-layer drop at three sizes: 30 steps of falling untimed, then 30 timed;"
           " 10 and 10 with --quick)\n\n";
    printScaling(results, out);
    out << "\n### Two workers\n\n";
    printWorkers(results, out);
    out << "\n### Wrapper overhead (anyphys with events on against the raw engine, same process)\n\n";
    printOverhead(results, out);
    out << "\n### Heap allocations per steady step (the last 60 steps of each run; fewer with --quick)\n\n";
    printAllocations(results, out);
    out << "\n### Not run\n\n";
    printNotRun(results, out);
    out << "\n### Targets (issue 9)\n\n";
    const int fails = printTargets(results, out);
    out << "\n" << fails << " target" << (fails == 1 ? "" : "s") << " failed.\n";
    return 0;
}
