#pragma once
// ODE's process-wide initialisation, its per-thread data and its one global random generator.
#include <mutex>

namespace anyphys::ode {

/// Initialises ODE once per process (thread-safe) and its per-thread collision data for the
/// calling thread. Every world calls it before touching ODE.
void ensureOdeInitialised();
/// ODE's per-thread collision data for the calling thread, allocated on its first call there and
/// freed when the thread ends. A world may be created on one thread and stepped or queried on
/// another (one thread at a time), so every step and query calls it; cheap after the first call.
void ensureOdeThreadData();
/// ODE's random generator (quickstep's row shuffle) is one global; a world swaps its own stream in
/// for its step under this lock, so two worlds stepping on two threads neither race on it nor
/// change each other's results (docs/threads.md).
std::mutex& odeRandomMutex();
/// How many messages ODE has sent (printed or not) in this process: for tests.
long odeMessagesReceived();
/// How many times ODE reported a failed LCP (d_ERR_LCP, from dWorldStep's Dantzig solver) on the
/// calling thread: ODE sends its messages on the thread that steps.
long odeLcpFailuresOnThisThread();

}  // namespace anyphys::ode
