#pragma once
// The rows of WorldSettings, in the order scene files write them (see schema.hpp), defined in
// api/src/schema/settings_fields.cpp.
// WorldSettings::taskSystem has no row: a pointer to the game's scheduler has no scene-file form.
#include <vector>

#include "anyphys/world_settings.hpp"
#include "anyphys/schema.hpp"

namespace anyphys::schema {

const std::vector<Field<WorldSettings>>& settingsFields();

}  // namespace anyphys::schema
