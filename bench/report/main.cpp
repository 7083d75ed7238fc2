// anyphys_bench_report FILE.json...: reads the benchmark programs' Google Benchmark JSON output
// (scripts/bench.sh writes it) and prints the Markdown report: the scene table, the per-body
// cost, the 2-worker speed-up, the wrapper overhead, the special effects' cost (alone with
// --effects), the allocations per steady step, what was
// not run and why, and the targets with PASS / FAIL. Exits 0 whatever the verdicts
// (benchmarks are not tests); 2 when a file cannot be read.
#include <exception>
#include <iostream>
#include <string>

#include "effects.hpp"
#include "results.hpp"
#include "tables.hpp"
#include "targets.hpp"

int main(int argc, char** argv) {
    using namespace anyphys::bench::report;
    // --effects: only the special-effect tables (scripts/bench.sh --effects).
    const bool effectsOnly = argc > 1 && std::string(argv[1]) == "--effects";
    const int firstFile = effectsOnly ? 2 : 1;
    if (argc <= firstFile) {
        std::cerr << "usage: anyphys_bench_report [--effects] FILE.json...\n";
        return 2;
    }
    Results results;
    try {
        for (int i = firstFile; i < argc; ++i) results.load(argv[i]);
    } catch (const std::exception& e) {
        std::cerr << "anyphys_bench_report: " << e.what() << '\n';
        return 2;
    }
    std::ostream& out = std::cout;
    const auto effects = [&] {
        out << "### No special effect: World::step against its bare backend peer (CPU per step, best of the rounds)\n\n";
        printNoEffects(results, out);
        out << "\n### Cost per step of each special effect (the pile with it against the pile alone, CPU)\n\n";
        printEffectCosts(results, out);
    };
    if (effectsOnly) {
        effects();
        return 0;
    }
    out << "### Scenes (time per step; outcome at the end of the run)\n\n";
    printScenes(results, out);
    out << "\n### Per-body cost (the 10-layer drop at three sizes: 30 steps of falling untimed, then 30 timed;"
           " 10 and 10 with --quick)\n\n";
    printScaling(results, out);
    out << "\n### Two workers\n\n";
    printWorkers(results, out);
    out << "\n### Wrapper overhead (anyphys with events on against the raw engine, same process; \"with a listener\": "
           "a listener reads every event)\n\n";
    printOverhead(results, out);
    out << "\n";
    effects();
    out << "\n### Heap allocations per steady step (the last 60 steps of each run; fewer with --quick)\n\n";
    printAllocations(results, out);
    out << "\n### Not run\n\n";
    printNotRun(results, out);
    out << "\n### Targets (issue 9)\n\n";
    const int fails = printTargets(results, out);
    out << "\n" << fails << " target" << (fails == 1 ? "" : "s") << " failed.\n";
    return 0;
}
