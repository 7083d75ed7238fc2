// `anyphys merge PARTS... --out RESULTS.csv`: joins the results of a sharded sweep (one CSV per
// `compare --shard k/N` process) into the file one unsharded run would have written, after
// checking that every configuration appears exactly once.
#include <algorithm>
#include <map>
#include <memory>
#include <optional>

#include "cli.hpp"
#include "results_writer.hpp"
#include "sweep_grid.hpp"

namespace anyphys::cli {
namespace {

struct MergeOptions {
    std::vector<std::string> parts;
    std::string out;
};

struct Row {
    std::size_t id = 0;
    std::string file;
    std::map<std::string, std::string> cells;

    std::string get(const std::string& column) const {
        const auto it = cells.find(column);
        return it == cells.end() ? "" : it->second;
    }
};

std::size_t wholeCell(const Row& row, const std::string& column, std::size_t line) {
    const std::string text = row.get(column);
    char* end = nullptr;
    const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || end != text.c_str() + text.size())
        throw Error(row.file + ": row " + std::to_string(line) + " has no whole number in column " + column +
                    " (not a results file of `anyphys compare --out`?)");
    return static_cast<std::size_t>(v);
}

/// The parts' rows, each checked to belong to one sweep: the same config_count and grid.
struct Parts {
    ResultsTable merged;  ///< columns only: the union, in first-seen order
    std::vector<Row> rows;
    std::size_t count = 0;
    std::optional<SweepGrid> grid;  ///< when the parts carry one (names a missing configuration)
};

Parts readParts(const std::vector<std::string>& files) {
    Parts p;
    std::optional<Row> first;  // the row the others must agree with
    for (const std::string& file : files) {
        const ResultsTable part = readResultsCsv(file);
        for (const std::string& c : part.columns)
            if (p.merged.column(c) < 0) p.merged.columns.push_back(c);
        for (std::size_t r = 0; r < part.rows.size(); ++r) {
            Row row;
            row.file = file;
            for (std::size_t c = 0; c < part.columns.size(); ++c) row.cells[part.columns[c]] = part.rows[r][c];
            const std::size_t line = r + 2;  // the header is line 1
            row.id = wholeCell(row, "config_id", line);
            const std::size_t count = wholeCell(row, "config_count", line);
            if (!first) first = row, p.count = count;
            for (const char* column : {"config_count", "grid"})
                if (row.get(column) != first->get(column))
                    throw Error("the parts are not of one sweep: " + first->file + " has " + column + " \"" +
                                first->get(column) + "\", " + file + " line " + std::to_string(line) + " has \"" +
                                row.get(column) + "\"");
            if (row.id >= count)
                throw Error(file + ": row " + std::to_string(line) + " has config_id " + std::to_string(row.id) +
                            ", beyond config_count " + std::to_string(count));
            p.rows.push_back(std::move(row));
        }
    }
    if (!first) throw Error("the parts hold no configurations");
    if (const std::string text = first->get("grid"); !text.empty()) {
        SweepGrid grid = SweepGrid::parse(text);
        if (grid.size() != p.count)
            throw Error(first->file + ": grid \"" + text + "\" has " + std::to_string(grid.size()) +
                        " configurations, config_count says " + std::to_string(p.count));
        p.grid = std::move(grid);
    }
    return p;
}

/// "3 (scene=projectile backend=native timeStep=1/60)", or the id alone without a grid.
std::string name(const Parts& p, std::size_t id) {
    return std::to_string(id) + (p.grid ? " (" + p.grid->describe(id) + ")" : "");
}

/// Every missing and every duplicated configuration, in one line; empty when there is none.
std::string problems(const Parts& p) {
    std::vector<std::string> missing, duplicated;
    std::size_t next = 0;
    for (std::size_t i = 0; i < p.rows.size(); ++i) {
        const Row& row = p.rows[i];
        for (; next < row.id; ++next) missing.push_back(name(p, next));
        const bool repeat = i > 0 && p.rows[i - 1].id == row.id;
        if (repeat && (i < 2 || p.rows[i - 2].id != row.id))  // name each duplicated configuration once
            duplicated.push_back(name(p, row.id) + " in " + p.rows[i - 1].file + " and " + row.file);
        next = row.id + 1;
    }
    for (; next < p.count; ++next) missing.push_back(name(p, next));
    std::vector<std::string> out;
    if (!missing.empty())
        out.push_back(std::to_string(missing.size()) + " of " + std::to_string(p.count) +
                      " configurations missing: " + join(missing));
    if (!duplicated.empty()) out.push_back("configurations appearing more than once: " + join(duplicated));
    return join(out, "; ");
}

int merge(const MergeOptions& o) {
    Parts p = readParts(o.parts);
    std::stable_sort(p.rows.begin(), p.rows.end(), [](const Row& a, const Row& b) { return a.id < b.id; });
    if (const std::string text = problems(p); !text.empty()) throw Error("merge: " + text);

    for (const Row& row : p.rows) {
        std::vector<std::string> cells;
        for (const std::string& c : p.merged.columns) cells.push_back(row.get(c));
        p.merged.rows.push_back(std::move(cells));
    }
    writeResults(o.out, p.merged);
    return 0;
}

}  // namespace

Command addMergeCommand(CLI::App& parent) {
    auto o = std::make_shared<MergeOptions>();
    CLI::App* app = parent.add_subcommand(
        "merge", "Join the results CSVs of a sharded sweep (compare --shard k/N) into one, checking every configuration is there once");
    app->add_option("parts", o->parts, "The part CSVs")->required()->check(CLI::ExistingFile);
    app->add_option("--out", o->out, "The merged CSV (a .jsonl is written beside it)")->required();
    return {app, [o] { return merge(*o); }};
}

}  // namespace anyphys::cli
