// anyphys: list backends, run scene files, compare backends and integrators on the built-in
// scene catalogue. Each subcommand lives in its own cmd_*.cpp.
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"

namespace {

/// Errors are exactly one line on stderr, so scripts can show them verbatim.
int fail(std::string message, int code) {
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    std::cerr << "anyphys: " << message << '\n';
    return code;
}

/// CLI11 would call a mistyped subcommand "a subcommand is required"; name it instead.
bool isUnknownSubcommand(int argc, char** argv, const std::vector<anyphys::cli::Command>& commands, std::string& known) {
    if (argc < 2 || argv[1][0] == '-') return false;
    bool found = false;
    for (const auto& command : commands) {
        known += (known.empty() ? "" : ", ") + command.app->get_name();
        found = found || command.app->get_name() == argv[1];
    }
    return !found;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace anyphys::cli;
    CLI::App app{"anyphys: one physics API over several engines; run scenes and compare backends", "anyphys"};
    app.require_subcommand(1);
    const std::vector<Command> commands{addBackendsCommand(app), addRunCommand(app), addCompareCommand(app),
                                        addHardCasesCommand(app), addScenesCommand(app), addSceneCommand(app),
                                        addMergeCommand(app), addReportCommand(app), addSchemaCommand(app)};
    if (std::string known; isUnknownSubcommand(argc, argv, commands, known))
        return fail("unknown subcommand \"" + std::string(argv[1]) + "\"; known: " + known, 2);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help: help on stdout, success
        return fail(e.what(), 2);                         // usage error
    }
    try {
        for (const Command& command : commands)
            if (command.app->parsed()) return command.run();
        return fail("no subcommand given", 2);
    } catch (const anyphys::Error& e) {
        return fail(e.what(), 1);
    } catch (const std::exception& e) {
        return fail(e.what(), 1);
    }
}
