// anyphys_soak: a long run of a ragdoll and box pile with random spawns and removals on each
// backend, checking that resident memory stays flat after warm-up and that every state stays
// finite (docs/reliability.md). The default, 1e6 steps per backend, is the long run; the test
// suite runs a short one (soak.short). Exit 0 when every backend passed, 1 otherwise.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <deque>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/assembly.hpp"

namespace {

using namespace anyphys;

struct Options {
    std::vector<std::string> backends;
    long steps = 1000000;
    long warmup = 0;             // 0: max(1000, steps / 10)
    double growthMiB = 4.0;      // allowed growth of resident memory after warm-up
    unsigned seed = 15;
    int maxRagdolls = 4;
    int maxBoxes = 24;
};

// Resident memory of this process, bytes (Linux /proc/self/statm: pages).
long residentBytes() {
    std::ifstream in("/proc/self/statm");
    long size = 0, resident = 0;
    in >> size >> resident;
    return resident * sysconf(_SC_PAGESIZE);
}

// One spawned thing: a ragdoll (its bodies) or a box.
struct Item {
    std::vector<Body> bodies;
    bool ragdoll = false;
};

struct Report {
    long steps = 0, spawned = 0, removed = 0, fellOut = 0;
    std::size_t peakBodies = 0;
    long warmRss = 0, maxRss = 0;
    double seconds = 0;
};

class Soak {
public:
    Soak(const std::string& backend, const Options& o) : o_(o), random_(o.seed) {
        const BackendInfo info = backendInfo(backend);
        WorldSettings s;
        s.backend = backend;
        s.planar = info.capabilities.dimensions == 2;
        world_ = std::make_unique<World>(s);
        ragdoll_ = builtinAssembly(s.planar ? "ragdoll_planar" : "ragdoll");
        BodyDef ground;
        ground.name = "ground";
        ground.type = BodyType::Static;
        ground.position = Vec3(0, -1, 0);
        ground.shape = ShapeDef::box(Vec3(30, 1, s.planar ? 1 : 30));
        world_->createBody(ground);
    }

