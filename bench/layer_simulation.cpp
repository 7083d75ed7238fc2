#include "layer_simulation.hpp"

namespace anyphys::bench {

std::string cannotRun(const ScenePlan& plan, const BackendInfo& backend, int workers) {
    const Capabilities& caps = backend.capabilities;
    if (plan.planar && !caps.planar) return "backend " + backend.name + " has no planar worlds";
    if (!plan.planar && caps.dimensions != 3) return "backend " + backend.name + " has no 3D worlds";
    if (workers > 1 && !caps.parameters.contains("settings.workers"))
        return "backend " + backend.name + " does not honour settings.workers";
    return {};
}

WorldSettings pileSettings(const ScenePlan& plan, const std::string& backend, int workers) {
    WorldSettings settings;
    settings.backend = backend;
    settings.planar = plan.planar;
    settings.gravity = Vec3(0, kGravity, 0);
    settings.timeStep = kTimeStep;
    settings.workers = workers;
    return settings;
}

std::vector<Body> createPile(World& world, const ScenePlan& plan, const std::string& material) {
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::box(plan.groundHalf);
    ground.position = Vec3(0, -1, 0);
    ground.material = material;
    world.createBody(ground);

    BodyDef box;
    box.shape = ScenePlan::box();
    box.material = material;
    box.density = plan.density;
    box.allowSleep = false;
    std::vector<Body> boxes;
    boxes.reserve(plan.starts.size());
    for (const Vec3& start : plan.starts) {
        box.position = start;
        boxes.push_back(world.createBody(box));
    }
    return boxes;
}

void readStates(const std::vector<Body>& boxes, std::vector<BoxState>& out) {
    out.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const BodyState s = boxes[i].state();
        out[i] = {s.position, s.orientation, s.linearVelocity};
    }
}

std::string describeSolver(const World& world) {
    const WorldSettings& s = world.settings();  // solver knobs resolved to the backend's defaults
    std::string text = std::string(toString(*s.solver)) + ", " + std::to_string(*s.substeps) + " substeps x " +
                       std::to_string(*s.iterations) + " it";
    if (s.workers > 1) text += ", " + std::to_string(s.workers) + " workers";
    return text;
}

namespace {
WorldSettings layerSettings(const ScenePlan& plan, const std::string& backend, int workers, Listening listening) {
    WorldSettings s = pileSettings(plan, backend, workers);
    s.contactImpulses = listening != Listening::WithoutImpulses;
    return s;
}
}  // namespace

LayerSimulation::LayerSimulation(const ScenePlan& plan, const std::string& backend, int workers, Listening listening)
    // the default material: friction 0.6, restitution 0
    : world_(std::make_unique<World>(layerSettings(plan, backend, workers, listening))),
      boxes_(createPile(*world_, plan)) {
    if (listening != Listening::None) world_->addListener(&events_);
}

void LayerSimulation::readBoxes(std::vector<BoxState>& out) const { readStates(boxes_, out); }

std::string LayerSimulation::describe() const { return describeSolver(*world_); }

}  // namespace anyphys::bench
