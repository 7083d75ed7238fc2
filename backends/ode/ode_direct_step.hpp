#pragma once
// dWorldStep with a fallback. ODE 0.16's Dantzig LCP gives up on some sets of resting contacts
// ("LCP internal error, s <= 0": a degenerate pivot) and leaves the rows it had not reached
// without force, so a ten-box stack fell through itself (12.8 m in 10 s). A step whose LCP gave
// up is taken again from the same state by quickstep, at the world's `iterations`.
#include <ode/ode.h>

#include <vector>

namespace anyphys::ode {

class OdeBody;

class DirectStepper {
public:
    /// Steps `world` by h with dWorldStep. If ODE reported an LCP failure during it (on this
    /// thread), every body of `bodies` is put back as it was and the step is taken with
    /// dWorldQuickStep instead. Returns true when it fell back.
    bool step(dWorldID world, const std::vector<OdeBody*>& bodies, dReal h);

private:
    struct Saved {
        dBodyID id;
        dReal position[3], quaternion[4], linear[3], angular[3], force[3], torque[3];
        bool enabled;
    };
    std::vector<Saved> saved_;  // capacity kept from step to step
};

}  // namespace anyphys::ode
