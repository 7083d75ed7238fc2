// The rows of FieldDef, FluidDef and ClothDef (see anyphys/fields/schema_fields.hpp). None is a
// capability parameter: the layer simulates fields, fluids and cloths itself, on every backend.
#include <string>
#include <vector>

#include "anyphys/fields/schema_fields.hpp"
#include "anyphys/schema/rows.hpp"

namespace anyphys::schema {

const std::vector<Field<FieldDef>>& fieldDefFields() {
    using D = FieldDef;
    using F = Field<D>;
    constexpr std::uint32_t buoyancy = bit(FieldType::Buoyancy), wind = bit(FieldType::Wind),
                            air = bit(FieldType::Drag) | bit(FieldType::Wind), explosion = bit(FieldType::Explosion);
    static const std::vector<F> rows = {
        // Its names through with(): g++ 12 fails (internal compiler error) on `.allowed = fieldTypeNames` here.
        with<D>({.key = "type", .path = "field.type", .type = Type::Enum, .required = true, .honour = Honour::Parent,
                 .ownCode = true},
                Access<D>{}, fieldTypeNames),
        with<D>({.key = "fluidDensity", .path = "field.fluidDensity", .unit = "kg/m^3", .value = 1000.0,
                 .check = Check::Positive, .honour = Honour::Parent, .types = buoyancy},
                member(&D::fluidDensity)),
        {.key = "surface", .path = "field.surface", .type = Type::Object, .unit = "object `{normal, offset}`",
         .defaultText = "`{\"normal\": [0, 1, 0], \"offset\": 0}`", .note = "the fluid's surface, see below",
         .honour = Honour::Parent, .types = buoyancy, .ownCode = true},
        with<D>({.key = "linearDrag", .path = "field.linearDrag", .unit = "1/s", .value = 0.0,
                 .check = Check::NonNegative, .note = "dv/dt = -c f v in the fluid, f the submerged fraction",
                 .honour = Honour::Parent, .types = buoyancy},
                member(&D::linearDrag)),
        with<D>({.key = "angularDrag", .path = "field.angularDrag", .unit = "1/s", .value = 0.0,
                 .check = Check::NonNegative, .note = "dw/dt = -c f w", .honour = Honour::Parent, .types = buoyancy},
                member(&D::angularDrag)),
        with<D>({.key = "velocity", .path = "field.velocity", .type = Type::Vec3, .unit = "m/s, world frame",
                 .value = Vec3(0, 0, 0), .check = Check::Finite, .note = "in the XY plane in a planar world",
                 .honour = Honour::Parent, .types = wind},
                member(&D::velocity)),
        with<D>({.key = "airDensity", .path = "field.airDensity", .unit = "kg/m^3", .value = 1.2,
                 .check = Check::Positive,
                 .note = "drag F = -0.5 rho Cd A |v| v (wind: on the velocity relative to the wind)",
                 .honour = Honour::Parent, .types = air},
                member(&D::airDensity)),
        with<D>({.key = "center", .path = "field.center", .type = Type::Vec3, .unit = "m, world frame",
                 .value = Vec3(0, 0, 0), .check = Check::Coordinate, .note = "z = 0 in a planar world",
                 .honour = Honour::Parent, .types = explosion},
                member(&D::center)),
        with<D>({.key = "time", .path = "field.time", .unit = "s", .value = 0.0, .check = Check::NonNegative,
                 .note = "fires in the step whose start t has t <= time < t + dt", .honour = Honour::Parent,
                 .types = explosion},
                member(&D::time)),
        with<D>({.key = "impulse", .path = "field.impulse", .unit = "N s", .value = 0.0, .check = Check::NonNegative,
                 .note = "at the centre, falling linearly to 0 at `radius`", .honour = Honour::Parent,
                 .types = explosion},
                member(&D::impulse)),
        with<D>({.key = "radius", .path = "field.radius", .unit = "m", .value = 1.0, .check = Check::Length,
                 .honour = Honour::Parent, .types = explosion},
                member(&D::radius)),
    };
    return rows;
}

const std::vector<Field<FieldDef>>& fieldSurfaceFields() {
    using D = FieldDef;
    static const std::vector<Field<D>> rows = {
        with<D>({.key = "normal", .path = "field.surface.normal", .type = Type::Vec3, .value = Vec3(0, 1, 0),
                 .check = Check::Finite,
                 .note = "unit (norm 1 within 1e-6), pointing out of the fluid; in the XY plane in a planar world",
                 .honour = Honour::Parent},
                member(&D::surfaceNormal)),
        with<D>({.key = "offset", .path = "field.surface.offset", .unit = "m", .value = 0.0,
                 .check = Check::Coordinate, .note = "the fluid is where `normal . x < offset`",
                 .honour = Honour::Parent},
                member(&D::surfaceOffset)),
    };
    return rows;
}

const std::vector<Field<FluidDef>>& fluidDefFields() {
    using D = FluidDef;
    static const std::vector<Field<D>> rows = {
        with<D>({.key = "name", .path = "fluid.name", .type = Type::String, .value = std::string(""),
                 .note = "the `system` column of `anyphys run --particles`", .honour = Honour::Parent},
                member(&D::name)),
        {.key = "box", .path = "fluid.box", .type = Type::Object, .unit = "object `{min, max}`", .required = true,
         .note = "the box the fluid fills at start, see below", .honour = Honour::Parent, .ownCode = true},
        with<D>({.key = "spacing", .path = "fluid.spacing", .unit = "m", .value = 0.05, .check = Check::Positive,
                 .note = "the box may hold at most 200000 particles", .honour = Honour::Parent},
                member(&D::spacing)),
        with<D>({.key = "density", .path = "fluid.density", .unit = "kg/m^3", .value = 1000.0, .check = Check::Positive,
                 .note = "rest density", .honour = Honour::Parent},
                member(&D::density)),
        with<D>({.key = "viscosity", .path = "fluid.viscosity", .unit = "Pa s", .value = 0.001,
                 .check = Check::NonNegative, .note = "dynamic viscosity", .honour = Honour::Parent},
                member(&D::viscosity)),
    };
    return rows;
}

const std::vector<Field<FluidDef>>& fluidBoxFields() {
    using D = FluidDef;
    static const std::vector<Field<D>> rows = {
        with<D>({.key = "min", .path = "fluid.box.min", .type = Type::Vec3, .unit = "m, world frame",
                 .value = Vec3(-0.5, 0, -0.5), .required = true, .check = Check::Coordinate, .honour = Honour::Parent},
                member(&D::boxMin)),
        with<D>({.key = "max", .path = "fluid.box.max", .type = Type::Vec3, .unit = "m, world frame",
                 .value = Vec3(0.5, 1, 0.5), .required = true, .check = Check::Coordinate,
                 .note = "> `min` in every coordinate", .honour = Honour::Parent},
                member(&D::boxMax)),
    };
    return rows;
}

const std::vector<Field<ClothDef>>& clothDefFields() {
    using D = ClothDef;
    static const std::vector<Field<D>> rows = {
        with<D>({.key = "name", .path = "cloth.name", .type = Type::String, .value = std::string(""),
                 .note = "the `system` column of `anyphys run --particles`", .honour = Honour::Parent},
                member(&D::name)),
        with<D>({.key = "corner", .path = "cloth.corner", .type = Type::Vec3, .unit = "m, world frame",
                 .value = Vec3(0, 2, 0), .check = Check::Coordinate, .note = "z = 0 in a planar world",
                 .honour = Honour::Parent},
                member(&D::corner)),
        {.key = "size", .path = "cloth.size", .type = Type::Object, .unit = "m, `[along axisU, along axisV]`",
         .defaultText = "`[2, 1]`", .note = "both > 0", .honour = Honour::Parent, .ownCode = true},
        {.key = "resolution", .path = "cloth.resolution", .type = Type::Object, .unit = "cells, `[along U, along V]`",
         .defaultText = "`[20, 10]`", .note = "integers in [1, 1000]", .honour = Honour::Parent, .ownCode = true},
        with<D>({.key = "axisU", .path = "cloth.axisU", .type = Type::Vec3, .value = Vec3(1, 0, 0),
                 .check = Check::Finite, .note = "unit (norm 1 within 1e-6); without Z in a planar world",
                 .honour = Honour::Parent},
                member(&D::axisU)),
        with<D>({.key = "axisV", .path = "cloth.axisV", .type = Type::Vec3, .value = Vec3(0, -1, 0),
                 .check = Check::Finite,
                 .note = "unit, perpendicular to `axisU` (cosine within 1e-6 of 0); without Z in a planar world",
                 .honour = Honour::Parent},
                member(&D::axisV)),
        with<D>({.key = "areaDensity", .path = "cloth.areaDensity", .unit = "kg/m^2", .value = 0.2,
                 .check = Check::Positive, .honour = Honour::Parent},
                member(&D::areaDensity)),
        with<D>({.key = "stiffness", .path = "cloth.stiffness", .unit = "N/m", .value = 1e4, .check = Check::Positive,
                 .note = "stretch stiffness, force per unit width per unit strain", .honour = Honour::Parent},
                member(&D::stiffness)),
        with<D>({.key = "bending", .path = "cloth.bending", .unit = "1", .value = 0.01, .check = Check::UnitInterval,
                 .note = "the bending springs' stiffness as a fraction of the stretch springs'",
                 .honour = Honour::Parent},
                member(&D::bending)),
        with<D>({.key = "damping", .path = "cloth.damping", .unit = "1/s", .value = 0.1, .check = Check::NonNegative,
                 .note = "the nodes' velocity decays at this rate", .honour = Honour::Parent},
                member(&D::damping)),
        with<D>({.key = "thickness", .path = "cloth.thickness", .unit = "m", .value = 0.01, .check = Check::Positive,
                 .note = "how far nodes keep from rigid shapes", .honour = Honour::Parent},
                member(&D::thickness)),
        {.key = "pinned", .path = "cloth.pinned", .type = Type::Object, .unit = "`[[i, j], ...]`",
         .defaultText = "none", .note = "nodes held where they start; each within the resolution",
         .honour = Honour::Parent, .ownCode = true},
    };
    return rows;
}

}  // namespace anyphys::schema
