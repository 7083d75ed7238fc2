// `anyphys run SCENE.json`: steps a scene file and writes every body's state as CSV, with
// --events the collision and trigger events of each step, with --joints every joint's state, and
// with --particles every fluid particle and cloth node.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string_view>

#include "cli.hpp"

namespace anyphys::cli {
namespace {

struct RunOptions {
    std::string sceneFile;
    std::string backend;
    long long steps = 0;
    double dt = 0.0;
    std::string integrator;
    std::string out;
    std::string events;
    std::string joints;
    std::string particles;
    bool hash = false;
    // Set after parsing: which optional flags were given.
    const CLI::Option* backendOption = nullptr;
    const CLI::Option* stepsOption = nullptr;
    const CLI::Option* dtOption = nullptr;
    const CLI::Option* integratorOption = nullptr;
    const CLI::Option* outOption = nullptr;
    const CLI::Option* eventsOption = nullptr;
    const CLI::Option* jointsOption = nullptr;
    const CLI::Option* particlesOption = nullptr;
};

constexpr const char* kCsvHeader = "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
constexpr const char* kEventsHeader = "step,time,phase,bodyA,bodyB";
constexpr const char* kJointsHeader = "step,time,joint,position,speed,fx,fy,fz,tx,ty,tz";
constexpr const char* kParticlesHeader = "step,time,system,index,px,py,pz,vx,vy,vz";

/// A body name as one CSV field: quoted (RFC 4180) only if it holds a comma, quote or line break.
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

/// Numbers as CSV fields, each preceded by its comma, in the shortest decimal form that reads back
/// to the same double (std::to_chars, as exactNumber, but into one buffer per row: no string per
/// number), several times faster to write than %.17g, which matters when a row is written per body
/// per step.
class CsvNumbers {
public:
    CsvNumbers& operator<<(double value) {
        *end_++ = ',';
        end_ = std::to_chars(end_, buffer_ + sizeof buffer_, value).ptr;
        return *this;
    }
    CsvNumbers& operator<<(std::size_t value) {
        *end_++ = ',';
        end_ = std::to_chars(end_, buffer_ + sizeof buffer_, value).ptr;
        return *this;
    }
    std::string_view text() const { return {buffer_, static_cast<std::size_t>(end_ - buffer_)}; }

private:
    char buffer_[512];  // 25 characters at most per double with its comma: room for 20 fields
    char* end_ = buffer_;
};

std::string prefix(long long step, double time) { return std::to_string(step) + ',' + exactNumber(time) + ','; }

/// enter / stay / exit for collisions; trigger_enter / trigger_exit for sensors (the tracker
/// sends triggers no stay, so trigger_stay never appears).
std::string phaseName(const ContactEvent& event) {
    const char* phase = event.phase == ContactPhase::Enter ? "enter" : event.phase == ContactPhase::Stay ? "stay" : "exit";
    return (event.trigger ? "trigger_" : "") + std::string(phase);
}

/// Collects the events each step delivers, so they are written with that step's number and time.
class EventRecorder : public ContactEventListener {
public:
    void onContactEvent(const ContactEvent& e) override { events_.push_back(e); }

