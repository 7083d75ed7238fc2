#pragma once
// The rows of BodyDef and of ShapeDef, in the order scene files write them (see schema.hpp), defined in
// api/src/schema/body_fields.cpp.
#include <vector>

#include "anyphys/defs.hpp"
#include "anyphys/schema.hpp"

namespace anyphys::schema {

const std::vector<Field<BodyDef>>& bodyFields();
const std::vector<Field<ShapeDef>>& shapeFields();

}  // namespace anyphys::schema
