#pragma once
// The special-effect demos (anyphys_effects NAME), each written once against anyphys and run on
// every backend: planar on a 2D engine. effects.cpp dispatches.
#include "demo_support.hpp"

namespace anyphys::demo {

int runBoat(const DemoOptions& o);       ///< a boat on waves: a buoyancy field whose surface rolls
int runDamBreak(const DemoOptions& o);   ///< crates carried by a collapsing water column (fluid)
int runFlag(const DemoOptions& o);       ///< a flag on a pole in the wind (cloth and wind)
int runExplosion(const DemoOptions& o);  ///< an explosion at the foot of a stack of crates

/// A static box between two corners.
Body staticBlock(World& world, const std::string& name, const Vec3& lo, const Vec3& hi);

}  // namespace anyphys::demo
