// Wrapper overhead on Bullet: the catalogue's box_grid_1000 (1000 unit boxes dropped onto the
// ground, 300 steps of 1/60 s) run
//   (a) through anyphys on backend "bullet", effects derived from the scene as a user gets them
//       (events on: contacts are collected and tracked each step),
//   (b) through anyphys with the same effects declared but events off,
//   (c) written directly against Bullet with the configuration the backend uses (solver info,
//       shapes and margins, per-body gravity, sleeping thresholds, one internal step per step).
// The three runs are interleaved, `rounds` times each, in one process; the fastest round of each
// counts (the least disturbed by other load on the machine). Reported per step (CPU time):
//   anyphys_ms, anyphys_noevents_ms, direct_ms, overhead_pct = anyphys / direct - 1,
//   overhead_noevents_pct = anyphys_noevents / direct - 1.
#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"

namespace {

using namespace anyphys;

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// CPU seconds per step of the scene through anyphys.
double runAnyphys(const CatalogueScene& entry, bool events, double& finalHeight) {
    WorldSettings settings = entry.scene.settings;
    settings.backend = "bullet";
    if (!events) {
        // What the scene derives, minus events.
        settings.effects = Effects(Effect::Gravity) | Effect::Gyroscopic | Effect::Contacts | Effect::Friction |
                           Effect::ContinuousCollision | Effect::Sleeping;
        // Restitution only where some pair bounces, as the derivation does.
    }
    World world(settings, entry.scene.materials);
    std::vector<Body> bodies;
    for (const BodyDef& def : entry.scene.bodies) bodies.push_back(world.createBody(def));
    const long long steps = std::llround(entry.duration / settings.timeStep);
    const double start = cpuSeconds();
    for (long long i = 0; i < steps; ++i) world.step();
    const double perStep = (cpuSeconds() - start) / static_cast<double>(steps);
    finalHeight = 0;
    for (const Body& b : bodies) finalHeight += b.position().y();
    return perStep;
}

/// The same scene on Bullet directly, configured as backends/bullet configures its world.
double runDirect(const CatalogueScene& entry, double& finalHeight) {
    const WorldSettings& s = entry.scene.settings;
    const BackendInfo& info = backendInfo("bullet");
    auto configuration = std::make_unique<btDefaultCollisionConfiguration>();
    auto dispatcher = std::make_unique<btCollisionDispatcher>(configuration.get());
    auto broadphase = std::make_unique<btDbvtBroadphase>();
    auto solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    auto world = std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(),
                                                           configuration.get());
    world->setGravity(btVector3(0, 0, 0));
    world->setForceUpdateAllAabbs(false);
    btContactSolverInfo& si = world->getSolverInfo();
    si.m_numIterations = s.iterations.value_or(info.capabilities.defaultIterations);
    si.m_erp = si.m_erp2 = static_cast<btScalar>(s.baumgarte);
    si.m_splitImpulse = true;
    si.m_splitImpulsePenetrationThreshold = -0.04f;
    si.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
    si.m_maxGyroscopicForce = BT_LARGE_FLOAT;
    si.m_restitutionVelocityThreshold = static_cast<btScalar>(s.restitutionThreshold);
    gDeactivationTime = static_cast<btScalar>(s.timeToSleep);  // a process global: fine in a benchmark
    world->getDispatchInfo().m_useContinuous = true;

