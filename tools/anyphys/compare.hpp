#pragma once
// One cell of `anyphys compare`: a catalogue scene run on one backend with one integrator, and
// what was measured (accuracy against the analytic answer, conservation, wall time).
#include <optional>
#include <string>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"

namespace anyphys::cli {

struct ComboResult {
    enum class Status {
        Ok,
        Unsupported,  ///< the backend refused the scene or a setting (reason says what)
        Failed,       ///< the backend accepted it but threw while stepping
    };

    std::string scene;
    std::string backend;
    std::string integrator;
    Status status = Status::Ok;
    std::string reason;  ///< why unsupported / failed
    long long steps = 0;
    double wallMs = 0.0;                        ///< steady_clock time around the stepping only
    std::optional<double> positionError;        ///< m, max over bodies at the end; scenes with a reference
    std::optional<double> angularMomentumDrift; ///< (|L_end| - |L_0|) / |L_0|; scenes conserving L
    std::optional<double> energyDrift;          ///< (E_end - E_0) / |E_0|; scenes conserving energy
    std::optional<double> checkValue;           ///< the scene's own measure (CatalogueScene::check)
    bool checkPassed = false;                   ///< checkValue within the check's tolerance
    bool knownDeviation = false;                ///< failed, and the backend declares that criterion missed
    std::optional<double> ceiling;              ///< the backend's declared ceiling for the criterion, if any
    bool overCeiling = false;                   ///< declared, but the value is worse than the ceiling
};

/// Runs `scene` for its duration on `backend` with `integrator`. Never throws for a refusal:
/// that becomes an Unsupported result naming the reason.
ComboResult runCombo(const CatalogueScene& scene, const BackendInfo& backend, Integrator integrator);

}  // namespace anyphys::cli
