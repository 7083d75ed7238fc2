#include "tables.hpp"

#include <map>
#include <set>

#include "../scenes.hpp"
#include "engines.hpp"
#include "markdown.hpp"

namespace anyphys::bench::report {
namespace {

std::string settled(const Record& r) {
    std::string text = r["settled"] == 1 ? "yes" : "no";
    if (r["nonfinite"] > 0) text += " (" + num(r["nonfinite"], 0) + " non-finite)";
    return text;
}

/// The rows of one scene, in the order the table shows them.
std::vector<const Record*> sceneRows(const Results& results, const std::string& scene) {
    std::vector<const Record*> rows;
    const auto take = [&](const std::string& kind, const std::string& engine, int workers) {
        if (const Record* r = results.find(kind, scene, engine, workers); r && r->ran()) rows.push_back(r);
    };
    for (const std::string& engine : engineOrder(results)) {
        take("scene", engine, 1);
        take("workers", engine, 2);
    }
    for (const std::string& engine : engineOrder(results)) take("raw", engine, 1);
    return rows;
}

}  // namespace

void printScenes(const Results& results, std::ostream& out) {
    Table table({"scene", "engine", "solver", "steps", "wall ms/step", "median ms", "CPU ms/step", "penetration mm",
                 "ground pen. mm", "moved > 0.25 m", "max move m", "max speed m/s", "settled", "allocs/step"},
                3);
    for (const std::string& scene : tableScenes())
        for (const Record* r : sceneRows(results, scene))
            table.row({scene, engineName(*r), r->label, num((*r)["steps"], 0), num((*r)["wall_ms"], 3),
                       num((*r)["wall_median_ms"], 3), num((*r)["cpu_ms"], 3), num((*r)["penetration_mm"], 2),
                       num((*r)["ground_penetration_mm"], 2), num((*r)["moved"], 0), num((*r)["max_move_m"], 3),
                       num((*r)["max_speed"], 3), settled(*r), allocations((*r)["allocs_per_step"])});
    table.print(out);
}

void printScaling(const Results& results, std::ostream& out) {
    Table table({"engine", "scene", "bodies", "CPU us per body-step", "wall us per body-step", "CPU ms/step",
                 "per-body CPU vs the first"});
    for (const std::string& engine : engineOrder(results)) {
        double first = std::nan("");
        for (const std::string& scene : scalingScenes()) {
            const Record* r = results.find("scaling", scene, engine);
            if (!r || !r->ran()) continue;
            if (std::isnan(first)) first = (*r)["cpu_us_per_body"];
            table.row({"anyphys " + engine, scene, num((*r)["bodies"], 0), num((*r)["cpu_us_per_body"], 3),
                       num((*r)["wall_us_per_body"], 3), num((*r)["cpu_ms"], 2),
                       num((*r)["cpu_us_per_body"] / first, 2) + "x"});
        }
    }
    table.print(out);
}

void printWorkers(const Results& results, std::ostream& out) {
    // Both wall times from the workers/ row: 1 and 2 workers alternated, the fastest of each kept.
    Table table({"scene", "engine", "1 worker wall ms/step", "2 workers wall ms/step", "speed-up", "rounds",
                 "2 workers CPU ms/step"});
    for (const Record& w : results.all()) {
        if (w.kind != "workers" || !w.ran()) continue;
        table.row({w.scene, "anyphys " + w.engine, num(w["one_worker_wall_ms"], 2), num(w["wall_ms"], 2),
                   num(w["speedup"], 2) + "x", num(w["rounds"], 0), num(w["cpu_ms"], 2)});
    }
    if (table.empty())
        out << "No backend ran with 2 workers (none lists \"settings.workers\"; see the targets below).\n";
    else
        table.print(out);
}

void printOverhead(const Results& results, std::ostream& out) {
    Table table({"scene", "engine", "anyphys CPU ms/step", "raw CPU ms/step", "overhead (CPU)", "overhead (wall)",
                 "with a listener (CPU)", "listener, no impulses (CPU)", "events/step", "penetration mm anyphys / raw",
                 "settled anyphys / raw", "allocs/step anyphys / raw", "rounds"});
    for (const Record* overhead : inEngineOrder(results, "overhead")) {
        const Record& r = *overhead;
        if (!r.ran()) continue;
        const auto yesNo = [](double v) { return std::string(v == 1 ? "yes" : "no"); };
        table.row({r.scene, engineName(r), num(r["anyphys_cpu_ms"], 3), num(r["raw_cpu_ms"], 3),
                   num(r["overhead_pct"], 1) + " %", num(r["overhead_wall_pct"], 1) + " %",
                   num(r["listening_overhead_pct"], 1) + " %", num(r["points_overhead_pct"], 1) + " %",
                   num(r["listening_events_per_step"], 0),
                   num(r["anyphys_penetration_mm"], 2) + " / " + num(r["raw_penetration_mm"], 2),
                   yesNo(r["anyphys_settled"]) + " / " + yesNo(r["raw_settled"]),
                   allocations(r["anyphys_allocs_per_step"]) + " / " + allocations(r["raw_allocs_per_step"]),
                   num(r["rounds"], 0)});
    }
    table.print(out);
}

void printAllocations(const Results& results, std::ostream& out) {
    std::vector<std::string> header = {"engine", "kind"};
    for (const std::string& scene : tableScenes()) header.push_back(scene);
    Table table(header);
    for (const std::string kind : {"scene", "raw"})
        for (const std::string& engine : engineOrder(results)) {
            std::vector<std::string> row = {kind == "raw" ? rawName(engine) : "anyphys " + engine,
                                            kind == "raw" ? "raw engine" : "through anyphys"};
            bool any = false;
            for (const std::string& scene : tableScenes()) {
                const Record* r = results.find(kind, scene, engine);
                any = any || (r && r->ran());
                row.push_back(r && r->ran() ? allocations((*r)["allocs_per_step"]) : "");
            }
            if (any) table.row(row);
        }
    table.print(out);
}

void printNotRun(const Results& results, std::ostream& out) {
    std::map<std::string, std::set<std::string>> byReason;  // sorted: the same output every run
    for (const Record& r : results.all())
        if (!r.ran()) byReason[r.error].insert(r.kind + "/" + r.scene);
    for (const auto& [reason, what] : byReason) {
        out << "- " << reason << ":";
        for (const std::string& w : what) out << ' ' << w;
        out << '\n';
    }
}

}  // namespace anyphys::bench::report
