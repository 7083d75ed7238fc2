#pragma once
// The worlds of the effects benchmark (effects_cost.cpp): a benchmark pile through anyphys, stepped
// either by World::step or by its backend peer directly, and the same pile with one special effect
// (a field, a fluid or a cloth) added.
#include <memory>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "simulation.hpp"

namespace anyphys {
class WorldPeer;
}

namespace anyphys::bench {

/// The special effects the benchmark prices, by the names of its rows.
/// The fields of fields/, and Restitution: every box and the ground of a material with e = 0.5 (no
/// field; what the engines' bounces cost, landings and the rest after them alike).
enum class SpecialEffect { None, Buoyancy, Drag, Wind, Explosion, Fluid, Cloth, Restitution };
const std::vector<std::pair<std::string, SpecialEffect>>& specialEffects();

struct PileOptions {
    bool events = true;                          ///< false: effects declared as derived, minus events
    SpecialEffect effect = SpecialEffect::None;  ///< what is added to the pile
    bool viaPeer = false;                        ///< step the backend peer instead of World::step
};

/// The plan's pile as LayerSimulation builds it (static ground, boxes that never sleep), plus the
/// option's effect. `units()` is what the effect works on: particles, nodes or bodies.
class PileSimulation final : public Simulation {
public:
    PileSimulation(const ScenePlan& plan, const std::string& backend, const PileOptions& options);
    void step() override;
    void readBoxes(std::vector<BoxState>& out) const override;
    std::string describe() const override;
    int units() const { return units_; }

private:
    std::unique_ptr<World> world_;
    WorldPeer* peer_ = nullptr;  // set when the peer is stepped directly
    double time_ = 0.0;          // the peer's clock then (World::time does not advance)
    std::vector<Body> boxes_;
    int units_ = 0;
};

}  // namespace anyphys::bench
