// Running and measuring one (scene, backend, integrator) combination.
#include "compare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cli.hpp"
#include "scene_measures.hpp"

namespace anyphys::cli {

ComboResult runCombo(const CatalogueScene& entry, const BackendInfo& backend, Integrator integrator) {
    ComboResult result;
    result.scene = entry.name;
    result.backend = backend.name;
    result.integrator = std::string(toString(integrator));
    const auto refuse = [&result](ComboResult::Status status, std::string reason) {
        result.status = status;
        result.reason = std::move(reason);
        return result;
    };

    WorldSettings settings = entry.scene.settings;
    settings.backend = backend.name;
    settings.integrator = integrator;
    if (auto missing = missingFor(backend.capabilities, settings, entry.scene); !missing.empty())
        return refuse(ComboResult::Status::Unsupported, join(missing));

    // The backend may still refuse something its capability table cannot express.
    std::unique_ptr<World> world;
    std::vector<Body> bodies;
    try {
        world = std::make_unique<World>(settings, entry.scene.materials);
        bodies = createSceneObjects(*world, entry.scene).bodies;
    } catch (const Error& e) {
        return refuse(ComboResult::Status::Unsupported, e.what());
    }

    result.steps = std::llround(entry.duration / settings.timeStep);
    const double energy0 = mechanicalEnergy(*world, bodies, entry.scene);
    const double momentum0 = angularMomentumNorm(bodies);
    std::unique_ptr<SceneProbe> probe = entry.check ? entry.check->makeProbe() : nullptr;
    if (probe) probe->observe(world->time(), bodyStates(bodies));
    try {
        // Only the stepping is timed, not the probe's observations.
        std::chrono::steady_clock::duration stepping{};
        for (long long i = 0; i < result.steps; ++i) {
            const auto start = std::chrono::steady_clock::now();
            world->step();
            stepping += std::chrono::steady_clock::now() - start;
            if (probe) probe->observe(world->time(), bodyStates(bodies));
        }
        result.wallMs = std::chrono::duration<double, std::milli>(stepping).count();
    } catch (const Error& e) {
        return refuse(ComboResult::Status::Failed, e.what());
    }

    if (entry.reference) {
        double worst = 0.0;
        bool any = false;
        for (const Body& body : bodies) {
            if (auto exact = entry.reference(body.name(), world->time())) {
                const double error = (body.position() - exact->position).norm();
                if (!(error <= worst)) worst = error;  // written so a NaN (blow-up) is kept, not hidden
                any = true;
            }
        }
        if (any) result.positionError = worst;
    }
    if (entry.conservesEnergy)
        result.energyDrift = relativeChange(energy0, mechanicalEnergy(*world, bodies, entry.scene));
    if (entry.conservesAngularMomentum)
        result.angularMomentumDrift = relativeChange(momentum0, angularMomentumNorm(bodies));
    if (probe) {
        const CheckVerdict verdict = judgeCheck(*entry.check, backend.capabilities, probe->value());
        result.checkValue = verdict.value;
        result.checkPassed = verdict.passed;
        result.ceiling = verdict.ceiling;
        result.overCeiling = verdict.overCeiling;
        result.knownDeviation = verdict.knownDeviation;
    }
    return result;
}

}  // namespace anyphys::cli
