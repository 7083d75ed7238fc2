#pragma once
// ODE's process-wide initialisation.

namespace anyphys::ode {

/// Initialises ODE once per process (thread-safe) and its per-thread collision data for the
/// calling thread. Every world calls it before touching ODE.
void ensureOdeInitialised();
/// How many messages ODE has sent (printed or not) in this process: for tests.
long odeMessagesReceived();

}  // namespace anyphys::ode
