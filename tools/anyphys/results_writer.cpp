// The results files: CSV for tables and spreadsheets, JSONL for scripts.
#include "results_writer.hpp"

#include <cmath>
#include <cstdlib>
#include <set>

#include <nlohmann/json.hpp>

#include "cli.hpp"

namespace anyphys::cli {
namespace {

/// Columns whose cells are names or prose, never numbers (a commit hash may be all digits).
bool isTextColumn(const std::string& name) {
    static const std::set<std::string> text{"scene",  "backend", "integrator",  "solver",          "effectOff",
                                            "status", "reason",  "sweep",       "error_reference", "check_label",
                                            "shard",  "commit",  "anyphys_version", "grid"};
    return text.contains(name);
}

nlohmann::ordered_json cellJson(const std::string& column, const std::string& cell) {
    if (cell.empty()) return nullptr;
    if (isTextColumn(column)) return cell;
    if (cell == "true") return true;
    if (cell == "false") return false;
    char* end = nullptr;
    const long long whole = std::strtoll(cell.c_str(), &end, 10);
    if (end == cell.c_str() + cell.size()) return whole;  // counts and ids stay integers
    const double v = std::strtod(cell.c_str(), &end);
    if (end == cell.c_str() + cell.size() && std::isfinite(v)) return v;
    return cell;  // "nan", "inf" (a blow-up): JSON has no number for them
}

}  // namespace

std::string jsonlPathFor(const std::string& csvPath) {
    const std::string ext = ".csv";
    if (csvPath.size() > ext.size() && csvPath.compare(csvPath.size() - ext.size(), ext.size(), ext) == 0)
        return csvPath.substr(0, csvPath.size() - ext.size()) + ".jsonl";
    return csvPath + ".jsonl";
}

std::string toJsonl(const ResultsTable& table) {
    std::string out;
    for (const auto& row : table.rows) {
        nlohmann::ordered_json object = nlohmann::ordered_json::object();
        for (std::size_t i = 0; i < table.columns.size(); ++i) object[table.columns[i]] = cellJson(table.columns[i], row[i]);
        out += object.dump() + '\n';
    }
    return out;
}

void writeResults(const std::string& csvPath, const ResultsTable& table) {
    writeFile(csvPath, toCsv(table));
    writeFile(jsonlPathFor(csvPath), toJsonl(table));
}

}  // namespace anyphys::cli
