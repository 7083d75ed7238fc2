#pragma once
// The rows of FieldDef, FluidDef and ClothDef (see anyphys/schema.hpp), in the order scene files
// write them; defined in fields/src/schema/fields_rows.cpp. They live in fields/ because api/ may
// not know these defs. A FieldDef row's `types` are the field types that have it
// (bit(FieldType)). Objects ("surface", "box") have tables of their own, on the same def.
#include <cstdint>
#include <vector>

#include "anyphys/fields/field_def.hpp"
#include "anyphys/fields/particle_defs.hpp"
#include "anyphys/schema.hpp"

namespace anyphys::schema {

const std::vector<Field<FieldDef>>& fieldDefFields();
const std::vector<Field<FieldDef>>& fieldSurfaceFields();  ///< the keys of a buoyancy field's "surface"
const std::vector<Field<FluidDef>>& fluidDefFields();
const std::vector<Field<FluidDef>>& fluidBoxFields();      ///< the keys of a fluid's "box"
const std::vector<Field<ClothDef>>& clothDefFields();

/// Bit of a field type in Field::types of a FieldDef row.
constexpr std::uint32_t bit(FieldType t) { return 1u << static_cast<unsigned>(t); }

}  // namespace anyphys::schema
