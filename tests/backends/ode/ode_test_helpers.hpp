#pragma once
// What the ODE backend tests share: the backend's peer behind a World.
#include <ode/ode.h>

#include "anyphys/anyphys.hpp"
#include "ode_world.hpp"

namespace anyphys::ode::test {

/// The backend's world behind a World, reached through the escape hatch (the peer registers
/// itself as the dWorld's user data).
inline OdeWorld& peerOf(World& world) { return *static_cast<OdeWorld*>(dWorldGetData(world.native<dxWorld>())); }

/// The API fuzzer's needle: a hull of ten points within a metre and one 1e7 m away, at
/// (-5, -5, -5). libccd's MPR looped for ever on it against a small sphere or capsule.
inline BodyDef needleHullFromTheFuzzer() {
    BodyDef needle;
    needle.position = Vec3(-5, -5, -5);
    needle.shape = ShapeDef::convex({{-0.130045, 0.0762332, -0.058296}, {0.0313901, -0.991031, -1}, {-1, -1, -1},
                                     {-1, -1, -0.55157}, {0.0224215, 0.605381, 0.0672646}, {-0.0403587, 1e7, -0.0852018},
                                     {-0.748879, 0.2287, 0.192825}, {-0.0313901, -0.309417, -0.0493274},
                                     {-0.0493274, -0.0493274, -0.0493274}, {0.0941704, -0.0493274, -0.0493274}});
    return needle;
}

}  // namespace anyphys::ode::test
