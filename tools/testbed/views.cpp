#include "views.hpp"

#include <chrono>

namespace anyphys::testbed {
namespace {

WorldSettings settingsFor(const Scene& scene, const std::string& backend, const LiveSettings& live) {
    WorldSettings s = scene.settings;
    s.backend = backend;
    if (live.timeStep) s.timeStep = *live.timeStep;
    if (live.substeps) s.substeps = live.substeps;
    if (live.iterations) s.iterations = live.iterations;
    if (live.solver) s.solver = live.solver;
    if (live.integrator) s.integrator = *live.integrator;
    if (live.effects) s.effects = live.effects;
    return s;
}

std::vector<BodyState> statesOf(const std::vector<Body>& bodies, std::size_t count) {
    std::vector<BodyState> states;
    states.reserve(count);
    for (std::size_t i = 0; i < count && i < bodies.size(); ++i) states.push_back(bodies[i].state());
    return states;
}

}  // namespace

double mechanicalEnergy(const World& world, const std::vector<Body>& bodies, const std::vector<BodyDef>& defs) {
    const Vec3 g = world.settings().gravity;
    double energy = 0.0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        if (b.type() != BodyType::Dynamic) continue;
        const double m = b.massProperties().mass;
        const double scale = i < defs.size() ? defs[i].gravityScale : 1.0;
        energy += 0.5 * m * b.linearVelocity().squaredNorm() + 0.5 * b.angularVelocity().dot(b.angularMomentum()) -
                  m * scale * g.dot(b.centerOfMass());
    }
    return energy;
}

void Views::open(const SceneSource& source, const std::vector<std::string>& backends, const LiveSettings& settings) {
    if (backends.empty() || backends.size() > kMaxViews)
        throw Error("--backends: give 1 to " + std::to_string(kMaxViews) + " backends, got " + std::to_string(backends.size()));
    source_ = source;
    settings_ = settings;
    views_.clear();
    views_.resize(backends.size());
    for (std::size_t i = 0; i < backends.size(); ++i) {
        View& v = views_[i];
        v.backend = backends[i];
        v.sceneName = source.name;
        try {
            const SceneSource own = sceneForBackend(source, backendInfo(v.backend).capabilities);
            v.sceneName = own.name;
            v.sceneFile = own.file;
            v.scene = own.scene;
            v.check = own.check;
        } catch (const Error& e) {
            v.error = e.what();
            continue;
        }
        build(v, nullptr);
    }
}

void Views::reset() {
    for (View& v : views_) {
        if (v.scene.bodies.empty()) continue;  // its scene could not be had (v.error says why)
        v.balls.clear();
        v.timeOffset = 0.0;
        v.history.clear();
        build(v, nullptr);
    }
}

void Views::apply(const LiveSettings& settings) {
    settings_ = settings;
    for (View& v : views_) {
        if (v.scene.bodies.empty()) continue;
        if (!v.world) {  // it did not run with the last settings: start it afresh
            v.balls.clear();
            v.timeOffset = 0.0;
            build(v, nullptr);
            continue;
        }
        const std::vector<BodyState> states = statesOf(v.bodies, v.bodies.size());
        v.timeOffset += v.world->time();
        build(v, &states);
    }
}

void Views::build(View& v, const std::vector<BodyState>* states) {
    v.error.clear();
    v.bodies.clear();
    v.world.reset();
    try {
        v.world = std::make_unique<World>(settingsFor(v.scene, v.backend, settings_), v.scene.materials);
        v.bodies = createSceneObjects(*v.world, v.scene).bodies;
        v.sceneBodies = v.bodies.size();
        for (const BodyDef& ball : v.balls) v.bodies.push_back(v.world->createBody(ball));
        if (states) {
            // Joints were made at the scene's pose (their frames are measured from it); now every
            // body moves to where it was.
            for (std::size_t i = 0; i < v.bodies.size() && i < states->size(); ++i) {
                Body& b = v.bodies[i];
                if (b.type() == BodyType::Static) continue;
                const BodyState& s = (*states)[i];
                b.setTransform(s.position, s.orientation);
                b.setLinearVelocity(s.linearVelocity);
                b.setAngularVelocity(s.angularVelocity);
            }
        } else {
            v.probe = v.check && v.check->makeProbe ? v.check->makeProbe() : nullptr;
            if (v.probe) {
                v.probe->observe(v.time(), statesOf(v.bodies, v.sceneBodies));
                v.checkValue = v.probe->value();
            }
        }
        measure(v);
    } catch (const Error& e) {
        // A scene file's settings are named as the file names them, as `anyphys run` does.
        v.error = v.sceneFile.empty() ? e.what() : asSceneFileError(e, v.sceneFile).what();
        v.world.reset();
        v.bodies.clear();
    }
}

void Views::measure(View& v) {
    std::vector<BodyDef> defs(v.scene.bodies);
    defs.insert(defs.end(), v.balls.begin(), v.balls.end());
    v.energy = mechanicalEnergy(*v.world, v.bodies, defs);
}

void Views::step(const std::function<void(View&)>& beforeStep) {
    for (View& v : views_) {
        if (!v.world) continue;
        try {
            if (beforeStep) beforeStep(v);
            const auto start = std::chrono::steady_clock::now();
            v.world->step();
            v.lastStepMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            v.meanStepMs = v.history.empty() ? v.lastStepMs : 0.95 * v.meanStepMs + 0.05 * v.lastStepMs;
            if (v.probe) {
                v.probe->observe(v.time(), statesOf(v.bodies, v.sceneBodies));
                v.checkValue = v.probe->value();
            }
            measure(v);
            v.history.push_back(HistorySample{float(v.lastStepMs), float(v.energy)});
            while (v.history.size() > kHistory) v.history.pop_front();
        } catch (const Error& e) {
            v.error = std::string("step: ") + e.what();
            v.world.reset();
            v.bodies.clear();
        }
    }
}

void Views::shootBall(const Vec3& position, const Vec3& velocity) {
    for (View& v : views_) {
        if (!v.world) continue;
        BodyDef ball;
        ball.name = "ball_" + std::to_string(v.balls.size());
        ball.shape = ShapeDef::sphere(0.2);
        ball.density = 3000.0;
        ball.position = position;
        ball.linearVelocity = velocity;
        if (v.world->settings().planar) {
            ball.position.z() = 0.0;
            ball.linearVelocity.z() = 0.0;
        }
        try {
            v.bodies.push_back(v.world->createBody(ball));
            v.balls.push_back(ball);
        } catch (const Error& e) {
            v.error = std::string("ball: ") + e.what();
        }
    }
}

}  // namespace anyphys::testbed
