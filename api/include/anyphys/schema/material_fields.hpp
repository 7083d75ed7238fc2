#pragma once
// The rows of Material (see schema.hpp), defined in
// api/src/schema/material_fields.cpp. A material takes effect through the bodies that name it
// (`body.material`), so its rows are not capability parameters of their own.
#include <vector>

#include "anyphys/containers/material_library.hpp"
#include "anyphys/schema.hpp"

namespace anyphys::schema {

const std::vector<Field<Material>>& materialFields();

}  // namespace anyphys::schema
