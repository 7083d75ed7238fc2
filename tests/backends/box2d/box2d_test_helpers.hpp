#pragma once
// Builders shared by the Box2D backend tests: planar worlds and the usual bodies.
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include "anyphys/anyphys.hpp"

namespace anyphys::box2d::test {

constexpr double kG = 9.81;
constexpr double kDegree = std::numbers::pi / 180.0;

inline WorldSettings planarSettings() {
    WorldSettings s;
    s.backend = "box2d";
    s.planar = true;
    return s;
}

inline BodyDef ground(const Vec3& normal = Vec3(0, 1, 0), const std::string& material = "") {
    BodyDef def;
    def.name = "ground";
    def.type = BodyType::Static;
    def.shape = ShapeDef::plane(normal, 0.0);
    def.material = material;
    return def;
}

inline BodyDef ball(const std::string& name, double radius, const Vec3& at, const std::string& material = "") {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::sphere(radius);
    def.position = at;
    def.material = material;
    return def;
}

inline BodyDef box(const std::string& name, const Vec3& half, const Vec3& at, const std::string& material = "") {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::box(half);
    def.position = at;
    def.material = material;
    return def;
}

/// Prints a measured value, so a run reports numbers and not only pass / fail.
inline void report(const std::string& what, double value, const std::string& unit = "") {
    std::cout << "[ MEASURED ] box2d " << what << " = " << value << (unit.empty() ? "" : " " + unit) << '\n';
}

}  // namespace anyphys::box2d::test
