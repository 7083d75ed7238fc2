#include "effects.hpp"

#include <vector>

#include "engines.hpp"
#include "markdown.hpp"

namespace anyphys::bench::report {
namespace {

/// The (kind, scene, engine) triples of `kind`, in engine order, each once (repetitions and their
/// aggregates share a name).
std::vector<const Record*> distinct(const Results& results, const std::string& kind) {
    std::vector<const Record*> out;
    for (const std::string& engine : engineOrder(results))
        for (const Record& r : results.all()) {
            if (r.kind != kind || r.engine != engine || !r.aggregate.empty()) continue;
            bool seen = false;
            for (const Record* o : out) seen = seen || (o->scene == r.scene && o->engine == r.engine);
            if (!seen) out.push_back(&r);
        }
    return out;
}

std::string ratio(double v) { return num(v, 3) + "x"; }

std::string units(const Record& r) {
    const std::string n = num(r["units"], 0);
    if (r.scene == "fluid") return n + " particles";
    if (r.scene == "cloth") return n + " nodes";
    if (r.scene == "explosion") return "1 blast, " + n + " bodies";
    if (r.scene == "restitution") return n + " bouncing bodies";
    return n + " bodies";
}

}  // namespace

void printNoEffects(const Results& results, std::ostream& out) {
    Table table({"scene", "engine", "events", "World CPU ms/step", "peer CPU ms/step", "World / peer (CPU)",
                 "World / peer (median step)", "same states", "runs"},
                3);
    for (const std::string kind : {"no_effects", "no_effects_noevents"})
        for (const Record* first : distinct(results, kind)) {
            if (!first->ran()) continue;
            const Record& r = *results.median(kind, first->scene, first->engine);
            table.row({r.scene, r.engine, kind == "no_effects" ? "on (derived)" : "off (declared)",
                       num(r["world_cpu_ms"], 3), num(r["peer_cpu_ms"], 3), ratio(r["ratio_cpu"]),
                       ratio(r["ratio_median"]), r["same_states"] == 1 ? "yes" : "no",
                       r.aggregate.empty() ? "1" : "median of reps"});
        }
    table.print(out);
}

void printEffectCosts(const Results& results, std::ostream& out) {
    Table table({"effect", "scene", "engine", "acts on", "pile CPU ms/step", "with the effect", "cost ms/step",
                 "cost us per unit", "ratio"},
                4);
    for (const std::string name : {"buoyancy", "drag", "wind", "explosion", "fluid", "cloth", "restitution"})
        for (const std::string kind : {"effect_cost", "effect_cost_planar"})
            for (const std::string& engine : engineOrder(results)) {
                const Record* r = results.median(kind, name, engine);
                if (!r || !r->ran()) continue;
                table.row({name, kind == "effect_cost" ? "drop200" : "drop200_planar", engine, units(*r),
                           num((*r)["base_cpu_ms"], 3), num((*r)["effect_cpu_ms"], 3), num((*r)["cost_cpu_ms"], 3),
                           num((*r)["cost_us_per_unit"], 2), ratio((*r)["ratio_cpu"])});
            }
    table.print(out);
}

}  // namespace anyphys::bench::report
