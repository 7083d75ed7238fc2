#pragma once
// A scene being simulated, whoever simulates it: anyphys on some backend (layer_simulation.hpp)
// or an engine driven directly (direct/*.cpp). measure() times any of them the same way.
#include <string>
#include <vector>

#include "outcome.hpp"

namespace anyphys::bench {

class Simulation {
public:
    virtual ~Simulation() = default;
    /// One step of kTimeStep.
    virtual void step() = 0;
    /// The boxes' states, in the order of the plan's starts (`out` is resized).
    virtual void readBoxes(std::vector<BoxState>& out) const = 0;
    /// The solver configuration that runs, for the label, e.g. "soft_step, 4 substeps x 3 it".
    virtual std::string describe() const = 0;
};

}  // namespace anyphys::bench
