#pragma once
// Writing a results table as RESULTS.csv plus RESULTS.jsonl beside it (same stem): one JSON
// object per line with the same keys, numbers as numbers, empty cells as null.
#include <string>

#include "results_csv.hpp"

namespace anyphys::cli {

/// "dir/x.jsonl" for "dir/x.csv" (any other name: the name plus ".jsonl").
std::string jsonlPathFor(const std::string& csvPath);
/// One JSON object per row. Text columns (scene, backend, names, reasons, the commit) stay strings
/// even when they look numeric; other cells that read fully as a finite number become numbers,
/// "true" / "false" booleans, empty cells null.
std::string toJsonl(const ResultsTable& table);
/// Writes the CSV and its .jsonl; throws anyphys::Error naming a file it cannot write.
void writeResults(const std::string& csvPath, const ResultsTable& table);

}  // namespace anyphys::cli
