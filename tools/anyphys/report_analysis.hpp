#pragma once
// `anyphys report` analysis of one scene's rows: what each section of the report shows, computed
// once so that the pages, the plots and stdout agree.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "report_data.hpp"

namespace anyphys::cli {

/// Rows of one backend / solver (/ integrator) in the error-against-cost plot, by cost.
struct CostCurve {
    std::string label;
    std::vector<const ReportRow*> rows;
};

/// pos_error against timeStep for one group of rows that differ only in timeStep.
struct ConvergenceLine {
    std::string label;
    std::vector<const ReportRow*> rows;  ///< plottable (finite error > 0), by timeStep
    std::optional<double> order;         ///< least-squares slope of log error on log timeStep
    double intercept = 0;                ///< of that fit (natural logs)
    double fitFrom = 0, fitTo = 0;       ///< the fitted steps' range
    std::size_t fitPoints = 0;           ///< points used in the fit
    std::size_t belowFloor = 0;          ///< points left out: error below the rounding floor
    std::optional<int> theoretical;      ///< of the integrator, when the rows name one
};

enum class Stability { stable, drifted, exploded };
const char* toString(Stability s);

/// One backend's classes over timeStep x iterations (an empty value: the scene's own).
struct StabilityMap {
    std::string backend;
    std::vector<Number> steps, iterations;  ///< the axes, ascending (scene's own first)
    struct Cell {
        std::size_t x = 0, y = 0;
        Stability cls = Stability::stable;
        std::size_t rows = 0;  ///< configurations in the cell; the worst class is shown
    };
    std::vector<Cell> cells;
};

/// The cheapest configuration per backend meeting pos_error <= level x scene_scale.
struct CheapestAtLevel {
    double level = 0;
    std::vector<std::pair<std::string, const ReportRow*>> perBackend;  ///< nullptr: none
};

/// Time per step with each effect off relative to effectOff=none, for one backend and one set of
/// the other settings: ms_per_step_min where every row has it (the least disturbed of the timed
/// runs: the ratio of two minima is steadier than of two medians), else ms_per_step_median.
struct EffectCost {
    std::string backend, settings;
    const ReportRow* baseline = nullptr;
    std::vector<Number> ratio;  ///< per SceneReport::effects; empty where not measured
};

struct SceneReport {
    std::string scene;
    std::string stem;  ///< file-name-safe, unique among the scenes
    Number scale;      ///< scene_scale
    std::vector<const ReportRow*> rows;
    std::vector<std::string> backends;  ///< first-seen order
    std::vector<std::string> varying;   ///< setting columns with more than one value here

    std::size_t okRows = 0;
    std::vector<std::pair<std::string, std::size_t>> notOk;  ///< "status: reason" -> count

    std::vector<std::pair<std::string, const ReportRow*>> headline;  ///< per backend; nullptr: none
    std::map<std::string, std::string> notRun;  ///< backend -> reason, when none of its rows ran
    std::vector<CostCurve> costCurves;
    std::vector<const ReportRow*> pareto;  ///< by cost
    std::size_t unplottedCost = 0;         ///< ok rows without a positive finite error and cost
    std::vector<ConvergenceLine> convergence;
    bool hasConvergence = false;           ///< some line has two or more time steps
    std::vector<StabilityMap> stability;   ///< empty: one timeStep and one iterations value
    std::vector<CheapestAtLevel> cheapest;
    std::vector<std::string> effects;      ///< effects switched off in some row (not "none")
    std::vector<EffectCost> effectCosts;
    bool effectTimingIsMin = false;        ///< the ratios compare ms_per_step_min (else the median)
};

/// Error levels of the cheapest-configuration table, as fractions of scene_scale.
inline constexpr double kCheapestLevels[] = {1e-2, 1e-3, 1e-4};
/// Rounding, not truncation: an error below double epsilon x scene_scale x steps, the
/// worst case of one rounding per step adding up, is left out of the fit. Rows without `steps`
/// use 1e-12 x scene_scale (10^4 steps).
inline constexpr double kDoubleEpsilon = 0x1p-52;
inline constexpr double kFloorStepsUnknown = 1e4;
/// That floor for one row, in m.
double roundingFloor(const ReportRow& row, const Number& scale);

/// One SceneReport per scene, in first-seen order.
std::vector<SceneReport> analyse(const ReportData& data);

/// The row's settings that vary in its scene, "integrator=rk4 timeStep=0.0167" (numbers %.3g);
/// `skip` names a setting to leave out.
std::string describeSettings(const ReportRow& row, const std::vector<std::string>& varying,
                             const std::string& skip = "");
/// "native integrator=rk4 ..." or "native (scene settings)".
std::string describeConfig(const ReportRow& row, const std::vector<std::string>& varying);
Stability classify(const ReportRow& row);
/// The order of accuracy of an integrator of that name.
std::optional<int> theoreticalOrder(const std::string& integrator);

}  // namespace anyphys::cli
