// Validation of fields, fluids and cloths: each member's own rule from its row
// (anyphys/fields/schema_fields.hpp); the rules between members are code here.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include "anyphys/checks.hpp"
#include "anyphys/fields/schema_fields.hpp"

namespace anyphys {

using schema::checkFields;
using schema::checkRow;
using schema::clothDefFields;
using schema::fieldDefFields;
using schema::fieldSurfaceFields;
using schema::fluidBoxFields;
using schema::fluidDefFields;

/// Checks the members `type` uses, naming them under `path` ("fields[2].radius: must be > 0, got
/// -1" from a file, "FieldDef.radius: ..." from code).
void validate(const FieldDef& f, const std::string& path) {
    const auto& rows = fieldDefFields();
    switch (f.type) {
        case FieldType::Buoyancy:
            checkRow(rows, "fluidDensity", f, path);
            checkRow(fieldSurfaceFields(), "normal", f, path + ".surface");
            if (std::abs(f.surfaceNormal.norm() - 1.0) > 1e-6)
                throw Error::invalid(path + ".surface.normal", formatVec3(f.surfaceNormal), "must be a unit vector (norm 1 within 1e-6)");
            checkRow(fieldSurfaceFields(), "offset", f, path + ".surface");
            checkRow(rows, "linearDrag", f, path);
            checkRow(rows, "angularDrag", f, path);
            break;
        case FieldType::Drag: checkRow(rows, "airDensity", f, path); break;
        case FieldType::Wind:
            checkRow(rows, "airDensity", f, path);
            checkRow(rows, "velocity", f, path);
            break;
        case FieldType::Explosion:
            for (std::string_view key : {"center", "time", "impulse", "radius"}) checkRow(rows, key, f, path);
            break;
    }
}

/// Checks a fluid, naming fields under `path` ("fluids[0].spacing: must be > 0, got 0").
void validate(const FluidDef& f, const std::string& path) {
    checkFields(fluidBoxFields(), f, path + ".box", [](const auto&) { return true; });
    checkFields(fluidDefFields(), f, path, [](const auto&) { return true; });
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
void validate(const ClothDef& c, const std::string& path) {
    using namespace detail;
    const auto& rows = clothDefFields();
    checkRow(rows, "corner", c, path);
    for (int k = 0; k < 2; ++k) {
        requirePositive(path + ".size[" + std::to_string(k) + "]", c.size[k]);  // row "size": both > 0
        if (c.resolution[k] < 1 || c.resolution[k] > 1000)
            throw Error::invalid(path + ".resolution[" + std::to_string(k) + "]", std::to_string(c.resolution[k]),
                                 "must be an integer in [1, 1000]");
    }
    for (const auto& [field, axis] : {std::pair{".axisU", c.axisU}, std::pair{".axisV", c.axisV}}) {
        checkRow(rows, std::string_view(field).substr(1), c, path);
        if (std::abs(axis.norm() - 1.0) > 1e-6)
            throw Error::invalid(path + field, formatVec3(axis), "must be a unit vector (norm 1 within 1e-6)");
    }
    if (std::abs(c.axisU.dot(c.axisV)) > 1e-6)
        throw Error::invalid(path + ".axisV", formatVec3(c.axisV), "must be perpendicular to axisU " + formatVec3(c.axisU));
    for (std::string_view key : {"areaDensity", "stiffness", "bending", "damping", "thickness"}) checkRow(rows, key, c, path);
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
