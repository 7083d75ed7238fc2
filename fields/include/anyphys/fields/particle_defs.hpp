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
inline void validate(const FluidDef& f, const std::string& path) {
    using namespace detail;
    requireCoordinate(path + ".box.min", f.boxMin);
    requireCoordinate(path + ".box.max", f.boxMax);
    requirePositive(path + ".spacing", f.spacing);
    requirePositive(path + ".density", f.density);
    requireNonNegative(path + ".viscosity", f.viscosity);
    for (int k = 0; k < 3; ++k)
        if (!(f.boxMax[k] > f.boxMin[k]))
            throw Error::invalid(path + ".box.max", formatVec3(f.boxMax),
                                 "must exceed box.min " + formatVec3(f.boxMin) + " in every coordinate");
    double count = 1.0;
    for (int k = 0; k < 3; ++k) count *= std::max(1.0, std::floor((f.boxMax[k] - f.boxMin[k]) / f.spacing));
    if (count > static_cast<double>(kMaxParticles))
        throw Error::invalid(path + ".spacing", f.spacing,
                             "gives " + std::to_string(static_cast<long long>(count)) + " particles in the box; at most " +
                                 std::to_string(kMaxParticles) + " are allowed");
}

/// Checks a cloth, naming fields under `path`.
inline void validate(const ClothDef& c, const std::string& path) {
    using namespace detail;
    requireCoordinate(path + ".corner", c.corner);
    for (int k = 0; k < 2; ++k) {
        requirePositive(path + ".size[" + std::to_string(k) + "]", c.size[k]);
        if (c.resolution[k] < 1 || c.resolution[k] > 1000)
            throw Error::invalid(path + ".resolution[" + std::to_string(k) + "]", std::to_string(c.resolution[k]),
                                 "must be an integer in [1, 1000]");
    }
    for (const auto& [field, axis] : {std::pair{".axisU", c.axisU}, std::pair{".axisV", c.axisV}}) {
        requireFinite(path + field, axis);
        if (std::abs(axis.norm() - 1.0) > 1e-6)
            throw Error::invalid(path + field, formatVec3(axis), "must be a unit vector (norm 1 within 1e-6)");
    }
    if (std::abs(c.axisU.dot(c.axisV)) > 1e-6)
        throw Error::invalid(path + ".axisV", formatVec3(c.axisV), "must be perpendicular to axisU " + formatVec3(c.axisU));
    requirePositive(path + ".areaDensity", c.areaDensity);
    requirePositive(path + ".stiffness", c.stiffness);
    requireNonNegative(path + ".bending", c.bending);
    if (c.bending > 1.0) throw Error::invalid(path + ".bending", c.bending, "must be in [0, 1]");
    requireNonNegative(path + ".damping", c.damping);
    requirePositive(path + ".thickness", c.thickness);
    for (std::size_t n = 0; n < c.pinned.size(); ++n) {
        const auto& p = c.pinned[n];
        if (p[0] < 0 || p[0] > c.resolution[0] || p[1] < 0 || p[1] > c.resolution[1])
            throw Error::invalid(path + ".pinned[" + std::to_string(n) + "]",
                                 "[" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + "]",
                                 "must name a node [i, j] with 0 <= i <= " + std::to_string(c.resolution[0]) +
                                     " and 0 <= j <= " + std::to_string(c.resolution[1]));
    }
}

}  // namespace anyphys