    // Bullet multiplies the two bodies' friction: sqrt of the scene's (single) mixed value on each.
    const BodyDef& box0 = entry.scene.bodies[1];
    const MixedMaterial mix = entry.scene.materials.resolve(box0.material, entry.scene.bodies[0].material);
    const btScalar friction = static_cast<btScalar>(std::sqrt(mix.friction));
    const btScalar restitution = static_cast<btScalar>(std::sqrt(mix.restitution));

    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    const btVector3 gravity(static_cast<btScalar>(s.gravity.x()), static_cast<btScalar>(s.gravity.y()),
                            static_cast<btScalar>(s.gravity.z()));
    for (const BodyDef& def : entry.scene.bodies) {
        btRigidBody* body = nullptr;
        if (def.type == BodyType::Static) {
            const Vec3 n = def.shape.normal.normalized();
            shapes.push_back(std::make_unique<btStaticPlaneShape>(
                btVector3(static_cast<btScalar>(n.x()), static_cast<btScalar>(n.y()), static_cast<btScalar>(n.z())),
                static_cast<btScalar>(def.shape.offset)));
            btRigidBody::btRigidBodyConstructionInfo ci(0, nullptr, shapes.back().get());
            bodies.push_back(std::make_unique<btRigidBody>(ci));
            body = bodies.back().get();
        } else {
            const Vec3 h = def.shape.halfExtents;
            auto box = std::make_unique<btBoxShape>(
                btVector3(static_cast<btScalar>(h.x()), static_cast<btScalar>(h.y()), static_cast<btScalar>(h.z())));
            box->setMargin(static_cast<btScalar>(std::min(0.04, 0.1 * h.minCoeff())));
            const double density = def.density.value_or(1000.0);
            const double mass = def.mass.value_or(density * 8 * h.x() * h.y() * h.z());
            btVector3 inertia(static_cast<btScalar>(mass * (h.y() * h.y() + h.z() * h.z()) / 3),
                              static_cast<btScalar>(mass * (h.x() * h.x() + h.z() * h.z()) / 3),
                              static_cast<btScalar>(mass * (h.x() * h.x() + h.y() * h.y()) / 3));
            btRigidBody::btRigidBodyConstructionInfo ci(static_cast<btScalar>(mass), nullptr, box.get(), inertia);
            ci.m_linearSleepingThreshold = static_cast<btScalar>(s.sleepLinearVelocity);
            ci.m_angularSleepingThreshold = static_cast<btScalar>(s.sleepAngularVelocity);
            shapes.push_back(std::move(box));
            bodies.push_back(std::make_unique<btRigidBody>(ci));
            body = bodies.back().get();
            body->setFlags(BT_DISABLE_WORLD_GRAVITY | BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
            const double core = h.minCoeff();
            body->setCcdMotionThreshold(static_cast<btScalar>(0.5 * core));
            body->setCcdSweptSphereRadius(static_cast<btScalar>(0.9 * core));
        }
        btTransform xf;
        xf.setIdentity();
        xf.setOrigin(btVector3(static_cast<btScalar>(def.position.x()), static_cast<btScalar>(def.position.y()),
                               static_cast<btScalar>(def.position.z())));
        body->setWorldTransform(xf);
        body->setFriction(friction);
        body->setRestitution(restitution);
        world->addRigidBody(body, btBroadphaseProxy::AllFilter, btBroadphaseProxy::AllFilter);
        if (def.type == BodyType::Dynamic) body->setGravity(gravity);
    }
    const long long steps = std::llround(entry.duration / s.timeStep);
    const auto h = static_cast<btScalar>(s.timeStep);
    const double start = cpuSeconds();
    for (long long i = 0; i < steps; ++i) world->stepSimulation(h, 1, h);
    const double perStep = (cpuSeconds() - start) / static_cast<double>(steps);
    finalHeight = 0;
    for (const auto& b : bodies) finalHeight += b->getWorldTransform().getOrigin().y();
    for (const auto& b : bodies) world->removeRigidBody(b.get());
    return perStep;
}

void BM_BulletWrapperOverhead(benchmark::State& state) {
    const CatalogueScene& entry = catalogueScene("box_grid_1000");
    const int rounds = static_cast<int>(state.range(0));
    double best[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};
    double heights[3] = {0, 0, 0};
    for (auto _ : state) {
        for (int r = 0; r < rounds; ++r) {
            best[0] = std::min(best[0], runAnyphys(entry, true, heights[0]));
            best[1] = std::min(best[1], runAnyphys(entry, false, heights[1]));
            best[2] = std::min(best[2], runDirect(entry, heights[2]));
        }
        state.SetIterationTime(best[0]);
    }
    state.counters["anyphys_ms"] = 1000 * best[0];
    state.counters["anyphys_noevents_ms"] = 1000 * best[1];
    state.counters["direct_ms"] = 1000 * best[2];
    state.counters["overhead_pct"] = 100 * (best[0] / best[2] - 1);
    state.counters["overhead_noevents_pct"] = 100 * (best[1] / best[2] - 1);
    // Mean box height at the end, per run: the same physics gives the same pile (to float noise).
    const double n = static_cast<double>(entry.scene.bodies.size() - 1);
    state.counters["mean_y_anyphys"] = heights[0] / n;
    state.counters["mean_y_noevents"] = heights[1] / n;
    state.counters["mean_y_direct"] = heights[2] / n;
}

}  // namespace

BENCHMARK(BM_BulletWrapperOverhead)->Arg(3)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
