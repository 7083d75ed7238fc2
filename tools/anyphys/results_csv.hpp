#pragma once
// The results file of `anyphys compare --out`: a CSV table with a header row, one row per run
// configuration. Read by `anyphys merge`. Cells are plain text; a cell
// holding a comma, a quote or a line break is quoted with doubled quotes (RFC 4180).
#include <string>
#include <vector>

namespace anyphys::cli {

struct ResultsTable {
    std::vector<std::string> columns;
    std::vector<std::vector<std::string>> rows;  ///< each as long as `columns`

    /// Index of a column, or -1 when the table has none of that name.
    int column(const std::string& name) const;
    /// The cell of `row` in column `name`; "" when the column is absent.
    const std::string& cell(std::size_t row, const std::string& name) const;
};

/// Reads a results CSV. Throws anyphys::Error naming the file and line when it cannot be read or
/// a row's cell count differs from the header's.
ResultsTable readResultsCsv(const std::string& path);
/// The table as CSV text (header first).
std::string toCsv(const ResultsTable& table);
/// One CSV line (no newline) of these cells, quoting where needed.
std::string csvLine(const std::vector<std::string>& cells);

}  // namespace anyphys::cli
