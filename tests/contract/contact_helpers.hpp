#pragma once
// Small builders and measurements shared by the contact-era contract tests (contacts, events,
// materials, sleeping, queries).
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::test {

constexpr double kG = 9.81;  // m/s^2, the default gravity's magnitude

/// Capability text for ANYPHYS_REQUIRE: "" when the backend has all, else what it lacks.
inline std::string lacking(const Capabilities& caps, std::initializer_list<ShapeType> shapes, Effects effects) {
    std::string missing;
    const auto add = [&missing](const std::string& what) { missing += (missing.empty() ? "" : ", ") + what; };
    for (ShapeType s : shapes)
        if (!caps.shapes.contains(s)) add("shape " + std::string(toString(s)));
    for (const EffectName& e : kEffectNames)
        if (effects.has(e.effect) && !caps.effects.has(e.effect)) add("effect " + std::string(e.name));
    return missing;
}

/// The static ground: the plane y = 0.
inline BodyDef groundDef(const std::string& material = "") {
    BodyDef def;
    def.name = "ground";
    def.type = BodyType::Static;
    def.shape = ShapeDef::plane(Vec3(0, 1, 0), 0.0);
    def.material = material;
    return def;
}

inline BodyDef ballDef(const std::string& name, double radius, const Vec3& position, const std::string& material = "") {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::sphere(radius);
    def.position = position;
    def.material = material;
    return def;
}

inline BodyDef boxDef(const std::string& name, const Vec3& half, const Vec3& position, const std::string& material = "") {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::box(half);
    def.position = position;
    def.material = material;
    return def;
}

/// Prints a measured value in the test log, so a run reports numbers, not just pass / fail.
inline void report(const std::string& what, double value, const std::string& unit = "") {
    std::cout << "[ MEASURED ] " << what << " = " << value << (unit.empty() ? "" : " " + unit) << '\n';
}

inline bool finite(const BodyState& s) {
    return s.position.allFinite() && s.orientation.coeffs().allFinite() && s.linearVelocity.allFinite() &&
           s.angularVelocity.allFinite();
}

/// Steps until the body has bounced once and passed its apex (or `maxTime` elapses); returns the
/// highest centre height reached after the bounce (NaN if it never rose again). Sampled once a
/// step, so the apex is read low by at most g dt^2 / 8 (0.34 mm at dt = 1/60).
inline double firstReboundApex(World& world, const Body& body, double maxTime) {
    bool rising = false;
    double apex = std::numeric_limits<double>::quiet_NaN();
    while (world.time() < maxTime) {
        world.step();
        const double y = body.position().y(), vy = body.linearVelocity().y();
        if (!rising && vy > 0) rising = true;
        if (rising) {
            if (!(y <= apex)) apex = y;  // also replaces the initial NaN
            if (vy < 0) break;
        }
    }
    return apex;
}

}  // namespace anyphys::test