    /// One row per event received since the last call, in delivery order.
    void writeRows(std::ostream& out, long long step, double time, const std::map<BodyId, std::string>& names) {
        const std::string head = prefix(step, time);
        const auto nameOf = [&names](BodyId id) {
            const auto it = names.find(id);
            return it == names.end() ? std::string("#") + std::to_string(id.index) : csvField(it->second);
        };
        for (const ContactEvent& e : events_) out << head << phaseName(e) << ',' << nameOf(e.bodyA) << ',' << nameOf(e.bodyB) << '\n';
        events_.clear();
    }

private:
    std::vector<ContactEvent> events_;
};

/// One row per body, every number exact (CsvNumbers).
void writeRows(std::ostream& out, long long step, double time, const std::vector<Body>& bodies) {
    const std::string head = prefix(step, time);
    for (const Body& body : bodies) {
        const BodyState s = body.state();
        const Quat& q = s.orientation;
        const Vec3 &p = s.position, &v = s.linearVelocity, &w = s.angularVelocity;
        CsvNumbers row;
        row << p.x() << p.y() << p.z() << q.w() << q.x() << q.y() << q.z() << v.x() << v.y() << v.z() << w.x() << w.y()
            << w.z();
        out << head << csvField(body.name()) << row.text() << '\n';
    }
}

/// One row per joint: position and speed (Joint::position, speed), the reaction on bodyB (world
/// frame). A joint without a name is written as #index (its place in the scene's list).
void writeJointRows(std::ostream& out, long long step, double time, const std::vector<Joint>& joints) {
    const std::string head = prefix(step, time);
    for (std::size_t i = 0; i < joints.size(); ++i) {
        const Joint& joint = joints[i];
        const Vec3 f = joint.reactionForce(), t = joint.reactionTorque();
        CsvNumbers row;
        row << joint.position() << joint.speed() << f.x() << f.y() << f.z() << t.x() << t.y() << t.z();
        out << head << (joint.name().empty() ? "#" + std::to_string(i) : csvField(joint.name())) << row.text() << '\n';
    }
}

/// One row per fluid particle and cloth node: its system's name (or #k, its place among the
/// world's fluids then cloths), its index (a cloth's node (i, j) is j (resolution[0] + 1) + i).
void writeParticleRows(std::ostream& out, long long step, double time, const World& world) {
    const std::string head = prefix(step, time);
    const std::vector<ParticleSystemView> systems = world.particleSystems();
    for (std::size_t k = 0; k < systems.size(); ++k) {
        const ParticleSystemView& s = systems[k];
        const std::string name = s.name.empty() ? "#" + std::to_string(k) : csvField(s.name);
        for (std::size_t i = 0; i < s.positions->size(); ++i) {
            const Vec3& p = (*s.positions)[i];
            const Vec3& v = (*s.velocities)[i];
            CsvNumbers row;
            row << i << p.x() << p.y() << p.z() << v.x() << v.y() << v.z();
            out << head << name << row.text() << '\n';
        }
    }
}

/// FNV-1a over the bit patterns of every body's final state, in scene order: equal hashes mean
/// bit-identical runs (determinism), any difference changes it.
std::uint64_t stateHash(const std::vector<Body>& bodies) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    const auto mix = [&h](double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int i = 0; i < 8; ++i) {
            h ^= (bits >> (8 * i)) & 0xffu;
            h *= 0x100000001b3ull;
        }
    };
    for (const Body& body : bodies) {
        const BodyState s = body.state();
        for (double v : {s.position.x(), s.position.y(), s.position.z(), s.orientation.w(), s.orientation.x(),
                         s.orientation.y(), s.orientation.z(), s.linearVelocity.x(), s.linearVelocity.y(),
                         s.linearVelocity.z(), s.angularVelocity.x(), s.angularVelocity.y(), s.angularVelocity.z()})
            mix(v);
    }
    return h;
}

/// Applies the (already validated) command-line overrides to the scene settings.
void applyOverrides(const RunOptions& o, Scene& scene) {
    if (o.backendOption->count()) scene.settings.backend = o.backend;
    if (o.dtOption->count()) scene.settings.timeStep = o.dt;
    if (o.integratorOption->count()) scene.settings.integrator = parseIntegrator("--integrator", o.integrator);
}

void validateFlags(const RunOptions& o) {
    if (o.stepsOption->count() && o.steps < 0) throw Error::invalid("--steps", o.steps, "must be >= 0");
    if (o.dtOption->count() && !(std::isfinite(o.dt) && o.dt > 0))
        throw Error::invalid("--dt", o.dt, "must be a finite time step > 0 (seconds)");
    if (o.integratorOption->count()) parseIntegrator("--integrator", o.integrator);
    if (o.backendOption->count()) parseBackend("--backend", o.backend);  // throws listing the known backends
}

