#pragma once
// The axes of `anyphys compare --sweep NAME=V1,V2,...`: parsing and checking what is asked for,
// and applying one value of an axis to a world's settings on a given backend.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::cli {

/// One swept setting: its scene-format name and its values, each as typed and normalised.
struct SweepAxis {
    std::string name;                 ///< e.g. "timeStep", "erp", "effectOff"
    std::vector<std::string> given;   ///< as typed, e.g. "1/60"
    std::vector<std::string> values;  ///< normalised: numbers as exactNumber writes them, names as they are
};

/// Parses "NAME=V1,V2,..." naming every value. Throws anyphys::Error naming the option, the
/// value and what is allowed when the name is unknown or a value does not fit it.
SweepAxis parseSweepAxis(const std::string& spec);

/// The names an axis may have, for messages.
std::string allowedAxisNames();

/// The number of a normalised numeric value (what parseSweepAxis produced).
double axisNumber(const std::string& value);

/// Applies `value` of axis `name` to `settings` for a backend with `caps`. Returns why the
/// backend does not honour it, or nothing. `derivedEffects` gives the effects the world derives
/// for the scene (asked only by effectOff).
std::optional<std::string> applyAxisValue(const std::string& name, const std::string& value, const Capabilities& caps,
                                          WorldSettings& settings, const std::function<Effects()>& derivedEffects);

}  // namespace anyphys::cli
