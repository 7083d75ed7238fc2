#pragma once
// Definitions ("defs") from which bodies are created. Every field has a documented unit and
// default; a def is a plain value, validated when it is used (see validation.hpp).
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/enums.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

/// The value of a shape's size or direction that was not given: NaN, which validation reports
/// as "not set" naming the field. A shape's sizes have no default, so a box without half extents
/// is an error instead of a silent 1 m cube.
inline constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();

/// A collision shape in the body frame. Which fields matter depends on `type`; the sizes a type
/// needs must be given (the factories below take them), the rest keep their defaults.
struct ShapeDef {
    ShapeType type = ShapeType::Sphere;
    double radius = kUnset;                     ///< m, sphere and capsule, > 0; required
    Vec3 halfExtents = Vec3::Constant(kUnset);  ///< m, box half sizes along body x, y, z, each > 0; required
    double halfHeight = kUnset;                 ///< m, capsule: half length of the core segment along body Y, >= 0; required
    Vec3 normal = Vec3::UnitY();                ///< plane: normal (world frame), non-zero, normalised by the layer; default up (a plane has no size to forget)
    double offset = 0.0;                        ///< m, plane: points p with normal.dot(p) == offset; default 0
    std::vector<Vec3> points;                   ///< m, convex: points (body frame) whose hull is the shape; >= 4, not coplanar
    std::vector<Vec3> vertices;                 ///< m, mesh: vertex positions (body frame)
    std::vector<std::uint32_t> indices;         ///< mesh: three vertex indices per triangle, counter-clockwise seen from outside
    std::vector<ShapeDef> shapes;               ///< compound: child shapes (any type but plane, mesh and compound)
    Vec3 position = Vec3::Zero();               ///< m, compound child: placement in the body frame; default origin
    Quat orientation = Quat::Identity();        ///< compound child: rotation in the body frame; default identity
    std::optional<double> density;              ///< kg/m^3, compound child: its own density; default the body's
                                                ///< (its material's density when it names its own material)
    // A compound child's own surface, each an override of the BodyDef field of the same name
    // (unset: the body's). Only compound children may carry them: a lone shape is the body.
    std::optional<std::string> material;        ///< compound child: name in the world's MaterialLibrary; default the body's
    std::optional<bool> isTrigger;              ///< compound child: a sensor part (trigger events, no response); default the body's
    std::optional<std::uint32_t> layer;         ///< compound child: collision layer bits; default the body's
    std::optional<std::uint32_t> mask;          ///< compound child: layers this child collides with; default the body's

    static ShapeDef sphere(double r) { ShapeDef s; s.type = ShapeType::Sphere; s.radius = r; return s; }
    static ShapeDef box(const Vec3& half) { ShapeDef s; s.type = ShapeType::Box; s.halfExtents = half; return s; }
    static ShapeDef capsule(double r, double halfHeight) {
        ShapeDef s; s.type = ShapeType::Capsule; s.radius = r; s.halfHeight = halfHeight; return s;
    }
    static ShapeDef plane(const Vec3& n, double offset) {
        ShapeDef s; s.type = ShapeType::Plane; s.normal = n; s.offset = offset; return s;
    }
    static ShapeDef convex(std::vector<Vec3> points) {
        ShapeDef s; s.type = ShapeType::Convex; s.points = std::move(points); return s;
    }
    static ShapeDef mesh(std::vector<Vec3> vertices, std::vector<std::uint32_t> indices) {
        ShapeDef s; s.type = ShapeType::Mesh; s.vertices = std::move(vertices); s.indices = std::move(indices); return s;
    }
    static ShapeDef compound(std::vector<ShapeDef> children) {
        ShapeDef s; s.type = ShapeType::Compound; s.shapes = std::move(children); return s;
    }
    /// True when some surface override (material, isTrigger, layer, mask) is set.
    bool overridesSurface() const { return material || isTrigger || layer || mask; }
    /// This shape placed at a pose in the body frame (for compound children).
    ShapeDef placed(const Vec3& at, const Quat& rotation = Quat::Identity()) const {
        ShapeDef s = *this; s.position = at; s.orientation = rotation; return s;
    }
};

/// Everything needed to create a body.
struct BodyDef {
    std::string name;                          ///< optional label (scene files, CSV output); default ""
    BodyType type = BodyType::Dynamic;         ///< default dynamic
    Vec3 position = Vec3::Zero();              ///< m, world frame, the body origin (shapes are placed relative to it); default origin
    Quat orientation = Quat::Identity();       ///< unit quaternion body -> world; default identity
    Vec3 linearVelocity = Vec3::Zero();        ///< m/s, world frame; default 0
    Vec3 angularVelocity = Vec3::Zero();       ///< rad/s, world frame; default 0
    ShapeDef shape;                            ///< required: e.g. ShapeDef::sphere(0.5) (a def without one is refused)
    std::optional<double> mass;                ///< kg; default: density x shape volume
    std::optional<double> density;             ///< kg/m^3; default: the material's density, else 1000
    std::optional<Vec3> inertia;               ///< kg m^2, principal moments in the body frame; default: from shape and mass
    std::string material;                      ///< name in the world's MaterialLibrary; default "" (the library default)
    double linearDamping = 0.0;                ///< 1/s, dv/dt = -c v; default 0
    double angularDamping = 0.0;               ///< 1/s, dw/dt = -c w; default 0
    double gravityScale = 1.0;                 ///< multiplies world gravity for this body; default 1
    /// Drag coefficient for drag and wind fields (fields/), >= 0; default: by shape (0.47 sphere,
    /// 1.05 box, 0.82 capsule, 0.8 convex; a compound takes its first child's).
    std::optional<double> dragCoefficient;
    GyroscopicMode gyroscopic = GyroscopicMode::Implicit;  ///< default implicit (stable, conserves |L| closely)
    bool isTrigger = false;                    ///< a sensor: reports trigger enter / exit, never collides; default false
    std::uint32_t layer = 1;                   ///< collision layer bits; default 1
    std::uint32_t mask = 0xFFFFFFFFu;          ///< layers this body collides with; default all
    bool allowSleep = true;                    ///< may fall asleep when at rest; default true
    bool isAwake = true;                       ///< starts awake; default true
    /// The game's own value, kept for it and never read by anyphys (an entity id, or a pointer
    /// stored as reinterpret_cast<std::uintptr_t>(p)); Body::userData / setUserData. Default 0.
    std::uint64_t userData = 0;
};

/// Two bodies may touch only if each one's layer is in the other's mask. The layer decides
/// this for every backend, so all of them filter identically.
inline bool layersCollide(std::uint32_t layerA, std::uint32_t maskA, std::uint32_t layerB, std::uint32_t maskB) {
    return (layerA & maskB) != 0 && (layerB & maskA) != 0;
}

/// The solved mass properties of a body (what the backend receives).
struct MassProperties {
    double mass = 0.0;                          ///< kg; 0 for static and kinematic bodies
    Vec3 inertia = Vec3::Zero();                ///< kg m^2, principal moments about the centre of mass
    Vec3 centerOfMass = Vec3::Zero();           ///< m, body frame
    Quat principalAxes = Quat::Identity();      ///< rotation from principal axes to the body frame
};

/// A body's kinematic state, world frame. Position is the body origin; linear velocity is that
/// of the centre of mass (they coincide unless a compound shape moves the centre of mass).
struct BodyState {
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
};

}  // namespace anyphys
