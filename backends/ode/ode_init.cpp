#include "ode_init.hpp"

#include <ode/ode.h>

#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>

#include "ode_box_plane.hpp"
#include "ode_convex_capsule.hpp"
#include "ode_convex_sphere.hpp"

namespace anyphys::ode {
namespace {

std::atomic<long> messagesReceived{0};
thread_local long lcpFailures = 0;

// ODE reports solver trouble (for example "LCP internal error, s <= 0" from dWorldStep's Dantzig
// solver) through a message callback that by default prints every occurrence: hundreds of lines
// a second from one stack. Each kind of message (its format text) is printed once per process,
// with a note that repeats are not shown. LCP failures are also counted per thread, for
// DirectStepper to take such a step again.
void reportOnce(int number, const char* format, va_list args) {
    ++messagesReceived;
    if (number == d_ERR_LCP) ++lcpFailures;
    static std::mutex mutex;
    static std::set<std::string> seen;
    {
        std::lock_guard lock(mutex);
        if (!seen.insert(format).second) return;
    }
    char text[512];
    std::vsnprintf(text, sizeof text, format, args);
    std::fprintf(stderr, "anyphys ode: ODE message %d: %s (repeats of this message are not shown)\n", number, text);
}

}  // namespace

long odeMessagesReceived() { return messagesReceived; }

long odeLcpFailuresOnThisThread() { return lcpFailures; }

void ensureOdeInitialised() {
    // dInitODE2 must run once before any ODE call. dCloseODE is never called: worlds of this
    // and other backends may live until exit, and ODE's globals stay reachable from its statics
    // (so LeakSanitizer does not report them).
    static const bool initialised = [] {
        dInitODE2(0);
        dSetMessageHandler(&reportOnce);
        dSetColliderOverride(dConvexClass, dSphereClass, &collideConvexSphere);  // ode_convex_sphere.hpp
        dSetColliderOverride(dConvexClass, dCapsuleClass, &collideConvexCapsule);  // ode_convex_capsule.hpp
        dSetColliderOverride(dBoxClass, dCapsuleClass, &collideBoxCapsule);  // ode_convex_capsule.hpp
        dSetColliderOverride(dBoxClass, dPlaneClass, &collideBoxPlane);  // ode_box_plane.hpp
        return true;
    }();
    (void)initialised;
    ensureOdeThreadData();
}

void ensureOdeThreadData() {
    // Collision caches are per thread: a world stepped from another thread needs its own. The
    // thread_local's destructor frees them when the thread ends (no leak per worker thread).
    struct ThreadData {
        ThreadData() { dAllocateODEDataForThread(dAllocateMaskAll); }
        ~ThreadData() { dCleanupODEAllDataForThread(); }
    };
    thread_local ThreadData data;
    (void)data;
}

std::mutex& odeRandomMutex() {
    static std::mutex mutex;
    return mutex;
}

}  // namespace anyphys::ode
