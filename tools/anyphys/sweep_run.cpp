// One sweep configuration: an untimed, measured warm-up run, then `repeat` timed runs.
#include "sweep_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>

#include "cli.hpp"
#include "run_observers.hpp"

namespace anyphys::cli {
namespace {

/// The 1-minute load average, so a slow row can be told from a busy machine.
std::optional<double> loadAverage() {
    std::ifstream in("/proc/loadavg");
    double load = 0.0;
    if (in >> load) return load;
    return std::nullopt;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// Largest diameter of a dynamic body's bounding sphere, m: the size of what moves.
double largestBodySize(const Scene& scene) {
    double size = 0.0;
    for (const BodyDef& def : scene.bodies)
        if (def.type == BodyType::Dynamic) size = std::max(size, 2.0 * boundingRadius(def.shape));
    return size;
}

/// The effects a world derives from the scene's content on this backend (settings.effects unset).
Effects derivedEffects(const CatalogueScene& entry, WorldSettings settings) {
    settings.effects.reset();
    World world(settings, entry.scene.materials);
    createSceneObjects(world, entry.scene);
    return world.activeEffects();
}

/// Keeps the largest distance any dynamic body moved from its start.
struct DisplacementWatch {
    std::vector<Vec3> start;
    double worst = 0.0;
    void observe(const std::vector<Body>& bodies) {
        if (start.empty())
            for (const Body& b : bodies) start.push_back(b.position());
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            if (bodies[i].type() != BodyType::Dynamic) continue;
            const double d = (bodies[i].position() - start[i]).norm();
            if (!(d <= worst)) worst = d;
        }
    }
};

/// Rank of an integrator's accuracy: order first, then a symplectic method above a
/// non-symplectic one of the same order (it keeps the energy of a long run bounded).
int integratorRank(Integrator integrator) {
    switch (integrator) {
        case Integrator::ExplicitEuler: return 0;
        case Integrator::SemiImplicitEuler: return 1;
        case Integrator::Midpoint: return 2;
        case Integrator::Verlet: return 3;
        case Integrator::RK4: return 4;
    }
    return 0;
}

/// The larger of `worst` and `value`, keeping a NaN (a blow-up) visible.
void keepWorst(std::optional<double>& worst, double value) {
    if (!worst || !(value <= *worst)) worst = value;
}

}  // namespace

double configCost(const SweepConfig& config, const std::vector<SweepAxis>& axes, int repeat) {
    WorldSettings s = config.scene->scene.settings;
    for (std::size_t i = 0; i < axes.size(); ++i) {
        const std::string& name = axes[i].name;
        if (name == "timeStep") s.timeStep = axisNumber(config.values[i]);
        if (name == "substeps") s.substeps = static_cast<int>(axisNumber(config.values[i]));
        if (name == "iterations") s.iterations = static_cast<int>(axisNumber(config.values[i]));
    }
    s = withBackendDefaults(s, config.backend->capabilities);
    const double steps = static_cast<double>(std::max<long long>(1, std::llround(config.scene->duration / s.timeStep)));
    const auto bodies = static_cast<double>(config.scene->scene.bodies.size());
    return steps * bodies * repeat * static_cast<double>(*s.substeps) * static_cast<double>(*s.iterations);
}

SweepRunner::SweepRunner(std::vector<SweepAxis> axes, int repeat) : axes_(std::move(axes)), repeat_(repeat) {
    for (const BackendInfo& b : availableBackends())
        if (b.name == "native") native_ = b;  // the engines' common yardstick, when built
}

SweepRecord SweepRunner::run(const SweepConfig& config) {
    const CatalogueScene& entry = *config.scene;
    const Capabilities& caps = config.backend->capabilities;
    SweepRecord r;
    r.repeat = repeat_;
    r.machineLoad = loadAverage();
    const auto refuse = [&r](std::string status, std::string reason) {
        r.status = std::move(status);
        r.reason = std::move(reason);
        return r;
    };

    WorldSettings settings = entry.scene.settings;
    settings.backend = config.backend->name;
    settings.workers = 1;  // one thread: the cost of the method, not of the machine's cores
    std::optional<std::string> refusal;
    for (std::size_t i = 0; i < axes_.size() && !refusal; ++i) {
        try {
            refusal = applyAxisValue(axes_[i].name, config.values[i], caps, settings,
                                     [&] { return derivedEffects(entry, settings); });
        } catch (const Error& e) {
            refusal = e.what();  // the world refused the scene while deriving its effects
        }
    }
    r.settings = withBackendDefaults(settings, caps);
    r.steps = std::max<long long>(1, std::llround(entry.duration / settings.timeStep));
    if (refusal) return refuse("unsupported", *refusal);
    if (auto missing = missingFor(caps, settings, entry.scene); !missing.empty())
        return refuse("unsupported", join(missing));

    // The warm-up run, untimed, is the measured one: every backend is deterministic, so the
    // timed repeats below follow the same states.
    std::unique_ptr<World> world;
    std::vector<Body> bodies;
    try {
        world = std::make_unique<World>(settings, entry.scene.materials);
        bodies = createSceneObjects(*world, entry.scene).bodies;
    } catch (const Error& e) {
        return refuse("unsupported", e.what());
    }
    r.settings = world->settings();
    r.effects = join(world->activeEffects().names(), "+");
    const double energy0 = mechanicalEnergy(*world, bodies, entry.scene);
    const double momentum0 = angularMomentumNorm(bodies);
    std::unique_ptr<SceneProbe> probe = entry.check ? entry.check->makeProbe() : nullptr;
    JointGapWatch gaps(entry.scene, bodyStates(bodies));
    PenetrationWatch penetration(*world);
    DisplacementWatch moved;
    moved.observe(bodies);
    if (probe) probe->observe(world->time(), bodyStates(bodies));
    try {
        for (long long i = 0; i < r.steps; ++i) {
            world->step();
            const std::vector<BodyState> states = bodyStates(bodies);
            if (probe) probe->observe(world->time(), states);
            gaps.observe(states);
            penetration.observe(*world);
            moved.observe(bodies);
        }
    } catch (const Error& e) {
        return refuse("failed", e.what());
    }

    // Timed runs: a fresh world each, built outside the clock; only the stepping is timed.
    std::vector<double> msPerStep;
    try {
        for (int k = 0; k < repeat_; ++k) {
            World timed(settings, entry.scene.materials);
            createSceneObjects(timed, entry.scene);
            const auto start = std::chrono::steady_clock::now();
            for (long long i = 0; i < r.steps; ++i) timed.step();
            const auto elapsed = std::chrono::steady_clock::now() - start;
            msPerStep.push_back(std::chrono::duration<double, std::milli>(elapsed).count() / static_cast<double>(r.steps));
        }
    } catch (const Error& e) {
        return refuse("failed", e.what());
    }
    if (!msPerStep.empty()) {
        r.msPerStepMin = *std::min_element(msPerStep.begin(), msPerStep.end());
        r.msPerStepMedian = median(msPerStep);
        r.msPerSimSecond = *r.msPerStepMedian / settings.timeStep;
    }

    if (entry.conservesEnergy) r.energyDrift = relativeChange(energy0, mechanicalEnergy(*world, bodies, entry.scene));
    if (entry.conservesAngularMomentum) r.momentumDrift = relativeChange(momentum0, angularMomentumNorm(bodies));
    r.maxPenetration = penetration.value();
    r.jointGap = gaps.value();
    if (probe) r.check = judgeCheck(*entry.check, caps, probe->value());

    // Accuracy: against the closed form where the scene has one, else the engine's converged run.
    double displacement = moved.worst;
    if (entry.reference) {
        for (const Body& body : bodies)
            if (auto exact = entry.reference(body.name(), world->time())) {
                keepWorst(r.posError, (body.position() - exact->position).norm());
                keepWorst(r.velError, (body.linearVelocity() - exact->linearVelocity).norm());
            }
        if (r.posError) r.errorReference = "closed_form";
        displacement = closedFormDisplacement(entry);
    } else {
        const auto againstRun = [&bodies](const Reference& ref, std::optional<double>& pos, std::optional<double>* vel) {
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                if (bodies[i].type() != BodyType::Dynamic) continue;
                keepWorst(pos, (bodies[i].position() - ref.positions[i]).norm());
                if (vel) keepWorst(*vel, (bodies[i].linearVelocity() - ref.velocities[i]).norm());
            }
        };
        if (const Reference& ref = converged(entry, *config.backend); ref.ran) {
            againstRun(ref, r.posError, &r.velError);
            r.errorReference = "converged";
            displacement = ref.maxDisplacement;
        }
        if (native_)
            if (const Reference& ref = converged(entry, *native_); ref.ran) againstRun(ref, r.posErrorVsEngines, nullptr);
    }
    r.sceneScale = std::max(largestBodySize(entry.scene), displacement);
    r.errorTarget = 1e-2 * *r.sceneScale;
    return r;
}

