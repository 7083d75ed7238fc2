#pragma once
// Validation of defs and settings: the rows of the field table (schema/*_fields.hpp) check each
// field; the rules that span fields or depend on a shape's type are code (api/src/validation.cpp).
// Shared by the World (path "BodyDef", "WorldSettings") and the scene loader (path "bodies[3]",
// "settings") so both report the same rule in the same words:
//   "bodies[3].shape.radius: must be > 0, got -1".
#include <cmath>
#include <string>

#include "anyphys/checks.hpp"
#include "anyphys/defs.hpp"
#include "anyphys/error.hpp"
#include "anyphys/world_settings.hpp"

namespace anyphys {

/// `isChild`: the shape is a compound's child (its surface overrides are allowed, nesting is not).
void validate(const ShapeDef& s, const std::string& path, bool isChild = false);
void validate(const BodyDef& b, const std::string& path);
void validate(const WorldSettings& s, const std::string& path);

/// The rules of a body that depend on the world's settings: its initial velocities within the
/// speed ceilings. `settingsPath` names the settings in messages ("WorldSettings", "settings").
void validateLimits(const BodyDef& b, const WorldSettings& s, const std::string& path,
                    const std::string& settingsPath);

namespace detail {
// Tolerance for "zero" out-of-plane components of a planar body: rounding of an in-plane value.
inline constexpr double kPlanarTolerance = 1e-9;

inline bool rotatesAboutZOnly(const Quat& q) {
    return std::abs(q.x()) <= kPlanarTolerance && std::abs(q.y()) <= kPlanarTolerance;
}
}  // namespace detail

/// The extra rules of a planar world (WorldSettings::planar): the body lies in the XY plane,
/// turns about Z only and moves in the plane. Messages name the body.
void validatePlanar(const BodyDef& b, const std::string& path);

/// The same for a shape on its own (a query's): a compound's children lie in the plane and turn
/// about Z only; a plane's normal lies in the plane.
void validatePlanar(const ShapeDef& s, const std::string& path);

}  // namespace anyphys
