// Turning sweep records into results rows.
#include "sweep_rows.hpp"

#include <map>

#include "build_info.hpp"
#include "cli.hpp"

namespace anyphys::cli {
namespace {

constexpr const char* kSolverColumns[] = {"timeStep", "substeps", "iterations", "integrator", "solver"};

bool isSolverColumn(const std::string& name) {
    for (const char* c : kSolverColumns)
        if (name == c) return true;
    return false;
}

std::string number(double v) { return exactNumber(v); }
std::string number(const std::optional<double>& v) { return v ? exactNumber(*v) : std::string(); }

}  // namespace

std::vector<std::string> sweepColumns(const std::vector<SweepAxis>& axes) {
    std::vector<std::string> columns{"config_id", "scene", "backend"};
    for (const char* c : kSolverColumns) columns.emplace_back(c);
    for (const SweepAxis& axis : axes)
        if (!isSolverColumn(axis.name)) columns.push_back(axis.name);
    for (const char* c : {"sweep", "status", "reason", "repeat", "steps", "effects", "ms_per_step_min", "ms_per_step_median",
                          "ms_per_sim_second", "machine_load", "pos_error", "vel_error", "error_reference",
                          "pos_error_vs_engines", "scene_scale", "error_target", "energy_drift", "momentum_drift",
                          "max_penetration", "joint_gap", "check_label", "check_value", "check_ok",
                          "check_known_deviation", "config_count", "shard", "grid", "anyphys_version", "commit"})
        columns.emplace_back(c);
    return columns;
}

std::vector<std::string> sweepRow(const std::vector<SweepAxis>& axes, const SweepConfig& config, const SweepRecord& r,
                                  const SweepGrid& grid, const ShardSpec& shard) {
    const WorldSettings& s = r.settings;
    std::map<std::string, std::string> cells{
        {"config_id", std::to_string(config.id)},
        {"scene", config.scene->name},
        {"backend", config.backend->name},
        {"timeStep", number(s.timeStep)},
        {"substeps", s.substeps ? std::to_string(*s.substeps) : ""},
        {"iterations", s.iterations ? std::to_string(*s.iterations) : ""},
        {"integrator", std::string(toString(s.integrator))},
        {"solver", s.solver ? std::string(toString(*s.solver)) : ""},
        {"sweep", config.label},
        {"status", r.status},
        {"reason", r.reason},
        {"repeat", std::to_string(r.repeat)},
        {"steps", std::to_string(r.steps)},
        {"effects", r.effects},
        {"ms_per_step_min", number(r.msPerStepMin)},
        {"ms_per_step_median", number(r.msPerStepMedian)},
        {"ms_per_sim_second", number(r.msPerSimSecond)},
        {"machine_load", number(r.machineLoad)},
        {"pos_error", number(r.posError)},
        {"vel_error", number(r.velError)},
        {"error_reference", r.errorReference},
        {"pos_error_vs_engines", number(r.posErrorVsEngines)},
        {"scene_scale", number(r.sceneScale)},
        {"error_target", number(r.errorTarget)},
        {"energy_drift", number(r.energyDrift)},
        {"momentum_drift", number(r.momentumDrift)},
        {"max_penetration", number(r.maxPenetration)},
        {"joint_gap", number(r.jointGap)},
        {"check_label", r.check ? config.scene->check->label : ""},
        {"check_value", r.check ? number(r.check->value) : ""},
        {"check_ok", r.check ? (r.check->passed ? "true" : "false") : ""},
        {"check_known_deviation", r.check ? (r.check->knownDeviation ? "true" : "false") : ""},
        {"config_count", std::to_string(grid.size())},
        {"grid", grid.text()},
        {"shard", shard.label()},
        {"anyphys_version", kAnyphysVersion},
        {"commit", kAnyphysCommit},
    };
    for (std::size_t i = 0; i < axes.size(); ++i)
        if (!isSolverColumn(axes[i].name)) cells[axes[i].name] = config.values[i];
    std::vector<std::string> row;
    for (const std::string& column : sweepColumns(axes)) row.push_back(cells[column]);
    return row;
}

}  // namespace anyphys::cli
