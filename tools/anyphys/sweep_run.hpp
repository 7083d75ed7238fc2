#pragma once
// Running one configuration of a sweep: a catalogue scene on a backend with one value of every
// axis, timed over repeated runs and measured against a reference motion.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"
#include "scene_measures.hpp"
#include "sweep_axes.hpp"

namespace anyphys::cli {

/// One cell of the grid. `id` is its index in the full, unsharded list.
struct SweepConfig {
    std::size_t id = 0;
    const CatalogueScene* scene = nullptr;
    const BackendInfo* backend = nullptr;
    std::vector<std::string> values;  ///< one per axis, normalised (SweepAxis::values)
    std::string label;                ///< the axis values as typed, "timeStep=1/60 integrator=rk4"
};

/// What one configuration gave. Empty optionals are metrics that do not apply.
struct SweepRecord {
    std::string status = "ok";  ///< ok, unsupported (not run), failed (threw while stepping)
    std::string reason;
    WorldSettings settings;     ///< as run: the backend's defaults filled in
    int repeat = 0;
    long long steps = 0;
    std::optional<double> msPerStepMin, msPerStepMedian, msPerSimSecond, machineLoad;
    std::optional<double> posError, velError, posErrorVsEngines, sceneScale, errorTarget;
    std::string errorReference;  ///< closed_form, converged or ""
    std::string effects;         ///< the effects the world simulated, "gravity+events" ("" when not run)
    std::optional<double> energyDrift, momentumDrift, maxPenetration, jointGap;
    std::optional<CheckVerdict> check;
};

/// The estimated cost of a configuration, to balance shards: steps x bodies x repeat x substeps x
/// iterations (the swept values, else the scene's, else the backend's defaults). Depends only on
/// the command line and the built backends, so every shard computes the same estimate.
double configCost(const SweepConfig& config, const std::vector<SweepAxis>& axes, int repeat);

/// Runs configurations; keeps each scene x backend's reference motion, run once when first needed.
class SweepRunner {
public:
    SweepRunner(std::vector<SweepAxis> axes, int repeat);
    SweepRecord run(const SweepConfig& config);

private:
    /// The end state of a converged reference run of one engine, and the scene's scale.
    struct Reference {
        bool ran = false;
        std::vector<Vec3> positions, velocities;  ///< per scene body, at the end
        double maxDisplacement = 0.0;             ///< m, any dynamic body over the run
    };
    const Reference& converged(const CatalogueScene& scene, const BackendInfo& backend);
    double closedFormDisplacement(const CatalogueScene& scene);

    std::vector<SweepAxis> axes_;
    int repeat_;
    std::optional<BackendInfo> native_;
    std::map<std::pair<std::string, std::string>, Reference> references_;
    std::map<std::string, double> closedFormDisplacements_;
};

}  // namespace anyphys::cli
