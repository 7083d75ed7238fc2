#pragma once
// The native step as a pipeline of stages. Each stage says whether the world needs it; the
// world runs only the stages that are needed, so an effect that is off costs nothing but the
// one check made when the world's content or effects change.
//
// Order: collide (broad + narrow phase); collect constraints (contacts and joints of the step);
// implicit gyroscopic and integrate for free bodies (once per step: they have nothing to substep
// for); solve constraints (substeps, for the bodies they hold); continuous collision; sleep;
// clear forces.
#include <string_view>

namespace anyphys::native {

class NativeWorld;

struct StepInfo {
    double time = 0.0;  // s, start of the step
    double dt = 0.0;    // s
};

class Stage {
public:
    virtual ~Stage() = default;
    virtual std::string_view name() const = 0;
    virtual bool needed(const NativeWorld& world) const = 0;
    virtual void run(NativeWorld& world, const StepInfo& step) = 0;
};

}  // namespace anyphys::native
