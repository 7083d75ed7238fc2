// Typed rows for `anyphys report`: which columns are settings, and number cells parsed once so that
// every page formats the same parsed value.
#include "report_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "anyphys/error.hpp"
#include "results_csv.hpp"

namespace anyphys::cli {
namespace {

/// Columns that describe a run's outcome or bookkeeping; every other column is a swept setting.
const std::set<std::string>& nonSettingColumns() {
    static const std::set<std::string> names{
        "config_id", "scene", "backend", "sweep", "status", "reason", "repeat", "steps", "effects", "ms_per_step_min",
        "ms_per_step_median", "ms_per_sim_second", "machine_load", "pos_error", "vel_error", "error_reference",
        "pos_error_vs_engines", "scene_scale", "error_target", "energy_drift", "momentum_drift", "max_penetration",
        "joint_gap", "check_label", "check_value", "check_ok", "check_known_deviation", "config_count", "shard",
        "grid", "anyphys_version", "commit"};
    return names;
}

/// Parses one number cell; the writer spells blow-ups "nan", "inf", "-inf", which strtod reads.
Number parseNumber(const ReportRow& row, const std::string& column, const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size())
        throw Error(row.file + ": row " + std::to_string(row.row) + ": column " + column + " holds \"" + text +
                    "\", not a number");
    return value;
}

std::optional<bool> parseBool(const ReportRow& row, const std::string& column, const std::string& text) {
    if (text.empty()) return std::nullopt;
    if (text == "true") return true;
    if (text == "false") return false;
    throw Error(row.file + ": row " + std::to_string(row.row) + ": column " + column + " holds \"" + text +
                "\", not true or false");
}

void readFile(const std::string& path, ReportData& data) {
    const ResultsTable table = readResultsCsv(path);
    for (const char* required : {"scene", "backend", "ms_per_sim_second"})
        if (table.column(required) < 0)
            throw Error(path + ": no column \"" + std::string(required) +
                        "\" (not a results file of `anyphys compare --out`?)");
    for (const std::string& column : table.columns)
        if (!nonSettingColumns().count(column) &&
            std::find(data.settingColumns.begin(), data.settingColumns.end(), column) == data.settingColumns.end())
            data.settingColumns.push_back(column);

    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        ReportRow row;
        row.file = path;
        row.row = r + 1;
        const auto cell = [&](const char* name) -> const std::string& { return table.cell(r, name); };
        const auto number = [&](const char* name) { return parseNumber(row, name, cell(name)); };
        row.scene = cell("scene");
        row.backend = cell("backend");
        row.status = cell("status").empty() ? "ok" : cell("status");
        row.reason = cell("reason");
        row.effects = cell("effects");
        for (const std::string& column : table.columns)
            if (!nonSettingColumns().count(column)) row.settings[column] = table.rows[r][table.column(column)];
        row.effectOff = cell("effectOff");
        row.integrator = cell("integrator");
        row.solver = cell("solver");
        row.timeStep = number("timeStep");
        row.iterations = number("iterations");
        row.steps = number("steps");
        row.msPerSimSecond = number("ms_per_sim_second");
        row.msPerStepMedian = number("ms_per_step_median");
        row.msPerStepMin = number("ms_per_step_min");
        row.posError = number("pos_error");
        row.sceneScale = number("scene_scale");
        row.errorTarget = number("error_target");
        row.machineLoad = number("machine_load");
        for (const char* name : {"vel_error", "energy_drift", "momentum_drift", "max_penetration", "joint_gap",
                                 "check_value", "ms_per_step_min"})
            row.otherMetrics.push_back(number(name));
        row.checkOk = parseBool(row, "check_ok", cell("check_ok"));
        row.version = cell("anyphys_version");
        row.commit = cell("commit");
        data.rows.push_back(std::move(row));
    }
}

}  // namespace

Number ReportRow::target() const {
    if (errorTarget) return errorTarget;
    if (sceneScale) return 1e-2 * *sceneScale;
    return std::nullopt;
}

ReportData loadReportData(const std::vector<std::string>& files) {
    ReportData data;
    data.files = files;
    for (const std::string& file : files) readFile(file, data);
    return data;
}

std::string formatNumber(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", value);
    return buffer;
}

std::string formatNumber(const Number& value) { return value ? formatNumber(*value) : "-"; }

}  // namespace anyphys::cli
