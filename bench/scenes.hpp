#pragma once
// The benchmark scenes, defined once for every program (through anyphys and on the raw engines),
// so each engine gets the same boxes at the same places. drop1000, pyramid3d and pyramid_planar
// are exactly the layouts of the peer timing harness (shared/peers/scene_common.h: same
// arithmetic, the pyramid in float as in Box2D v3 / Box3D); the others extend them.
//
// Every scene: unit cubes (half extent 0.5 m) on a static ground box centred at (0, -1, 0) whose
// top face is y = 0, gravity (0, -9.81, 0), dt 1/60, friction 0.6 (the default material),
// restitution 0, sleeping off (allowSleep = false on every box).
#include <stdexcept>
#include <string>
#include <vector>

#include "anyphys/defs.hpp"
#include "anyphys/mass_properties.hpp"
#include "anyphys/math.hpp"

namespace anyphys::bench {

inline constexpr double kGravity = -9.81;         ///< m/s^2 along y
inline constexpr double kTimeStep = 1.0 / 60.0;   ///< s
inline constexpr double kHalf = 0.5;              ///< m, half extent of every box
inline constexpr double kFriction = 0.6;          ///< the default material's friction
inline constexpr double kMovedDistance = 0.25;    ///< m: a box "moved" when it ends this far sideways
inline constexpr double kSettledSpeed = 0.05;     ///< m/s: "settled" when every box is slower

struct ScenePlan {
    std::string name;
    bool planar = false;       ///< XY-plane scene (settings.planar; 2D engines)
    int steps = 0;             ///< steps of kTimeStep in a full run
    double density = 0.0;      ///< kg/m^3 (a 2D engine gets the same mass per box)
    Vec3 groundHalf;           ///< half extents of the ground box, centre (0, -1, 0)
    std::vector<Vec3> starts;  ///< box centres

    int count() const { return static_cast<int>(starts.size()); }
    /// kg and kg m^2 (principal, about the centre) of each box, by the layer's own formulas, so a
    /// raw engine gets the very numbers anyphys hands its backend.
    double mass() const { return density * shapeVolume(box()); }
    Vec3 inertia() const { return mass() * unitInertia(box()); }
    static ShapeDef box() { return ShapeDef::box(Vec3::Constant(kHalf)); }
};

/// `layers` layers of `nx` x `nz` boxes with 0.1 m gaps, the lowest 0.1 m above the ground
/// (scene_common.h's drop1000 for 10 x 10 x 10; nz = 1 puts one row in the XY plane).
inline std::vector<Vec3> dropGrid(int layers, int nx, int nz) {
    std::vector<Vec3> starts;
    starts.reserve(static_cast<std::size_t>(layers * nx * nz));
    const double cx = 0.5 * (nx - 1), cz = 0.5 * (nz - 1);
    for (int j = 0; j < layers; ++j)
        for (int i = 0; i < nx; ++i)
            for (int k = 0; k < nz; ++k)
                starts.emplace_back((i - cx) * 1.1, 0.6 + j * 1.1, nz == 1 ? 0.0 : (k - cz) * 1.1);
    return starts;
}

/// Box2D v3's / Box3D's CreateLargePyramid (shared/benchmarks.c), in float as there: touching
/// boxes, `baseCount` in the lowest row.
inline std::vector<Vec3> pyramid(int baseCount) {
    std::vector<Vec3> starts;
    const float a = 0.5f, shift = 1.0f * a;
    for (int i = 0; i < baseCount; ++i) {
        const float y = (2.0f * i + 1.0f) * shift;
        for (int j = i; j < baseCount; ++j) {
            const float x = (i + 1.0f) * shift + 2.0f * (j - i) * shift - a * baseCount;
            starts.emplace_back(x, y, 0.0);
        }
    }
    return starts;
}

/// The scenes by name:
///   drop1000          10 layers of 10 x 10, density 1000, ground half (50,1,50), 600 steps
///   drop10000         10 layers of 40 x 25 (10 000 boxes), otherwise as drop1000, 300 steps
///   drop50000         10 layers of 100 x 50, ground half (100,1,100), 300 steps (scaling)
///   drop_planar       10 layers of 100 in the XY plane, density 1000, ground half (100,1,1), 600 steps
///   pyramid3d         Box3D's large_pyramid: 100 rows, 5 050 cubes, density 100, ground half (400,1,400), 300 steps
///   pyramid_planar    the same positions, planar, density 1, ground half (100,1,1), 300 steps
///   pyramid20         the 20-row pyramid (210 cubes), otherwise as pyramid3d
///   pyramid20_planar  the 20-row pyramid, otherwise as pyramid_planar
///   drop200           8 layers of 5 x 5, otherwise as drop1000, 300 steps (the effects benchmark)
///   drop200_planar    10 layers of 20 in the XY plane, otherwise as drop_planar, 300 steps
inline ScenePlan makeScene(const std::string& name) {
    const Vec3 wideGround(400, 1, 400), planarGround(100, 1, 1);
    if (name == "drop1000") return {name, false, 600, 1000.0, Vec3(50, 1, 50), dropGrid(10, 10, 10)};
    if (name == "drop10000") return {name, false, 300, 1000.0, Vec3(50, 1, 50), dropGrid(10, 40, 25)};
    if (name == "drop50000") return {name, false, 300, 1000.0, Vec3(100, 1, 100), dropGrid(10, 100, 50)};
    if (name == "drop_planar") return {name, true, 600, 1000.0, planarGround, dropGrid(10, 100, 1)};
    if (name == "pyramid3d") return {name, false, 300, 100.0, wideGround, pyramid(100)};
    if (name == "pyramid_planar") return {name, true, 300, 1.0, planarGround, pyramid(100)};
    if (name == "pyramid20") return {name, false, 300, 100.0, wideGround, pyramid(20)};
    if (name == "pyramid20_planar") return {name, true, 300, 1.0, planarGround, pyramid(20)};
    if (name == "drop200") return {name, false, 300, 1000.0, Vec3(50, 1, 50), dropGrid(8, 5, 5)};
    if (name == "drop200_planar") return {name, true, 300, 1000.0, planarGround, dropGrid(10, 20, 1)};
    throw std::invalid_argument("unknown benchmark scene " + name);
}

/// The scenes of the main table, in the order they are reported.
inline const std::vector<std::string>& tableScenes() {
    static const std::vector<std::string> names = {"drop1000",  "drop10000",        "pyramid20", "pyramid3d",
                                                   "drop_planar", "pyramid20_planar", "pyramid_planar"};
    return names;
}

/// The per-body cost series: the same 10-layer drop at growing footprints.
inline const std::vector<std::string>& scalingScenes() {
    static const std::vector<std::string> names = {"drop1000", "drop10000", "drop50000"};
    return names;
}

}  // namespace anyphys::bench
