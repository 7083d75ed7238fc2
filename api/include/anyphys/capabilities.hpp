#pragma once
// Machine-readable description of what a backend honours. The layer checks every request
// against it; `anyphys backends --json` prints it.
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <string>
#include <vector>

#include "anyphys/effects.hpp"
#include "anyphys/enums.hpp"

namespace anyphys {

/// A backend option (a WorldSettings::backendOptions key): what it does and the values it takes.
/// World's constructor refuses a value outside [min, max], or a fraction for an integer option,
/// before the backend reads it: a count read from 1e12 or -3 would otherwise be cast or clamped
/// in silence.
struct BackendOption {
    std::string name;
    std::string meaning;  ///< one line, with the default
    double min = 0.0;
    double max = std::numeric_limits<double>::infinity();  ///< inclusive; infinity: no upper bound
    bool integer = false;                                  ///< a count or a 0 / 1 switch
    /// The rule in words, for errors and listings: "an integer in [0, 1]", "a number >= 0".
    std::string allowed() const;
};

/// When the user force callback is evaluated.
enum class ForceEvaluation {
    PerStage,  ///< at every derivative evaluation of the integrator (state-dependent forces stay high order)
    PerStep,   ///< once per step, held constant across it
};

struct Capabilities {
    int dimensions = 3;                        ///< 3, or 2 for planar-only engines
    bool planar = false;                       ///< can run planar (XY) worlds
    /// The engine's unit roundoff: the relative error of one rounding in its arithmetic. The layer
    /// is double throughout; an engine that steps in float (Box2D 2.4) rounds every state it
    /// returns to about 6e-8 relative, so "exact" results agree only to that.
    double unitRoundoff = 0x1p-53;
    std::set<ShapeType> shapes;                ///< shape types it can simulate
    std::set<BodyType> bodyTypes;              ///< body types it can simulate
    std::set<std::string> jointTypes;          ///< joint type names
    Effects effects;                           ///< effects it can simulate
    std::set<Integrator> integrators;          ///< selectable integrators
    std::set<Solver> solvers;                  ///< selectable constraint solvers
    Solver defaultSolver = Solver::ProjectedGaussSeidel;  ///< used when WorldSettings::solver is unset
    int defaultSubsteps = 1;                   ///< used when WorldSettings::substeps is unset
    int defaultIterations = 10;                ///< used when WorldSettings::iterations is unset
    std::set<GyroscopicMode> gyroscopicModes;  ///< per-body gyroscopic modes honoured
    ForceEvaluation forceEvaluation = ForceEvaluation::PerStep;
    bool contactImpulses = false;              ///< contact events carry real normal impulses
    std::set<std::string> queries;             ///< "raycast", "overlap"
    int maxConvexVertices = 0;                 ///< largest convex hull accepted (0: no limit)
    /// kg: the lightest and the heaviest dynamic body the engine holds up on its contacts (0: no
    /// limit within the layer's kMinMass and kMaxMass). Measured per backend, every solver: a
    /// box resting on the ground for 2 s, masses by decade; outside the range it sank through or
    /// went non-finite. A body outside is refused (strict) or warned about (lenient).
    double lightestBody = 0.0;
    double heaviestBody = 0.0;
    /// Pairs of (primitive) shape types this backend cannot collide, each stored with the smaller
    /// type first. A world whose content would pair them is refused (strict) or warned about
    /// (lenient) when the second body arrives.
    std::set<std::pair<ShapeType, ShapeType>> missingShapePairs;
    /// Individual def / settings fields honoured, by their scene-file path, e.g.
    /// "settings.substeps", "body.gravityScale". A field not listed is ignored by this backend.
    std::set<std::string> parameters;
    /// Backend options (WorldSettings::backendOptions keys), each with its meaning and range.
    std::vector<BackendOption> options;
    /// Contract criteria this backend misses at default settings, by criterion id (e.g.
    /// "stack10.top_drift"), each with the measured value, the reason and the settings at which
    /// it passes, if any. The contract suite reports these visibly instead of failing, and fails
    /// if a declared deviation no longer occurs (so the table stays true).
    std::map<std::string, std::string> knownDeviations;
    /// Ceilings of declared deviations, by criterion id: the worst value of the criterion's
    /// measure (in the test's unit) the deviation may reach. A miss beyond it fails, so a
    /// deviation that grows is caught, not reported as known.
    std::map<std::string, double> deviationCeilings;
};

}  // namespace anyphys
