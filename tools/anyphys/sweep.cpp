// The sweep: the grid of configurations, this shard's part of it, the runs, the results.
#include "sweep.hpp"

#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "progress.hpp"
#include "results_writer.hpp"
#include "sweep_grid.hpp"
#include "sweep_rows.hpp"
#include "sweep_run.hpp"

namespace anyphys::cli {
namespace {

/// The grid's shape: scenes, then backends, then the axes (first outermost).
SweepGrid gridOf(const SweepOptions& o) {
    SweepGrid grid;
    grid.axes.push_back({"scene", {}});
    for (const CatalogueScene* scene : o.scenes) grid.axes.back().values.push_back(scene->name);
    grid.axes.push_back({"backend", {}});
    for (const BackendInfo& backend : o.backends) grid.axes.back().values.push_back(backend.name);
    for (const SweepAxis& axis : o.axes) grid.axes.push_back({axis.name, axis.given});
    return grid;
}

/// Every configuration, numbered as the grid numbers them.
std::vector<SweepConfig> configurations(const SweepOptions& o, const SweepGrid& grid) {
    std::vector<SweepConfig> configs(grid.size());
    for (std::size_t id = 0; id < configs.size(); ++id) {
        const std::vector<std::size_t> at = grid.coordinates(id);
        SweepConfig& c = configs[id];
        c.id = id;
        c.scene = o.scenes[at[0]];
        c.backend = &o.backends[at[1]];
        for (std::size_t i = 0; i < o.axes.size(); ++i) {
            c.values.push_back(o.axes[i].values[at[i + 2]]);
            c.label += (i ? " " : "") + o.axes[i].name + "=" + o.axes[i].given[at[i + 2]];
        }
    }
    return configs;
}

std::string shortNumber(const std::string& cell, const char* pattern) {
    if (cell.empty()) return "-";
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, pattern, std::strtod(cell.c_str(), nullptr));
    return buffer;
}

/// The rows on stdout, a few columns wide: the full set is in the results file.
void printTable(const ResultsTable& t) {
    using Row = std::vector<std::string>;
    std::vector<Row> rows{{"scene", "backend", "sweep", "steps", "ms/step", "pos error m", "vel error m/s",
                           "energy drift", "|L| drift", "check"}};
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        const auto cell = [&](const char* name) { return t.cell(i, name); };
        Row row{cell("scene"), cell("backend"), cell("sweep").empty() ? "-" : cell("sweep")};
        if (cell("status") != "ok") {
            row.push_back(cell("status") + ": " + cell("reason"));
        } else {
            const std::string check = cell("check_ok").empty()
                                          ? "-"
                                          : shortNumber(cell("check_value"), "%.4g") +
                                                (cell("check_ok") == "true" ? " ok"
                                                 : cell("check_known_deviation") == "true" ? " FAIL (declared)"
                                                                                            : " FAIL");
            row.insert(row.end(), {cell("steps"), shortNumber(cell("ms_per_step_median"), "%.4f"),
                                   shortNumber(cell("pos_error"), "%.3e"), shortNumber(cell("vel_error"), "%.3e"),
                                   shortNumber(cell("energy_drift"), "%+.3e"), shortNumber(cell("momentum_drift"), "%+.3e"),
                                   check});
        }
        rows.push_back(std::move(row));
    }
    std::vector<std::size_t> widths(rows.front().size(), 0);
    for (const Row& row : rows)
        if (row.size() == widths.size())  // refusal rows span the measured columns; they don't set widths
            for (std::size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
    for (const Row& row : rows) {
        std::string line;
        for (std::size_t i = 0; i < row.size(); ++i) {
            const bool last = i + 1 == row.size();
            line += row[i];
            if (!last) line += std::string(widths[i] > row[i].size() ? widths[i] - row[i].size() : 0, ' ') + "  ";
        }
        std::cout << line << '\n';
    }
}

}  // namespace

int runSweep(const SweepOptions& o) {
    const SweepGrid grid = gridOf(o);
    const std::vector<SweepConfig> configs = configurations(o, grid);
    std::vector<double> costs;
    for (const SweepConfig& c : configs) costs.push_back(configCost(c, o.axes, o.repeat));
    const std::vector<std::size_t> members = shardMembers(costs, o.shard);

    ResultsTable table;
    table.columns = sweepColumns(o.axes);
    SweepRunner runner(o.axes, o.repeat);
    ProgressBar progress(members.size(), o.shard.count > 1 ? "shard " + o.shard.label() + " " : "");
    for (std::size_t i = 0; i < members.size(); ++i) {
        const SweepConfig& c = configs[members[i]];
        progress.update(i, c.scene->name + " " + c.backend->name + (c.label.empty() ? "" : " " + c.label));
        table.rows.push_back(sweepRow(o.axes, c, runner.run(c), grid, o.shard));
    }
    progress.update(members.size(), "done");
    progress.finish();

    if (!o.out.empty()) writeResults(o.out, table);
    if (o.json) {
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        const std::string lines = toJsonl(table);
        for (std::size_t start = 0, end; (end = lines.find('\n', start)) != std::string::npos; start = end + 1)
            list.push_back(nlohmann::ordered_json::parse(lines.substr(start, end - start)));
        std::cout << nlohmann::ordered_json{{"results", list}}.dump(2) << '\n';
    } else {
        printTable(table);
    }
    return 0;
}

}  // namespace anyphys::cli
