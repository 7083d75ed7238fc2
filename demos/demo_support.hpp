#pragma once
// What every demo program shares: the --backend / --seconds / --out options, a world that is
// planar on a 2D engine, the stepping loop with its trajectory CSV (the `anyphys run` format)
// and the non-finite check, and main()'s error reporting (one line on stderr, non-zero exit).
#include <CLI/CLI.hpp>

#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::demo {

struct DemoOptions {
    std::string backend = "native";
    double seconds = 0.0;  ///< simulated time, s
    std::string out;       ///< trajectory CSV; empty: none
};

/// Adds --backend, --seconds (default `defaultSeconds`) and --out to `app`.
void addCommonOptions(CLI::App& app, DemoOptions& options, double defaultSeconds);

/// Checks the common options (known backend, seconds finite and > 0); throws anyphys::Error
/// naming the option otherwise.
void validate(const DemoOptions& options);

/// True when the backend simulates planar worlds only (a 2D engine): the demo builds its planar
/// version of the scene, as the quickstart does.
bool planarOnly(const std::string& backend);

/// Default settings on `backend`, planar when the engine is 2D-only.
WorldSettings settingsFor(const std::string& backend);

/// Writes body states per step as CSV, the `anyphys run --out` format:
/// step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz.
class TrajectoryWriter {
public:
    /// An empty path writes nothing.
    explicit TrajectoryWriter(const std::string& path);
    /// One row per body; `prefix` goes before each name (several worlds in one file).
    void write(long long step, double time, const std::vector<Body>& bodies, const std::string& prefix = "");
    /// Flushes; throws anyphys::Error if the file could not be written.
    void finish();

private:
    std::string path_;
    std::ofstream file_;
};

/// The name of the first body whose position, orientation or velocity is not finite; empty if
/// all are finite.
std::string firstNonFinite(const std::vector<Body>& bodies);

/// What a demo does around each step: set controls or animation before it, measure after it.
struct StepHooks {
    std::function<void(long long step)> before;
    std::function<void(long long step)> after;
};

struct SimulationResult {
    bool finite = true;      ///< false: a state became non-finite (reported on stderr)
    long long steps = 0;     ///< steps taken
    double msPerStep = 0.0;  ///< wall time of World::step alone, mean
};

/// Steps `world` for options.seconds, recording `bodies` to options.out and calling the hooks.
/// Stops early, after one line on stderr naming the body and the time, if a state became
/// non-finite.
SimulationResult simulate(World& world, const std::vector<Body>& bodies, const DemoOptions& options,
                          const StepHooks& hooks = {});

/// The demos of a program that runs one chosen by name: its NAME argument and --list.
class DemoMenu {
public:
    /// `demos`: name -> one line saying what it shows.
    explicit DemoMenu(std::map<std::string, std::string> demos) : demos_(std::move(demos)) {}
    /// Adds the NAME argument and the --list flag to `app`.
    void addTo(CLI::App& app);
    /// True when --list was given (the list is printed). Otherwise checks NAME, throwing
    /// anyphys::Error naming it and the known demos when it is none of them.
    bool listedOrChecked() const;
    const std::string& chosen() const { return name_; }

private:
    std::map<std::string, std::string> demos_;
    std::string name_;
    bool list_ = false;
};

/// Parses the command line and runs `body`: usage errors exit 2, anyphys::Error and other
/// exceptions exit 1, each as one line "program: message" on stderr; --help exits 0.
int runMain(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

}  // namespace anyphys::demo
