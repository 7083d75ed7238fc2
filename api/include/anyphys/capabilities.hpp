#pragma once
// Machine-readable description of what a backend honours. The layer checks every request
// against it; `anyphys backends --json` prints it.
#include <set>
#include <string>
#include <vector>

#include "anyphys/effects.hpp"
#include "anyphys/enums.hpp"

namespace anyphys {

/// When the user force callback is evaluated.
enum class ForceEvaluation {
    PerStage,  ///< at every derivative evaluation of the integrator (state-dependent forces stay high order)
    PerStep,   ///< once per step, held constant across it
};

struct Capabilities {
    int dimensions = 3;                        ///< 3, or 2 for planar-only engines
    bool planar = false;                       ///< can run planar (XY) worlds
    std::set<ShapeType> shapes;                ///< shape types it can simulate
    std::set<BodyType> bodyTypes;              ///< body types it can simulate
    std::set<std::string> jointTypes;          ///< joint type names
    Effects effects;                           ///< effects it can simulate
    std::set<Integrator> integrators;          ///< selectable integrators
    std::set<Solver> solvers;                  ///< selectable constraint solvers
    std::set<GyroscopicMode> gyroscopicModes;  ///< per-body gyroscopic modes honoured
    ForceEvaluation forceEvaluation = ForceEvaluation::PerStep;
    bool contactImpulses = false;              ///< contact events carry real normal impulses
    std::set<std::string> queries;             ///< "raycast", "overlap"
    int maxConvexVertices = 0;                 ///< largest convex hull accepted (0: no limit)
    /// Individual def / settings fields honoured, by their scene-file path, e.g.
    /// "settings.substeps", "body.gravityScale". A field not listed is ignored by this backend.
    std::set<std::string> parameters;
    /// Backend options (WorldSettings::backendOptions keys) with a one-line meaning each.
    std::vector<std::pair<std::string, std::string>> options;
};

}  // namespace anyphys
