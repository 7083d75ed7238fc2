// BM_BoxGrid1000/<backend>: the catalogue's box_grid_1000 (10x10x10 unit boxes 1.2 m apart,
// dropped from 1 m onto the ground, dt 1/60) run for its 5 s on every backend that simulates
// boxes, planes and contacts in 3D. BM_BoxGrid1000Planar/<backend>: box_grid_1000_planar (50x20
// boxes in the XY plane, settings.planar) on every backend with planar worlds. Reported:
//   time                 wall time per World::step, averaged over the whole drop (falling, impacts
//                        and the settling pile: each phase costs differently)
//   cpu_ms_per_step      process CPU time per step (steadier than wall time on a loaded machine)
//   max_penetration_m    deepest overlap at the end, box-ground or box-box, from body poses
//   max_event_depth_m    deepest contact point the backend reported in the last step's events
//                        (awake pairs only: sleeping contacts send no events)
//   settled              1 if every box is asleep or slower than 0.05 m/s at the end, else 0
//   asleep_bodies        boxes asleep at the end
//   max_speed_mps        fastest box at the end
//   rest_ms_per_step     wall time per step of 60 further steps once the pile has settled
//                        (a resting, sleeping pile should cost almost nothing)
// A backend lacking something is listed with the reason instead of a time.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"
#include "box_overlap.hpp"

namespace anyphys {
namespace {

constexpr double kSettledSpeed = 0.05;  // m/s: the default sleep threshold

/// What this benchmark needs from a backend; empty when it has everything.
std::string lacking(const Capabilities& caps, bool planar) {
    std::string missing;
    const auto need = [&missing](bool has, const char* what) {
        if (!has) missing += (missing.empty() ? "" : ", ") + std::string(what);
    };
    need(planar ? caps.planar : caps.dimensions == 3, planar ? "planar worlds" : "3D worlds");
    need(caps.shapes.contains(ShapeType::Box), "shape box");
    need(caps.shapes.contains(ShapeType::Plane), "shape plane");
    need(caps.effects.has(Effect::Contacts), "effect contacts");
    return missing;
}

struct Box {
    Body body;
    Vec3 half;  ///< m, half extents
    bench::OrientedBox pose() const { return {body.position(), body.orientation().toRotationMatrix(), half}; }
};

/// Deepest overlap among the boxes and between the boxes and the ground plane y = 0.
double maxPenetration(const std::vector<bench::OrientedBox>& boxes) {
    constexpr double kReach = 1.7321;  // centres farther apart than 2 x |half diagonal| cannot touch
    double deepest = 0.0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        deepest = std::max(deepest, bench::groundPenetration(boxes[i]));
        for (std::size_t j = i + 1; j < boxes.size(); ++j)
            if ((boxes[i].center - boxes[j].center).squaredNorm() < kReach * kReach)
                deepest = std::max(deepest, bench::boxPenetration(boxes[i], boxes[j]));
    }
    return deepest;
}

double maxEventDepth(const std::vector<ContactEvent>& events) {
    double deepest = 0.0;
    for (const ContactEvent& e : events)
        for (const ContactPoint& p : e.points) deepest = std::max(deepest, p.depth);
    return deepest;
}

void boxGrid(benchmark::State& state, const BackendInfo& backend, const std::string& sceneName) {
    const CatalogueScene& entry = catalogueScene(sceneName);
    if (const std::string missing = lacking(backend.capabilities, entry.scene.settings.planar); !missing.empty()) {
        state.SkipWithError(("skipped: backend " + backend.name + " lacks " + missing).c_str());
        return;
    }
    const long long steps = std::llround(entry.duration / entry.scene.settings.timeStep);
    for (auto _ : state) {
        WorldSettings settings = entry.scene.settings;
        settings.backend = backend.name;
        World world(settings, entry.scene.materials);
        std::vector<Box> boxes;
        for (const BodyDef& def : entry.scene.bodies) {
            Body body = world.createBody(def);
            if (def.type == BodyType::Dynamic) boxes.push_back({body, def.shape.halfExtents});
        }
        const std::clock_t cpuStart = std::clock();
        const auto start = std::chrono::steady_clock::now();
        for (long long i = 0; i < steps; ++i) world.step();
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        const double cpuSeconds = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
        state.SetIterationTime(elapsed.count() / static_cast<double>(steps));  // per step
        state.counters["cpu_ms_per_step"] = 1000.0 * cpuSeconds / static_cast<double>(steps);

        std::vector<bench::OrientedBox> poses;
        double fastest = 0.0;
        int asleep = 0;
        for (const Box& box : boxes) {
            poses.push_back(box.pose());
            fastest = std::max(fastest, box.body.linearVelocity().norm());
            asleep += box.body.isAwake() ? 0 : 1;
        }
        state.counters["max_penetration_m"] = maxPenetration(poses);
        state.counters["max_event_depth_m"] = maxEventDepth(world.lastEvents());
        state.counters["max_speed_mps"] = fastest;
        state.counters["asleep_bodies"] = asleep;
        state.counters["settled"] = asleep == static_cast<int>(boxes.size()) || fastest < kSettledSpeed ? 1 : 0;
        constexpr int kRestSteps = 60;
        const auto restStart = std::chrono::steady_clock::now();
        for (int i = 0; i < kRestSteps; ++i) world.step();
        const std::chrono::duration<double, std::milli> rest = std::chrono::steady_clock::now() - restStart;
        state.counters["rest_ms_per_step"] = rest.count() / kRestSteps;
    }
    state.SetLabel(std::to_string(steps) + " steps of dt 1/60");
}

void registerAll() {
    for (const auto& [label, scene] : {std::pair{"BM_BoxGrid1000/", "box_grid_1000"},
                                       std::pair{"BM_BoxGrid1000Planar/", "box_grid_1000_planar"}})
        for (const BackendInfo& info : availableBackends())
            benchmark::RegisterBenchmark((label + info.name).c_str(),
                                         [info, scene = std::string(scene)](benchmark::State& s) { boxGrid(s, info, scene); })
                ->UseManualTime()
                ->Iterations(1)  // one drop is 300 steps of a 1000-box pile: a sample in itself
                ->Unit(benchmark::kMillisecond);
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
