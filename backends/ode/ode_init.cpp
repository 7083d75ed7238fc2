#include "ode_init.hpp"

#include <ode/ode.h>

namespace anyphys::ode {

void ensureOdeInitialised() {
    // dInitODE2 must run once before any ODE call. dCloseODE is never called: worlds of this
    // and other backends may live until exit, and ODE's globals stay reachable from its statics
    // (so LeakSanitizer does not report them).
    static const bool initialised = [] {
        dInitODE2(0);
        return true;
    }();
    (void)initialised;
    // Collision caches are per thread: a world stepped from another thread needs its own.
    // Cheap when already allocated for this thread.
    dAllocateODEDataForThread(dAllocateMaskAll);
}

}  // namespace anyphys::ode
