#pragma once
// Force fields: buoyancy, air drag, wind and explosions, simulated by the layer above the
// backends from forces, impulses, body states, ray casts and overlap queries, so they run alike
// on every backend. A world runs a field's stage only while it holds a field of that type (or its
// declared effects name it); see docs/fields.md.
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "anyphys/effects.hpp"
#include "anyphys/enums.hpp"
#include "anyphys/error.hpp"
#include "anyphys/math.hpp"
#include "anyphys/validation.hpp"

namespace anyphys {

enum class FieldType {
    Buoyancy,   ///< a fluid below a plane: Archimedes' force at the centre of buoyancy, and drag in the fluid
    Drag,       ///< still air: quadratic drag 0.5 rho Cd A |v| v
    Wind,       ///< moving air: quadratic drag on the velocity relative to the wind
    Explosion,  ///< one impulse on every body within a radius, at a given time
};

struct FieldTypeName {
    FieldType type;
    std::string_view name;
    Effect effect;  ///< the effect a field of this type switches on
};
inline constexpr FieldTypeName kFieldTypeNames[] = {
    {FieldType::Buoyancy, "buoyancy", Effect::Buoyancy},
    {FieldType::Drag, "drag", Effect::Drag},
    {FieldType::Wind, "wind", Effect::Wind},
    {FieldType::Explosion, "explosion", Effect::Explosion},
};

inline std::string_view toString(FieldType t) {
    for (const auto& n : kFieldTypeNames)
        if (n.type == t) return n.name;
    return "unknown";
}
inline std::optional<FieldType> fieldTypeFromString(std::string_view name) {
    for (const auto& n : kFieldTypeNames)
        if (n.name == name) return n.type;
    return std::nullopt;
}
inline std::string fieldTypeNames() {
    std::string out;
    for (const auto& n : kFieldTypeNames) out += (out.empty() ? "" : ", ") + std::string(n.name);
    return out;
}
/// The effect a field type switches on (Effect::Buoyancy, Drag, Wind, Explosion).
inline Effect fieldEffect(FieldType t) {
    for (const auto& n : kFieldTypeNames)
        if (n.type == t) return n.effect;
    return Effect::Drag;
}
/// Every field effect: what the field stage may run.
inline constexpr Effects kFieldEffects =
    Effects(Effect::Buoyancy) | Effects(Effect::Drag) | Effects(Effect::Wind) | Effects(Effect::Explosion);
/// The field effects that act through forces during the step (explosions are impulses before it).
inline constexpr Effects kFieldForceEffects = Effects(Effect::Buoyancy) | Effects(Effect::Drag) | Effects(Effect::Wind);

/// One field. Which members matter depends on `type`; the others keep their defaults (and are
/// neither read nor written in scene files).
struct FieldDef {
    FieldType type = FieldType::Drag;
    // ---- buoyancy ----
    double fluidDensity = 1000.0;            ///< kg/m^3, > 0; default 1000 (water)
    Vec3 surfaceNormal = Vec3(0, 1, 0);      ///< unit normal of the fluid surface, pointing out of the fluid; default +Y
    double surfaceOffset = 0.0;              ///< m, the surface is normal . x == offset, the fluid below it; default 0
    double linearDrag = 0.0;                 ///< 1/s, >= 0: dv/dt = -linearDrag f v in the fluid, f the submerged fraction; default 0
    double angularDrag = 0.0;                ///< 1/s, >= 0: dw/dt = -angularDrag f w; default 0
    // ---- drag and wind ----
    double airDensity = 1.2;                 ///< kg/m^3, > 0; default 1.2 (air at 20 C)
    Vec3 velocity = Vec3::Zero();            ///< m/s, wind: the air's velocity; default 0
    // ---- explosion ----
    Vec3 center = Vec3::Zero();              ///< m, world frame; default origin
    double time = 0.0;                       ///< s, >= 0: fires in the step whose start time t has t <= time < t + dt; default 0
    double impulse = 0.0;                    ///< N s, >= 0: the impulse at the centre, falling linearly to 0 at `radius`; default 0
    double radius = 1.0;                     ///< m, > 0; default 1

    static FieldDef buoyancy(double fluidDensity, const Vec3& normal = Vec3(0, 1, 0), double offset = 0.0,
                             double linearDrag = 0.0, double angularDrag = 0.0) {
        FieldDef f;
        f.type = FieldType::Buoyancy;
        f.fluidDensity = fluidDensity;
        f.surfaceNormal = normal;
        f.surfaceOffset = offset;
        f.linearDrag = linearDrag;
        f.angularDrag = angularDrag;
        return f;
    }
    static FieldDef drag(double airDensity = 1.2) {
        FieldDef f;
        f.type = FieldType::Drag;
        f.airDensity = airDensity;
        return f;
    }
    static FieldDef wind(const Vec3& velocity, double airDensity = 1.2) {
        FieldDef f;
        f.type = FieldType::Wind;
        f.velocity = velocity;
        f.airDensity = airDensity;
        return f;
    }
    static FieldDef explosion(const Vec3& center, double time, double impulse, double radius) {
        FieldDef f;
        f.type = FieldType::Explosion;
        f.center = center;
        f.time = time;
        f.impulse = impulse;
        f.radius = radius;
        return f;
    }
};

/// Default drag coefficients (BodyDef::dragCoefficient unset): 0.47 for a sphere, 1.05 for a box
/// (face on), 0.82 for a capsule (a long cylinder's axial value, between the two), 0.8 for a hull.
inline double defaultDragCoefficient(ShapeType type) {
    switch (type) {
        case ShapeType::Sphere: return 0.47;
        case ShapeType::Box: return 1.05;
        case ShapeType::Capsule: return 0.82;
        default: return 0.8;
    }
}

/// Checks the members `type` uses, naming them under `path` ("fields[2].radius: must be > 0, got
/// -1" from a file, "FieldDef.radius: ..." from code). Rows: schema_fields.hpp.
void validate(const FieldDef& f, const std::string& path);

}  // namespace anyphys
