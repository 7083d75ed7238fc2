#pragma once
// Builders shared by the Box2D backend tests: planar worlds and the usual bodies.
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"

namespace anyphys::box2d::test {

using anyphys::test::firstReboundApex;
using anyphys::test::kG;
constexpr double kDegree = std::numbers::pi / 180.0;

inline WorldSettings planarSettings() {
    WorldSettings s;
    s.backend = "box2d";
    s.planar = true;
    return s;
}

/// The static ground: a plane through the origin with this normal (in the XY plane).
inline BodyDef ground(const Vec3& normal = Vec3(0, 1, 0), const std::string& material = "") {
    BodyDef def = anyphys::test::groundDef(material);
    def.shape = ShapeDef::plane(normal, 0.0);
    return def;
}

inline BodyDef ball(const std::string& name, double radius, const Vec3& at, const std::string& material = "") {
    return anyphys::test::ballDef(name, radius, at, material);
}

inline BodyDef box(const std::string& name, const Vec3& half, const Vec3& at, const std::string& material = "") {
    return anyphys::test::boxDef(name, half, at, material);
}

/// Prints a measured value, so a run reports numbers and not only pass / fail.
inline void report(const std::string& what, double value, const std::string& unit = "") {
    anyphys::test::report("box2d " + what, value, unit);
}

}  // namespace anyphys::box2d::test
