#pragma once
// What the ODE backend tests share: the backend's peer behind a World.
#include <ode/ode.h>

#include "anyphys/anyphys.hpp"
#include "ode_world.hpp"

namespace anyphys::ode::test {

/// The backend's world behind a World, reached through the escape hatch (the peer registers
/// itself as the dWorld's user data).
inline OdeWorld& peerOf(World& world) { return *static_cast<OdeWorld*>(dWorldGetData(world.native<dxWorld>())); }

}  // namespace anyphys::ode::test
