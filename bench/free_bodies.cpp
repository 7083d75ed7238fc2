// Step time of the catalogue's benchmark load (1000 free spinning cubes under gravity).
//   free_bodies_step/<backend>/<integrator index>: one World::step, per integrator the backend
//     offers, with the effects declared as gravity and gyroscopic: the integrators' own cost.
//   effects_cost/<backend>/{off,derived,declared}: the same bodies with nothing for damping or
//     gyroscopic stages to do; "declared" turns those stages on anyway. declared / off is the
//     price of an unused stage. "derived" is what a user gets by default: the cubes have shapes
//     and could collide, so collision detection, sleeping and events run too.
//   fields_cost/<backend>/{drag,buoyancy}: effects_cost's "off" world (gravity only) with one
//     field added (its effect declared too): the price of the field stage when it runs. A world
//     without fields is "off" itself: compare it with the same case before fields existed.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"

namespace anyphys {
namespace {

constexpr int kBodies = 1000;

struct Loaded {
    std::unique_ptr<World> world;
};

Loaded load(const Scene& scene) {
    Loaded l{std::make_unique<World>(scene.settings, scene.materials)};
    for (const BodyDef& def : scene.bodies) l.world->createBody(def);
    return l;
}

/// Bodies fly freely forever (nothing to hit), so any number of steps is a fair sample.
void stepLoop(benchmark::State& state, World& world) {
    for (auto _ : state) world.step();
    state.SetItemsProcessed(state.iterations() * kBodies);  // body-steps per second
}

void freeBodiesStep(benchmark::State& state, const std::string& backend) {
    const Integrator integrator = EnumNames<Integrator>::values.at(static_cast<std::size_t>(state.range(0))).first;
    Scene scene = freeBodiesScene(kBodies);
    scene.settings.backend = backend;
    scene.settings.integrator = integrator;
    scene.settings.effects = Effect::Gravity | Effect::Gyroscopic;
    Loaded l = load(scene);
    state.SetLabel(std::string(toString(integrator)));
    stepLoop(state, *l.world);
}

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
    return out;
}

enum class EffectsCase { Off, Derived, Declared };

void effectsCost(benchmark::State& state, const std::string& backend, EffectsCase which) {
    Scene scene = freeBodiesScene(kBodies);
    scene.settings.backend = backend;
    for (BodyDef& def : scene.bodies) def.gyroscopic = GyroscopicMode::None;  // damping is already 0
    if (which == EffectsCase::Off) scene.settings.effects = Effects(Effect::Gravity);
    if (which == EffectsCase::Declared) scene.settings.effects = Effect::Gravity | Effect::Damping | Effect::Gyroscopic;
    Loaded l = load(scene);
    state.SetLabel(join(l.world->activeEffects().names()));
    stepLoop(state, *l.world);
}

enum class FieldsCase { Drag, Buoyancy };

void fieldsCost(benchmark::State& state, const std::string& backend, FieldsCase which) {
    Scene scene = freeBodiesScene(kBodies);
    scene.settings.backend = backend;
    for (BodyDef& def : scene.bodies) def.gyroscopic = GyroscopicMode::None;
    const FieldDef field = which == FieldsCase::Drag ? FieldDef::drag(1.2) : FieldDef::buoyancy(1000.0, Vec3(0, 1, 0), 5.0);
    scene.settings.effects = Effects(Effect::Gravity).add(fieldEffect(field.type));
    Loaded l = load(scene);
    l.world->addField(field);
    state.SetLabel(join(l.world->activeEffects().names()));
    stepLoop(state, *l.world);
}

void registerAll() {
    for (const BackendInfo& info : availableBackends()) {
        // The free cubes spin in 3D: a planar-only backend (box2d) refuses the world, which used
        // to abort the whole program at its first case.
        if (info.capabilities.dimensions < 3) continue;
        const std::string& name = info.name;
        auto* step = benchmark::RegisterBenchmark(("free_bodies_step/" + name).c_str(),
                                                  [name](benchmark::State& s) { freeBodiesStep(s, name); });
        for (std::size_t i = 0; i < EnumNames<Integrator>::values.size(); ++i)
            if (info.capabilities.integrators.contains(EnumNames<Integrator>::values[i].first))
                step->Arg(static_cast<int64_t>(i));
        step->Unit(benchmark::kMicrosecond);

        const std::pair<const char*, EffectsCase> cases[] = {
            {"off", EffectsCase::Off}, {"derived", EffectsCase::Derived}, {"declared", EffectsCase::Declared}};
        for (const auto& [label, which] : cases)
            benchmark::RegisterBenchmark(("effects_cost/" + name + "/" + label).c_str(),
                                         [name, which = which](benchmark::State& s) { effectsCost(s, name, which); })
                ->Unit(benchmark::kMicrosecond);
        const std::pair<const char*, FieldsCase> fields[] = {{"drag", FieldsCase::Drag}, {"buoyancy", FieldsCase::Buoyancy}};
        for (const auto& [label, which] : fields)
            benchmark::RegisterBenchmark(("fields_cost/" + name + "/" + label).c_str(),
                                         [name, which = which](benchmark::State& s) { fieldsCost(s, name, which); })
                ->Unit(benchmark::kMicrosecond);
    }
}

}  // namespace
}  // namespace anyphys

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    anyphys::registerAll();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
