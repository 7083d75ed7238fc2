// What the special effects (fields/: buoyancy, drag, wind, explosion, fluid, cloth) cost, in one
// process (docs/benchmarks.md, "Special effects"; scripts/bench.sh --effects runs it):
//   no_effects/<scene>/<backend>           the pile with no special effect, World::step against its
//   no_effects_noevents/<scene>/<backend>  own backend peer stepped directly (the bare engine work
//                                          through the peer, what World::step wraps). Alternating,
//                                          comparisonRounds() each, fastest run of each counts.
//                                          ratio_cpu = world / peer: the layer's whole per-step work
//                                          (effect checks, divergence check and, in no_effects,
//                                          contact events), so an upper bound on what the effect
//                                          machinery costs a scene that declares none.
//                                          same_states: both ended bit-identical.
//   effect_cost/<effect>/<backend>         drop200 with one effect added (effect_worlds.cpp) against
//   effect_cost_planar/<effect>/<backend>  the pile alone, both through World::step, alternating as
//                                          above (drop200_planar in the second): cost_cpu_ms per
//                                          step, and per particle, node or body (units). The
//                                          effect "restitution" is no field: every box and the
//                                          ground bounce (e = 0.5), the restitution stages' cost.
#include <algorithm>
#include <functional>
#include <limits>
#include <string>

#include "bench_main.hpp"
#include "effect_worlds.hpp"
#include "layer_simulation.hpp"

namespace anyphys::bench {
namespace {

struct Best {
    double cpuMs = std::numeric_limits<double>::infinity();
    double medianMs = std::numeric_limits<double>::infinity();
    double wallMs = std::numeric_limits<double>::infinity();
    std::vector<BoxState> boxes;  // at the end of the last run
    std::string described;

    void add(PileSimulation& simulation, const ScenePlan& plan, const RunPlan& run) {
        const RunResult r = measure(simulation, plan, run);
        cpuMs = std::min(cpuMs, r.cpuMs);
        medianMs = std::min(medianMs, r.wallMedianMs);
        wallMs = std::min(wallMs, r.wallMs);
        simulation.readBoxes(boxes);
        described = simulation.describe();
    }
};

/// `a` and `b` built afresh and run alternately, each first in every other round (neither always
/// meets a warm or a cold cache), comparisonRounds() times each.
void alternate(const ScenePlan& plan, const std::string& backend, const PileOptions& a, const PileOptions& b,
               Best& bestA, Best& bestB) {
    const RunPlan run = tableRun(plan);
    for (int round = 0; round < comparisonRounds(); ++round)
        for (int k = 0; k < 2; ++k) {
            const bool first = (k == 0) == (round % 2 == 0);
            PileSimulation simulation(plan, backend, first ? a : b);
            (first ? bestA : bestB).add(simulation, plan, run);
        }
}

bool sameStates(const std::vector<BoxState>& a, const std::vector<BoxState>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].position != b[i].position || a[i].orientation.coeffs() != b[i].orientation.coeffs() ||
            a[i].velocity != b[i].velocity)
            return false;
    return true;
}

void noEffects(benchmark::State& state, const std::string& scene, const BackendInfo& backend, bool events) {
    const ScenePlan plan = makeScene(scene);
    if (const std::string reason = cannotRun(plan, backend); !reason.empty()) {
        state.SkipWithError(("n/a: " + reason).c_str());
        return;
    }
    for (auto _ : state) {
        Best world, peer;
        alternate(plan, backend.name, {events, SpecialEffect::None, false}, {events, SpecialEffect::None, true}, world,
                  peer);
        state.SetIterationTime(world.wallMs / 1e3);
        auto& c = state.counters;
        c["bodies"] = plan.count();
        c["steps"] = tableRun(plan).steps;
        c["rounds"] = comparisonRounds();
        c["world_cpu_ms"] = world.cpuMs;
        c["peer_cpu_ms"] = peer.cpuMs;
        c["ratio_cpu"] = world.cpuMs / peer.cpuMs;
        c["world_median_ms"] = world.medianMs;
        c["peer_median_ms"] = peer.medianMs;
        c["ratio_median"] = world.medianMs / peer.medianMs;
        c["same_states"] = sameStates(world.boxes, peer.boxes) ? 1 : 0;
        state.SetLabel(world.described + ", best of " + std::to_string(comparisonRounds()));
    }
}

void effectCost(benchmark::State& state, SpecialEffect effect, const std::string& scene, const BackendInfo& backend) {
    const ScenePlan plan = makeScene(scene);
    if (const std::string reason = cannotRun(plan, backend); !reason.empty()) {
        state.SkipWithError(("n/a: " + reason).c_str());
        return;
    }
    for (auto _ : state) {
        Best base, with;
        int units = 0;
        {
            PileSimulation probe(plan, backend.name, {true, effect, false});
            units = probe.units();
        }
        alternate(plan, backend.name, {true, SpecialEffect::None, false}, {true, effect, false}, base, with);
        state.SetIterationTime(with.wallMs / 1e3);
        auto& c = state.counters;
        c["steps"] = tableRun(plan).steps;
        c["rounds"] = comparisonRounds();
        c["units"] = units;
        c["base_cpu_ms"] = base.cpuMs;
        c["effect_cpu_ms"] = with.cpuMs;
        c["cost_cpu_ms"] = with.cpuMs - base.cpuMs;
        c["ratio_cpu"] = with.cpuMs / base.cpuMs;
        c["cost_us_per_unit"] = 1e3 * (with.cpuMs - base.cpuMs) / units;
        c["base_median_ms"] = base.medianMs;
        c["effect_median_ms"] = with.medianMs;
        c["cost_median_ms"] = with.medianMs - base.medianMs;
        state.SetLabel(plan.name + ", " + with.described + ", best of " + std::to_string(comparisonRounds()));
    }
}

void add(const std::string& name, std::function<void(benchmark::State&)> run) {
    benchmark::RegisterBenchmark(name.c_str(), std::move(run))
        ->UseManualTime()
        ->Iterations(1)  // one run of 300 steps per side and round is a sample in itself
        ->Unit(benchmark::kMillisecond);
}

void registerAll() {
    for (const BackendInfo& backend : availableBackends()) {
        for (const std::string scene : {"drop200", "drop200_planar"}) {
            add("no_effects/" + scene + "/" + backend.name,
                [=](benchmark::State& s) { noEffects(s, scene, backend, true); });
            add("no_effects_noevents/" + scene + "/" + backend.name,
                [=](benchmark::State& s) { noEffects(s, scene, backend, false); });
        }
        for (const auto& [name, effect] : specialEffects()) {  // and restitution, after the loop
            add("effect_cost/" + name + "/" + backend.name,
                [=, effect = effect](benchmark::State& s) { effectCost(s, effect, "drop200", backend); });
            add("effect_cost_planar/" + name + "/" + backend.name,
                [=, effect = effect](benchmark::State& s) { effectCost(s, effect, "drop200_planar", backend); });
        }
        add("effect_cost/restitution/" + backend.name,
            [=](benchmark::State& s) { effectCost(s, SpecialEffect::Restitution, "drop200", backend); });
        add("effect_cost_planar/restitution/" + backend.name,
            [=](benchmark::State& s) { effectCost(s, SpecialEffect::Restitution, "drop200_planar", backend); });
    }
}

}  // namespace
}  // namespace anyphys::bench

int main(int argc, char** argv) { return anyphys::bench::benchMain(argc, argv, &anyphys::bench::registerAll); }
