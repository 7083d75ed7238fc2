#pragma once
// `anyphys report` input: the rows of one or more results CSVs (`compare --out`) as typed records.
// Several files are concatenated; a column one file lacks reads as an empty cell.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace anyphys::cli {

/// A number cell: empty where the metric does not apply; nan or inf after a blow-up.
using Number = std::optional<double>;

struct ReportRow {
    std::string file;        ///< the results file it came from, for messages
    std::size_t row = 0;     ///< 1-based data row in that file
    std::string scene, backend;
    std::string status;      ///< ok / unsupported / failed ("ok" when the file has no status)
    std::string reason;
    std::map<std::string, std::string> settings;  ///< every setting column (swept axes) -> its cell
    std::string effectOff;   ///< "" when the row does not switch effects
    std::string effects;     ///< the effects the run simulated, "gravity+events" ("" when unknown)
    std::string integrator, solver;
    Number timeStep, iterations, steps;
    Number msPerSimSecond, msPerStepMedian, msPerStepMin, posError, sceneScale, errorTarget, machineLoad;
    std::vector<Number> otherMetrics;  ///< vel/drift/penetration/gap/check value: only for blow-up tests
    std::optional<bool> checkOk;
    std::string version, commit;

    bool ok() const { return status == "ok"; }
    /// error_target, else 1 % of scene_scale, else none.
    Number target() const;
};

struct ReportData {
    std::vector<std::string> files;
    std::vector<std::string> settingColumns;  ///< setting columns of all files, first-seen order
    std::vector<ReportRow> rows;
};

/// Reads every file. Throws anyphys::Error naming the file when one cannot be read, lacks a
/// required column (scene, backend, ms_per_sim_second) or holds a non-number in a number column.
ReportData loadReportData(const std::vector<std::string>& files);

/// The one number format of the report pages and stdout: %.3g.
std::string formatNumber(double value);
/// formatNumber, or "-" for an empty cell.
std::string formatNumber(const Number& value);

}  // namespace anyphys::cli
