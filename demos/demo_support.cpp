#include "demo_support.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace anyphys::demo {
namespace {

/// A body name as one CSV field: quoted (RFC 4180) only if it holds a comma, quote or line break.
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace

void addCommonOptions(CLI::App& app, DemoOptions& options, double defaultSeconds) {
    options.seconds = defaultSeconds;
    app.add_option("--backend", options.backend, "Backend name (default native); a 2D engine runs the planar version");
    app.add_option("--seconds", options.seconds, "Simulated time in s")->capture_default_str();
    app.add_option("--out", options.out,
                   "Write body trajectories as CSV (the `anyphys run` format: step,time,body,px,..,wz)");
}

void validate(const DemoOptions& options) {
    backendInfo(options.backend);  // throws listing the known backends
    if (!(std::isfinite(options.seconds) && options.seconds > 0))
        throw Error::invalid("--seconds", options.seconds, "must be a finite time > 0 (seconds)");
}

bool planarOnly(const std::string& backend) { return backendInfo(backend).capabilities.dimensions == 2; }

WorldSettings settingsFor(const std::string& backend) {
    WorldSettings settings;
    settings.backend = backend;
    settings.planar = planarOnly(backend);
    return settings;
}

TrajectoryWriter::TrajectoryWriter(const std::string& path) : path_(path) {
    if (path_.empty()) return;
    file_.open(path_, std::ios::binary);
    if (!file_) throw Error(ErrorKind::Io, "", path_ + ": cannot open for writing");
    file_ << "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
}

void TrajectoryWriter::write(long long step, double time, const std::vector<Body>& bodies, const std::string& prefix) {
    if (!file_.is_open()) return;
    char buffer[512];
    for (const Body& body : bodies) {
        const BodyState s = body.state();
        const Quat& q = s.orientation;
        const Vec3 &p = s.position, &v = s.linearVelocity, &w = s.angularVelocity;
        // 17 significant digits read back to the same double, as `anyphys run` writes them.
        std::snprintf(buffer, sizeof buffer,
                      "%lld,%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                      step, time, csvField(prefix + body.name()).c_str(), p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(),
                      v.z(), w.x(), w.y(), w.z());
        file_ << buffer;
    }
}

void TrajectoryWriter::finish() {
    if (!file_.is_open()) return;
    file_.flush();
    if (!file_) throw Error(ErrorKind::Io, "", path_ + ": write failed");
}

std::string firstNonFinite(const std::vector<Body>& bodies) {
    for (const Body& body : bodies) {
        const BodyState s = body.state();
        if (!s.position.allFinite() || !s.orientation.coeffs().allFinite() || !s.linearVelocity.allFinite() ||
            !s.angularVelocity.allFinite())
            return body.name().empty() ? "#" + std::to_string(body.id().index) : body.name();
    }
    return {};
}

SimulationResult simulate(World& world, const std::vector<Body>& bodies, const DemoOptions& options,
                          const StepHooks& hooks) {
    TrajectoryWriter trajectory(options.out);
    const long long steps = std::llround(options.seconds / world.settings().timeStep);
    trajectory.write(0, world.time(), bodies);
    SimulationResult result;
    std::chrono::steady_clock::duration stepping{};
    for (long long step = 1; step <= steps; ++step) {
        if (hooks.before) hooks.before(step);
        const auto start = std::chrono::steady_clock::now();
        world.step();
        stepping += std::chrono::steady_clock::now() - start;
        result.steps = step;
        trajectory.write(step, world.time(), bodies);
        if (const std::string bad = firstNonFinite(bodies); !bad.empty()) {
            std::cerr << "non-finite state: body \"" << bad << "\" at t = " << world.time() << " s on "
                      << world.backendName() << '\n';
            result.finite = false;
            break;
        }
        if (hooks.after) hooks.after(step);
    }
    trajectory.finish();
    if (result.steps > 0)
        result.msPerStep = std::chrono::duration<double, std::milli>(stepping).count() / static_cast<double>(result.steps);
    return result;
}

void DemoMenu::addTo(CLI::App& app) {
    app.add_option("NAME", name_, "Demo to run (see --list)");
    app.add_flag("--list", list_, "List the demos");
}

bool DemoMenu::listedOrChecked() const {
    if (list_) {
        std::size_t width = 0;
        for (const auto& [name, what] : demos_) width = std::max(width, name.size());
        for (const auto& [name, what] : demos_) std::printf("%-*s  %s\n", static_cast<int>(width), name.c_str(), what.c_str());
        return true;
    }
    if (!demos_.contains(name_)) {
        std::string known;
        for (const auto& [name, what] : demos_) known += (known.empty() ? "" : ", ") + name;
        throw Error::invalid("NAME", "\"" + name_ + "\"", "must be one of " + known);
    }
    return false;
}

int runMain(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
    const std::string program = app.get_name();
    const auto fail = [&program](std::string message, int code) {
        for (char& c : message)
            if (c == '\n' || c == '\r') c = ' ';
        std::cerr << program << ": " << message << '\n';
        return code;
    };
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        return fail(e.what(), 2);
    }
    try {
        return body();
    } catch (const std::exception& e) {
        return fail(e.what(), 1);
    }
}

}  // namespace anyphys::demo
