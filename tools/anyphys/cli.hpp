#pragma once
// Shared pieces of the `anyphys` command-line tool: the subcommand registry and small helpers.
// Every subcommand lives in its own cmd_*.cpp and reports failure by throwing anyphys::Error;
// main() turns that into "anyphys: <message>" on stderr and a non-zero exit code.
#include <CLI/CLI.hpp>

#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::cli {

/// A registered subcommand: its CLI11 app (to see whether it was chosen) and what runs it.
struct Command {
    CLI::App* app = nullptr;
    std::function<int()> run;  ///< returns the process exit code
};

Command addBackendsCommand(CLI::App& parent);
Command addRunCommand(CLI::App& parent);
Command addCompareCommand(CLI::App& parent);
Command addHardCasesCommand(CLI::App& parent);
Command addScenesCommand(CLI::App& parent);
Command addSceneCommand(CLI::App& parent);
Command addMergeCommand(CLI::App& parent);
Command addReportCommand(CLI::App& parent);
Command addSchemaCommand(CLI::App& parent);

/// "a, b, c".
std::string join(const std::vector<std::string>& items, std::string_view separator = ", ");

/// Scene-file names of a set of enum values, in enum order.
template <class E>
std::vector<std::string> enumNames(const std::set<E>& values) {
    std::vector<std::string> out;
    for (E value : values) out.emplace_back(toString(value));
    return out;
}

/// The integrator of that scene-file name; throws anyphys::Error naming `option` otherwise.
Integrator parseIntegrator(const std::string& option, const std::string& name);

/// The built backend of that name; throws anyphys::Error naming `option` (e.g. "--backends")
/// otherwise, where the library's error names the settings field "backend".
BackendInfo parseBackend(const std::string& option, const std::string& name);

/// The shortest text that reads back to the same double ("0.2", "0.016666666666666666"; "nan",
/// "inf" for a blow-up), for results files.
std::string exactNumber(double value);

/// One number through a printf pattern ("%.3g"), for tables meant to be read.
std::string printfNumber(const char* pattern, double value);

/// Writes text to a file (for --out); throws anyphys::Error if it cannot.
void writeFile(const std::string& path, const std::string& text);

}  // namespace anyphys::cli