int run(const RunOptions& o) {
    validateFlags(o);  // before touching the file, so a bad flag is reported as such
    Scene scene = loadScene(o.sceneFile);
    applyOverrides(o, scene);
    // Default: one simulated second.
    const long long steps = o.stepsOption->count() ? o.steps : std::llround(1.0 / scene.settings.timeStep);

    EventRecorder recorder;  // before the world, so it outlives it
    World world = [&] {
        try {
            return World(scene.settings, scene.materials);
        } catch (const Error& e) {
            throw asSceneFileError(e, o.sceneFile);
        }
    }();
    const SceneObjects objects = [&] {
        try {
            return createSceneObjects(world, scene);
        } catch (const Error& e) {
            throw asSceneFileError(e, o.sceneFile);
        }
    }();
    const std::vector<Body>& bodies = objects.bodies;
    const std::vector<Joint>& joints = objects.joints;
    // Names captured now: an exit flagged as removal names a body that no longer exists.
    std::map<BodyId, std::string> names;
    for (const Body& body : bodies) names[body.id()] = body.name();

    std::ofstream file, eventFile, jointFile, particleFile;
    if (o.outOption->count()) {
        file.open(o.out, std::ios::binary);
        if (!file) throw Error(ErrorKind::Io, "", o.out + ": cannot open for writing");
    }
    if (o.eventsOption->count()) {
        eventFile.open(o.events, std::ios::binary);
        if (!eventFile) throw Error(ErrorKind::Io, "", o.events + ": cannot open for writing");
        eventFile << kEventsHeader << '\n';
        world.addListener(&recorder);
    }
    if (o.jointsOption->count()) {
        jointFile.open(o.joints, std::ios::binary);
        if (!jointFile) throw Error(ErrorKind::Io, "", o.joints + ": cannot open for writing");
        jointFile << kJointsHeader << '\n';
        writeJointRows(jointFile, 0, world.time(), joints);
    }
    if (o.particlesOption->count()) {
        particleFile.open(o.particles, std::ios::binary);
        if (!particleFile) throw Error(ErrorKind::Io, "", o.particles + ": cannot open for writing");
        particleFile << kParticlesHeader << '\n';
        writeParticleRows(particleFile, 0, world.time(), world);
    }
    // With --hash and no --out, stdout carries the hash alone, and the rows are not formatted at
    // all (formatting every body's state took a third of a 10 000-box run).
    std::ostringstream discard;
    discard.setstate(std::ios::badbit);  // writes are dropped
    const bool csvToStdout = !o.outOption->count() && !o.hash;
    std::ostream& out = o.outOption->count() ? static_cast<std::ostream&>(file) : csvToStdout ? std::cout : discard;
    const bool writeStates = &out != &discard;
    out << kCsvHeader << '\n';
    if (writeStates) writeRows(out, 0, world.time(), bodies);
    for (long long step = 1; step <= steps; ++step) {
        world.step();
        if (writeStates) writeRows(out, step, world.time(), bodies);
        if (eventFile.is_open()) recorder.writeRows(eventFile, step, world.time(), names);
        if (jointFile.is_open()) writeJointRows(jointFile, step, world.time(), joints);
        if (particleFile.is_open()) writeParticleRows(particleFile, step, world.time(), world);
    }
    if (o.hash) {
        char text[32];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(stateHash(bodies)));
        std::cout << "state-hash " << text << '\n';
    }
    if (&out == &discard) return 0;
    out.flush();
    if (!out) throw Error(ErrorKind::Io, "", (o.outOption->count() ? o.out : std::string("stdout")) + ": write failed");
    eventFile.flush();
    if (eventFile.is_open() && !eventFile) throw Error(ErrorKind::Io, "", o.events + ": write failed");
    jointFile.flush();
    if (jointFile.is_open() && !jointFile) throw Error(ErrorKind::Io, "", o.joints + ": write failed");
    particleFile.flush();
    if (particleFile.is_open() && !particleFile) throw Error(ErrorKind::Io, "", o.particles + ": write failed");
    return 0;
}

}  // namespace

Command addRunCommand(CLI::App& parent) {
    auto o = std::make_shared<RunOptions>();
    CLI::App* app = parent.add_subcommand("run", "Run a scene file and write every body's state per step as CSV");
    app->add_option("SCENE", o->sceneFile, "Scene JSON file (format: see README)")->required();
    o->backendOption = app->add_option("--backend", o->backend, "Backend name (overrides settings.backend)");
    o->stepsOption = app->add_option("--steps", o->steps, "Number of steps (default: one simulated second)");
    o->dtOption = app->add_option("--dt", o->dt, "Time step in seconds (overrides settings.timeStep)");
    o->integratorOption = app->add_option("--integrator", o->integrator,
                                          "Integrator (overrides settings.integrator): " + allowedNames<Integrator>());
    o->outOption = app->add_option("--out", o->out, "CSV output file (default: stdout)");
    o->eventsOption = app->add_option("--events", o->events,
                                      "Also write collision and trigger events as CSV (step,time,phase,bodyA,bodyB; "
                                      "phase enter, stay, exit, trigger_enter or trigger_exit)");
    o->jointsOption = app->add_option("--joints", o->joints,
                                      "Also write every joint per step as CSV (step,time,joint,position,speed,fx,fy,fz,"
                                      "tx,ty,tz: angle in rad or offset in m, its rate, the reaction on bodyB in N and "
                                      "N m, world frame)");
    o->particlesOption = app->add_option("--particles", o->particles,
                                         "Also write every fluid particle and cloth node per step as CSV (step,time,"
                                         "system,index,px,py,pz,vx,vy,vz; system: the fluid's or cloth's name)");
    app->add_flag("--hash", o->hash,
                  "Print `state-hash <16 hex digits>`: a hash of every body's final state (bit-exact; equal for "
                  "two runs of one scene on one backend). Without --out the CSV is then not printed");
    return {app, [o] { return run(*o); }};
}

}  // namespace anyphys::cli
