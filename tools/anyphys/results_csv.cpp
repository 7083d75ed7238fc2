// Reading and writing the results CSV (RFC 4180 quoting).
#include "results_csv.hpp"

#include <fstream>
#include <sstream>

#include "anyphys/error.hpp"

namespace anyphys::cli {
namespace {

std::string quoted(const std::string& cell) {
    if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
    std::string out = "\"";
    for (char c : cell) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + '"';
}

/// Splits the record starting at `pos` into cells; advances `pos` past its line end. A quoted
/// cell may span lines, so `line` counts the lines consumed.
std::vector<std::string> parseRecord(const std::string& text, std::size_t& pos, int& line, const std::string& path) {
    std::vector<std::string> cells(1);
    bool inQuotes = false;
    const int startLine = line;
    while (pos < text.size()) {
        const char c = text[pos++];
        if (inQuotes) {
            if (c == '"' && pos < text.size() && text[pos] == '"') cells.back() += '"', ++pos;
            else if (c == '"') inQuotes = false;
            else {
                if (c == '\n') ++line;
                cells.back() += c;
            }
        } else if (c == '"' && cells.back().empty()) inQuotes = true;
        else if (c == ',') cells.emplace_back();
        else if (c == '\n') { ++line; return cells; }
        else if (c != '\r') cells.back() += c;
    }
    if (inQuotes) throw Error(path + ":" + std::to_string(startLine) + ": a quoted cell is not closed");
    ++line;
    return cells;
}

}  // namespace

int ResultsTable::column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
        if (columns[i] == name) return static_cast<int>(i);
    return -1;
}

const std::string& ResultsTable::cell(std::size_t row, const std::string& name) const {
    static const std::string empty;
    const int i = column(name);
    return i < 0 ? empty : rows.at(row).at(static_cast<std::size_t>(i));
}

ResultsTable readResultsCsv(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorKind::Io, "", "cannot read results file \"" + path + "\"");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();

    ResultsTable table;
    std::size_t pos = 0;
    int line = 1;
    if (text.empty()) throw Error(path + ": empty file, expected a CSV header row");
    table.columns = parseRecord(text, pos, line, path);
    while (pos < text.size()) {
        const int recordLine = line;
        std::vector<std::string> cells = parseRecord(text, pos, line, path);
        if (cells.size() == 1 && cells[0].empty()) continue;  // blank line
        if (cells.size() != table.columns.size())
            throw Error(path + ":" + std::to_string(recordLine) + ": " + std::to_string(cells.size()) +
                        " cells, the header has " + std::to_string(table.columns.size()));
        table.rows.push_back(std::move(cells));
    }
    return table;
}

std::string csvLine(const std::vector<std::string>& cells) {
    std::string out;
    for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + quoted(cells[i]);
    return out;
}

std::string toCsv(const ResultsTable& table) {
    std::string out = csvLine(table.columns) + '\n';
    for (const auto& row : table.rows) out += csvLine(row) + '\n';
    return out;
}

}  // namespace anyphys::cli
