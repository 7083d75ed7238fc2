#pragma once
// Particle effects a scene may declare: fluids (position-based fluids) and cloths (a
// position-based sheet). The layer simulates them above the backends and couples them both ways
// with rigid bodies through body states and impulses; see docs/fields.md.
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "anyphys/error.hpp"
#include "anyphys/math.hpp"
#include "anyphys/validation.hpp"

namespace anyphys {

/// Most particles one fluid or cloth may hold: a bound on memory and on the cost of a step.
inline constexpr std::size_t kMaxParticles = 200000;

/// A block of fluid filling an axis-aligned box with particles on a lattice of `spacing`.
struct FluidDef {
    std::string name;                     ///< for --particles output and messages; default ""
    Vec3 boxMin = Vec3(-0.5, 0.0, -0.5);  ///< m, lower corner of the box the fluid fills at start
    Vec3 boxMax = Vec3(0.5, 1.0, 0.5);    ///< m, upper corner (each coordinate > boxMin's)
    double spacing = 0.05;                ///< m, > 0: distance between particles at rest; default 0.05
    double density = 1000.0;              ///< kg/m^3, > 0: rest density; default 1000 (water)
    double viscosity = 0.001;             ///< Pa s, >= 0: dynamic viscosity; default 0.001 (water)
};

/// A rectangular sheet of (resolution[0] + 1) x (resolution[1] + 1) nodes: node (i, j) starts at
/// corner + i size[0] / resolution[0] axisU + j size[1] / resolution[1] axisV.
struct ClothDef {
    std::string name;                            ///< default ""
    Vec3 corner = Vec3(0, 2, 0);                 ///< m, where node (0, 0) starts
    std::array<double, 2> size{2.0, 1.0};        ///< m, > 0: the sheet's extent along axisU and axisV
    std::array<int, 2> resolution{20, 10};       ///< cells along each axis, >= 1
    Vec3 axisU = Vec3(1, 0, 0);                  ///< unit direction of i; default +X
    Vec3 axisV = Vec3(0, -1, 0);                 ///< unit direction of j, perpendicular to axisU; default -Y (a hanging sheet)
    double areaDensity = 0.2;                    ///< kg/m^2, > 0; default 0.2 (a heavy cotton)
    double stiffness = 1e4;                      ///< N/m, > 0: stretch stiffness (force per unit width per unit strain); default 1e4
    double bending = 0.01;                       ///< >= 0: bending springs' stiffness as a fraction of the stretch springs'; default 0.01
    double damping = 0.1;                        ///< 1/s, >= 0: the nodes' velocity decays at this rate; default 0.1
    double thickness = 0.01;                     ///< m, > 0: nodes keep this far from rigid shapes; default 0.01
    std::vector<std::array<int, 2>> pinned;      ///< nodes (i, j) held where they start; default none
};

/// Checks a fluid, naming fields under `path` ("fluids[0].spacing: must be > 0, got 0").
void validate(const FluidDef& f, const std::string& path);
/// Checks a cloth, naming fields under `path`.
void validate(const ClothDef& c, const std::string& path);

}  // namespace anyphys
