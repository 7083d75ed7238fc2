// boxGridOverhead/{derived_effects,no_events}: what the anyphys layer and its ODE backend cost on top of ODE.
// The catalogue's box_grid_1000 (1000 unit boxes dropped onto the ground, 300 steps of 1/60 s)
// runs (a) through anyphys on backend "ode" and (b) written directly against ODE with the
// settings the backend uses (backends/ode/ode_tuning.hpp and ode_world.cpp: hash space, quickstep
// iterations and over-relaxation, ERP / CFM, surface layer, correcting velocity, contact count
// and surface mode, auto-disable, finite rotation). The direct version does what a plain ODE user
// does and nothing more: no contact events, no continuous collision sweep.
// Both run in this one process, alternating, `kRounds` times each; the fastest round of each is
// reported (the machine is shared, so the minimum is the least disturbed):
//   anyphys_ms_per_step / direct_ms_per_step   thread CPU time per step
//   overhead_pct                               100 (anyphys / direct - 1)
//   anyphys_asleep / direct_asleep             boxes asleep at the end (the two runs must agree)
#include <benchmark/benchmark.h>
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"

namespace anyphys {
namespace {

constexpr int kRounds = 3;

// The backend's values (backends/ode/ode_tuning.hpp, ode_world.cpp), repeated here because the
// comparison must drive raw ODE the same way: change both together.
constexpr int kIterations = 50;
constexpr double kQuickStepW = 1.3;
constexpr double kCfm = 1e-6;
constexpr double kSurfaceLayerPerSlop = 0.2;
constexpr int kMaxContactsPerPair = 4;
constexpr int kHashMinLevel = -3, kHashMaxLevel = 10;

double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Run {
    double secondsPerStep = 0.0;
    int asleep = 0;
};

Run runAnyphys(const CatalogueScene& entry, long long steps, bool events) {
    WorldSettings settings = entry.scene.settings;
    settings.backend = "ode";
    if (!events) {
        // What the scene derives, minus events: the layer's contact tracking and the backend's
        // contact reports (joint feedback, per-pair point lists) are then skipped.
        settings.effects = Effects(Effect::Gravity) | Effect::Contacts | Effect::Friction | Effect::Sleeping |
                           Effect::ContinuousCollision;
    }
    World world(settings, entry.scene.materials);
    std::vector<Body> boxes;
    for (const BodyDef& def : entry.scene.bodies) {
        Body body = world.createBody(def);
        if (def.type == BodyType::Dynamic) boxes.push_back(body);
    }
    const double start = threadSeconds();
    for (long long i = 0; i < steps; ++i) world.step();
    Run run{(threadSeconds() - start) / static_cast<double>(steps), 0};
    for (const Body& b : boxes) run.asleep += b.isAwake() ? 0 : 1;
    return run;
}

// ---- the same scene on raw ODE ----------------------------------------------------------------

struct DirectScene {
    dWorldID world = nullptr;
    dSpaceID space = nullptr;
    dJointGroupID contacts = nullptr;
    double friction = 0.0;
    std::vector<dBodyID> bodies;
};

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
    auto& scene = *static_cast<DirectScene*>(data);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (!b1 && !b2) return;  // static against static
    if ((!b1 || !dBodyIsEnabled(b1)) && (!b2 || !dBodyIsEnabled(b2))) return;  // asleep
    if (!b1) {
        std::swap(o1, o2);
        std::swap(b1, b2);
    }
    dContact contact[kMaxContactsPerPair];
    const int n = dCollide(o1, o2, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
        contact[i].surface.mode = dContactApprox1;
        contact[i].surface.mu = scene.friction;
        const dJointID j = dJointCreateContact(scene.world, scene.contacts, &contact[i]);
        dJointAttach(j, b1, b2);
    }
}

Run runDirect(const CatalogueScene& entry, long long steps) {
    const WorldSettings& s = entry.scene.settings;
    DirectScene scene;
    scene.world = dWorldCreate();
    scene.space = dHashSpaceCreate(nullptr);
    dHashSpaceSetLevels(scene.space, kHashMinLevel, kHashMaxLevel);
    scene.contacts = dJointGroupCreate(0);
    dWorldSetGravity(scene.world, s.gravity.x(), s.gravity.y(), s.gravity.z());
    dWorldSetERP(scene.world, s.baumgarte);
    dWorldSetCFM(scene.world, kCfm);
    dWorldSetQuickStepNumIterations(scene.world, kIterations);
    dWorldSetQuickStepW(scene.world, kQuickStepW);
    dWorldSetContactSurfaceLayer(scene.world, kSurfaceLayerPerSlop * s.linearSlop);
    dWorldSetContactMaxCorrectingVel(scene.world, s.contactPushMaxVelocity);
    dWorldSetAutoDisableFlag(scene.world, 1);
    dWorldSetAutoDisableLinearThreshold(scene.world, s.sleepLinearVelocity);
    dWorldSetAutoDisableAngularThreshold(scene.world, s.sleepAngularVelocity);
    dWorldSetAutoDisableAverageSamplesCount(scene.world, 1);
    dWorldSetAutoDisableSteps(scene.world, 0);
    dWorldSetAutoDisableTime(scene.world, s.timeToSleep);
    scene.friction = entry.scene.materials.resolve("", "").friction;  // every body uses the default material
    for (const BodyDef& def : entry.scene.bodies) {
        if (def.type == BodyType::Static) {
            const Vec3 n = def.shape.normal.normalized();
            dCreatePlane(scene.space, n.x(), n.y(), n.z(), def.shape.offset);
            continue;
        }
        const Vec3 h = def.shape.halfExtents;
        const dBodyID body = dBodyCreate(scene.world);
        dBodySetPosition(body, def.position.x(), def.position.y(), def.position.z());
        const double mass = def.density.value_or(1000.0) * 8 * h.x() * h.y() * h.z();
        dMass m;
        dMassSetBoxTotal(&m, mass, 2 * h.x(), 2 * h.y(), 2 * h.z());
        dBodySetMass(body, &m);
        dBodySetFiniteRotationMode(body, 1);
        dBodySetGyroscopicMode(body, 0);  // cubes: the term vanishes (the backend skips it too)
        const dGeomID geom = dCreateBox(scene.space, 2 * h.x(), 2 * h.y(), 2 * h.z());
        dGeomSetBody(geom, body);
        scene.bodies.push_back(body);
    }
    const double dt = s.timeStep;
    const double start = threadSeconds();
    for (long long i = 0; i < steps; ++i) {
        dSpaceCollide(scene.space, &scene, &nearCallback);
        dWorldQuickStep(scene.world, dt);
        dJointGroupEmpty(scene.contacts);
    }
    Run run{(threadSeconds() - start) / static_cast<double>(steps), 0};
    for (dBodyID b : scene.bodies) run.asleep += dBodyIsEnabled(b) ? 0 : 1;
    dJointGroupDestroy(scene.contacts);
    dSpaceDestroy(scene.space);  // destroys its geoms
    dWorldDestroy(scene.world);  // and its bodies
    return run;
}

void boxGridOverhead(benchmark::State& state, bool events) {
    const CatalogueScene& entry = catalogueScene("box_grid_1000");
    const long long steps = std::llround(entry.duration / entry.scene.settings.timeStep);
    dInitODE2(0);  // the backend initialises ODE too; a second call only counts a reference
    for (auto _ : state) {
        Run layer{std::numeric_limits<double>::infinity(), 0}, direct{std::numeric_limits<double>::infinity(), 0};
        for (int round = 0; round < kRounds; ++round) {
            // Alternate which goes first, so neither always meets a warm or a cold cache.
            const bool layerFirst = round % 2 == 0;
            for (int k = 0; k < 2; ++k) {
                if ((k == 0) == layerFirst) {
                    const Run r = runAnyphys(entry, steps, events);
                    if (r.secondsPerStep < layer.secondsPerStep) layer = r;
                } else {
                    const Run r = runDirect(entry, steps);
                    if (r.secondsPerStep < direct.secondsPerStep) direct = r;
                }
            }
        }
        state.SetIterationTime(layer.secondsPerStep);
        state.counters["anyphys_ms_per_step"] = 1000.0 * layer.secondsPerStep;
        state.counters["direct_ms_per_step"] = 1000.0 * direct.secondsPerStep;
        state.counters["overhead_pct"] = 100.0 * (layer.secondsPerStep / direct.secondsPerStep - 1.0);
        state.counters["anyphys_asleep"] = layer.asleep;
        state.counters["direct_asleep"] = direct.asleep;
    }
    state.SetLabel(std::to_string(steps) + " steps of dt 1/60, best of " + std::to_string(kRounds) + " rounds each");
}

// derived_effects: the scene as the catalogue gives it (events on, as derived from its content);
// no_events: the same with its effects declared without events, for a user who needs none.
BENCHMARK_CAPTURE(boxGridOverhead, derived_effects, true)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(boxGridOverhead, no_events, false)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace anyphys

BENCHMARK_MAIN();
