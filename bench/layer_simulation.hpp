#pragma once
// A benchmark scene through anyphys, as game code writes it: a World on one backend with its
// defaults (solver, substeps, iterations; effects derived from content, so contact events are on),
// a static ground box and the plan's boxes with allowSleep = false.
#include <memory>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "simulation.hpp"

namespace anyphys::bench {

/// Why `backend` cannot run the plan with `workers` threads (empty when it can): a planar scene
/// needs planar worlds, a 3D scene 3D ones, and more than one worker the parameter
/// "settings.workers" in the backend's capabilities.
std::string cannotRun(const ScenePlan& plan, const BackendInfo& backend, int workers = 1);

/// The settings every layer run of a plan uses: the plan's gravity, step and plane on `backend`.
WorldSettings pileSettings(const ScenePlan& plan, const std::string& backend, int workers = 1);
/// The plan's static ground and boxes (allowSleep false) in `world`, all of `material` (the
/// default material if empty); returns the boxes.
std::vector<Body> createPile(World& world, const ScenePlan& plan, const std::string& material = {});
/// The boxes' states as Simulation::readBoxes gives them.
void readStates(const std::vector<Body>& boxes, std::vector<BoxState>& out);
/// "soft_step, 8 substeps x 1 it": the solver configuration that runs.
std::string describeSolver(const World& world);

/// Reads every contact event a world delivers, as a game's listener would: counts them and the
/// points of each (so the events must be written, point by point).
class EventCounter final : public ContactEventListener {
public:
    void onContactEvent(const ContactEvent& e) override {
        ++events;
        points += e.points.size();
    }
    std::size_t events = 0, points = 0;
};

/// Who reads a layer run's contact events.
enum class Listening {
    None,                   ///< no one: a step only tracks which pairs touch (World::lastEvents)
    Everything,             ///< an EventCounter: every step writes and delivers its events
    WithoutImpulses,        ///< the same with settings.contactImpulses false (points and depths only)
};

class LayerSimulation final : public Simulation {
public:
    LayerSimulation(const ScenePlan& plan, const std::string& backend, int workers = 1,
                    Listening listening = Listening::None);
    void step() override { world_->step(); }
    void readBoxes(std::vector<BoxState>& out) const override;
    std::string describe() const override;
    const EventCounter& events() const { return events_; }

private:
    std::unique_ptr<World> world_;
    std::vector<Body> boxes_;
    EventCounter events_;
};

}  // namespace anyphys::bench