    Report run() {
        Report r;
        const long warmup = o_.warmup > 0 ? o_.warmup : std::max(1000L, o_.steps / 10);
        const auto start = std::chrono::steady_clock::now();
        for (long step = 0; step < o_.steps; ++step) {
            if (step % 10 == 0) spawn(r);
            if (step % 15 == 7 && coin(0.5)) removeRandom(r);
            world_->step();  // divergence policy throw: a non-finite or absurd state throws, naming the body
            if (step % 50 == 0) sweep(r);
            r.peakBodies = std::max(r.peakBodies, world_->bodyCount());
            if (step == warmup) r.warmRss = residentBytes();
            if (step > warmup && step % 500 == 0) r.maxRss = std::max(r.maxRss, residentBytes());
            r.steps = step + 1;
        }
        r.maxRss = std::max(r.maxRss, residentBytes());
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return r;
    }

private:
    bool coin(double p) { return std::uniform_real_distribution<double>(0, 1)(random_) < p; }
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random_); }
    // One draw per statement: the arguments of one call run in an order the compiler picks, and a
    // seed must give the same soak with every compiler.
    Vec3 uniformVec3(double lo, double hi) {
        const double x = uniform(lo, hi);
        const double y = uniform(lo, hi);
        const double z = uniform(lo, hi);
        return {x, y, z};
    }

    void spawn(Report& r) {
        const bool planar = world_->settings().planar;
        const double x = uniform(-6, 6);
        const double y = uniform(4, 9);
        const Vec3 at(x, y, planar ? 0 : uniform(-6, 6));
        int ragdolls = 0, boxes = 0;
        for (const Item& i : items_) (i.ragdoll ? ragdolls : boxes)++;
        Item item;
        if (coin(0.3)) {
            if (ragdolls >= o_.maxRagdolls) removeOldest(true, r);
            Scene one;
            appendInstance(one, ragdoll_, Transform{at, Quat::Identity()}, "r" + std::to_string(serial_++) + "/");
            item.bodies = createSceneObjects(*world_, one).bodies;
            item.ragdoll = true;
        } else {
            if (boxes >= o_.maxBoxes) removeOldest(false, r);
            BodyDef box;
            box.name = "box" + std::to_string(serial_++);
            box.position = at;
            const double vx = uniform(-3, 3);
            box.linearVelocity = Vec3(vx, 0, planar ? 0 : uniform(-3, 3));
            box.shape = coin(0.5) ? ShapeDef::box(uniformVec3(0.2, 0.6))
                                  : ShapeDef::sphere(uniform(0.2, 0.5));
            item.bodies.push_back(world_->createBody(box));
        }
        items_.push_back(std::move(item));
        ++r.spawned;
    }

    void remove(std::size_t index, Report& r) {
        for (Body& b : items_[index].bodies)
            if (b.isValid()) world_->destroyBody(b);
        items_.erase(items_.begin() + long(index));
        ++r.removed;
    }
    void removeOldest(bool ragdoll, Report& r) {
        for (std::size_t i = 0; i < items_.size(); ++i)
            if (items_[i].ragdoll == ragdoll) return remove(i, r);
    }
    void removeRandom(Report& r) {
        if (!items_.empty()) remove(std::uniform_int_distribution<std::size_t>(0, items_.size() - 1)(random_), r);
    }
    // Anything that left the ground (thrown off the edge) is removed; every state must be finite.
    void sweep(Report& r) {
        for (std::size_t i = 0; i < items_.size();) {
            bool out = false;
            for (const Body& b : items_[i].bodies) {
                const BodyState s = b.state();
                if (!s.position.allFinite() || !s.linearVelocity.allFinite() || !s.angularVelocity.allFinite())
                    throw Error(ErrorKind::Diverged, b.name(), "soak: body \"" + b.name() + "\" has a non-finite state");
                out = out || s.position.y() < -20;
            }
            if (out) {
                remove(i, r);
                ++r.fellOut;
            } else {
                ++i;
            }
        }
    }

    Options o_;
    std::mt19937 random_;
    std::unique_ptr<World> world_;
    Scene ragdoll_;
    std::deque<Item> items_;
    long serial_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("anyphys_soak: a ragdoll and box pile with random spawns and removals per backend; checks flat memory and finite states");
    app.add_option("--backend", o.backends, "Backends to run (default: every built backend)");
    app.add_option("--steps", o.steps, "Steps per backend (default 1000000: the long run)")->check(CLI::PositiveNumber);
    app.add_option("--warmup", o.warmup, "Steps before memory is measured (default max(1000, steps / 10))");
    app.add_option("--growth-mib", o.growthMiB, "Allowed growth of resident memory after warm-up, MiB (default 4)");
    app.add_option("--seed", o.seed, "Random seed (default 15)");
    CLI11_PARSE(app, argc, argv);
    if (o.backends.empty())
        for (const BackendInfo& b : availableBackends()) o.backends.push_back(b.name);

    int failures = 0;
    for (const std::string& name : o.backends) {
        try {
            const Report r = Soak(name, o).run();
            const double growth = double(r.maxRss - r.warmRss) / (1024.0 * 1024.0);
            const bool flat = growth <= o.growthMiB;
            std::printf("%-7s %ld steps in %.1f s (%.0f steps/s): %ld spawned, %ld removed (%ld fell off), peak %zu bodies; "
                        "resident %.1f MiB after warm-up, max %.1f MiB after (%+.2f MiB) %s\n",
                        name.c_str(), r.steps, r.seconds, r.steps / r.seconds, r.spawned, r.removed, r.fellOut, r.peakBodies,
                        r.warmRss / 1048576.0, r.maxRss / 1048576.0, growth, flat ? "flat" : "GREW");
            if (!flat) {
                std::fprintf(stderr, "anyphys_soak: %s: resident memory grew %.2f MiB after warm-up (allowed %.1f)\n",
                             name.c_str(), growth, o.growthMiB);
                ++failures;
            }
        } catch (const Error& e) {
            std::fprintf(stderr, "anyphys_soak: %s: %s\n", name.c_str(), e.what());
            ++failures;
        }
    }
    return failures == 0 ? 0 : 1;
}