const SweepRunner::Reference& SweepRunner::converged(const CatalogueScene& entry, const BackendInfo& backend) {
    const auto key = std::make_pair(entry.name, backend.name);
    if (const auto it = references_.find(key); it != references_.end()) return it->second;
    Reference& ref = references_[key];
    const Capabilities& caps = backend.capabilities;

    // Finer than every configuration of the grid: half its smallest step, its most substeps and
    // iterations (or the backend's defaults, whichever is larger).
    WorldSettings s = entry.scene.settings;
    s.backend = backend.name;
    s.workers = 1;
    int substeps = caps.defaultSubsteps, iterations = caps.defaultIterations;
    for (const SweepAxis& axis : axes_) {
        if (axis.name == "timeStep") s.timeStep = axisNumber(axis.values.front());  // the grid's steps, not the scene's
        for (const std::string& v : axis.values) {
            if (axis.name == "timeStep") s.timeStep = std::min(s.timeStep, axisNumber(v));
            if (axis.name == "substeps") substeps = std::max(substeps, static_cast<int>(axisNumber(v)));
            if (axis.name == "iterations") iterations = std::max(iterations, static_cast<int>(axisNumber(v)));
        }
    }
    s.timeStep /= 2;
    // The most accurate integrator the grid tries that this engine offers; the scene's own when
    // the grid does not sweep integrators (every row then runs it).
    std::optional<Integrator> best;
    for (const SweepAxis& axis : axes_)
        if (axis.name == "integrator")
            for (const std::string& v : axis.values) {
                const Integrator candidate = *fromString<Integrator>(v);
                if (caps.integrators.contains(candidate) && (!best || integratorRank(candidate) > integratorRank(*best)))
                    best = candidate;
            }
    if (best) s.integrator = *best;
    if (caps.parameters.contains("settings.substeps")) s.substeps = substeps;
    if (caps.parameters.contains("settings.iterations")) s.iterations = iterations;
    if (!missingFor(caps, s, entry.scene).empty()) return ref;
    try {
        World world(s, entry.scene.materials);
        const std::vector<Body> bodies = createSceneObjects(world, entry.scene).bodies;
        DisplacementWatch moved;
        moved.observe(bodies);
        const long long steps = std::max<long long>(1, std::llround(entry.duration / s.timeStep));
        for (long long i = 0; i < steps; ++i) {
            world.step();
            moved.observe(bodies);
        }
        for (const Body& b : bodies) {
            ref.positions.push_back(b.position());
            ref.velocities.push_back(b.linearVelocity());
        }
        ref.maxDisplacement = moved.worst;
        ref.ran = true;
    } catch (const Error&) {
        ref.ran = false;  // no reference: the rows' error columns stay empty
    }
    return ref;
}

double SweepRunner::closedFormDisplacement(const CatalogueScene& entry) {
    if (const auto it = closedFormDisplacements_.find(entry.name); it != closedFormDisplacements_.end()) return it->second;
    constexpr int kSamples = 1000;
    double worst = 0.0;
    for (const BodyDef& def : entry.scene.bodies) {
        const auto start = entry.reference(def.name, 0.0);
        if (!start) continue;
        for (int i = 1; i <= kSamples; ++i)
            if (const auto at = entry.reference(def.name, entry.duration * i / kSamples))
                worst = std::max(worst, (at->position - start->position).norm());
    }
    return closedFormDisplacements_[entry.name] = worst;
}

}  // namespace anyphys::cli
