// The rows of BodyDef and of ShapeDef, in the order scene files write them (see schema.hpp).
#include <string>
#include <vector>

#include "anyphys/defs.hpp"
#include "anyphys/schema/body_fields.hpp"
#include "anyphys/schema/rows.hpp"

namespace anyphys::schema {

const std::vector<Field<BodyDef>>& bodyFields() {
    using B = BodyDef;
    using F = Field<B>;
    static const std::vector<F> rows = {
        {.key = "name", .path = "body.name", .type = Type::String, .required = true,
         .note = "unique in the file; used by `anyphys run` output (from C++ optional, default `\"\"`)",
         .honour = Honour::Layer, .ownCode = true},
        with<B>({.key = "type", .path = "body.type", .type = Type::Enum, .value = std::string("dynamic")},
                member(&B::type), allowedNames<BodyType>),
        with<B>({.key = "position", .path = "body.position", .type = Type::Vec3, .unit = "m, world frame",
                 .value = Vec3(0, 0, 0), .check = Check::Coordinate,
                 .note = "where the body frame's origin is (shapes are placed from it)"},
                member(&B::position)),
        with<B>({.key = "orientation", .path = "body.orientation", .type = Type::Quat, .unit = "`[w, x, y, z]`",
                 .value = Quat::Identity(), .check = Check::UnitQuaternion, .note = "body -> world"},
                member(&B::orientation)),
        with<B>({.key = "linearVelocity", .path = "body.linearVelocity", .type = Type::Vec3, .unit = "m/s, world frame",
                 .value = Vec3(0, 0, 0), .check = Check::Finite,
                 .note = "magnitude <= `settings.maxSpeed`; zero for static bodies"},
                member(&B::linearVelocity)),
        with<B>({.key = "angularVelocity", .path = "body.angularVelocity", .type = Type::Vec3,
                 .unit = "rad/s, world frame", .value = Vec3(0, 0, 0), .check = Check::Finite,
                 .note = "magnitude <= `settings.maxAngularSpeed`; zero for static bodies"},
                member(&B::angularVelocity)),
        {.key = "shape", .path = "body.shape", .type = Type::Object, .unit = "object", .required = true,
         .note = "see [shapes](#shapes)", .ownCode = true},
        with<B>({.key = "mass", .path = "body.mass", .unit = "kg", .defaultText = "derived: `density` x the shape's volume",
                 .check = Check::Positive, .save = Save::WhenSet},
                member(&B::mass)),
        with<B>({.key = "density", .path = "body.density", .unit = "kg/m^3",
                 .defaultText = "the material's density, else 1000", .check = Check::Positive, .save = Save::WhenSet},
                member(&B::density)),
        with<B>({.key = "inertia", .path = "body.inertia", .type = Type::Vec3, .unit = "kg m^2",
                 .defaultText = "derived from shape and mass", .check = Check::Positive,
                 .note = "principal moments in the body frame", .save = Save::WhenSet},
                member(&B::inertia)),
        {.key = "material", .path = "body.material", .type = Type::String, .unit = "name",
         .value = std::string(""), .defaultText = "`\"\"` (the default material)",
         .note = "a key of `materials`, or `\"\"`", .ownCode = true},
        with<B>({.key = "linearDamping", .path = "body.linearDamping", .unit = "1/s", .value = 0.0,
                 .check = Check::NonNegative, .note = "dv/dt = -c v"},
                member(&B::linearDamping)),
        with<B>({.key = "angularDamping", .path = "body.angularDamping", .unit = "1/s", .value = 0.0,
                 .check = Check::NonNegative, .note = "dw/dt = -c w"},
                member(&B::angularDamping)),
        with<B>({.key = "gravityScale", .path = "body.gravityScale", .unit = "1", .value = 1.0, .check = Check::Within,
                 .bound = 1e3, .note = "multiplies the world's gravity for this body"},
                member(&B::gravityScale)),
        with<B>({.key = "gyroscopic", .path = "body.gyroscopic", .type = Type::Enum, .value = std::string("implicit"),
                 .note = "how the w x (I w) term is integrated"},
                member(&B::gyroscopic), allowedNames<GyroscopicMode>),
        with<B>({.key = "isTrigger", .path = "body.isTrigger", .type = Type::Bool, .value = false,
                 .note = "a sensor reports trigger enter / exit and never collides"},
                member(&B::isTrigger)),
        with<B>({.key = "layer", .path = "body.layer", .type = Type::Bits, .unit = "bits", .value = 1u,
                 .note = "the collision layers the body is on"},
                member(&B::layer)),
        with<B>({.key = "mask", .path = "body.mask", .type = Type::Bits, .unit = "bits", .value = 0xFFFFFFFFu,
                 .defaultText = "`4294967295` (all)", .note = "the layers it collides with"},
                member(&B::mask)),
        with<B>({.key = "allowSleep", .path = "body.allowSleep", .type = Type::Bool, .value = true,
                 .note = "may fall asleep when at rest"},
                member(&B::allowSleep)),
        with<B>({.key = "isAwake", .path = "body.isAwake", .type = Type::Bool, .value = true, .note = "starts awake"},
                member(&B::isAwake)),
        with<B>({.key = "dragCoefficient", .path = "body.dragCoefficient", .unit = "1",
                 .defaultText = "by shape: sphere 0.47, box 1.05, capsule 0.82, convex 0.8 (a compound: its first child's)",
                 .check = Check::NonNegative, .note = "Cd of `drag` and `wind` fields", .honour = Honour::Layer,
                 .save = Save::WhenSet},
                member(&B::dragCoefficient)),
        {.key = "userData", .path = "body.userData", .type = Type::Object, .unit = "any JSON value", .defaultText = "none",
         .note = "the game's: kept as JSON text (`Scene::bodyUserData`, by body name) and saved back as it came; an "
                 "unsigned integer is also `BodyDef::userData`, which `Body::userData()` returns",
         .honour = Honour::Layer, .save = Save::WhenSet, .ownCode = true},
    };
    return rows;
}

const std::vector<Field<ShapeDef>>& shapeFields() {
    using S = ShapeDef;
    using F = Field<S>;
    constexpr std::uint32_t spheres = bit(ShapeType::Sphere) | bit(ShapeType::Capsule);
    static const std::vector<F> rows = {
        {.key = "type", .path = "body.shape.type", .type = Type::Enum, .required = true,
         .honour = Honour::Parent, .ownCode = true, .allowed = allowedNames<ShapeType>},
        with<S>({.key = "radius", .path = "body.shape.radius", .unit = "m", .value = kUnset, .required = true,
                 .check = Check::Length, .honour = Honour::Parent, .types = spheres},
                member(&S::radius)),
        with<S>({.key = "halfExtents", .path = "body.shape.halfExtents", .type = Type::Vec3, .unit = "m, along body x, y, z",
                 .value = Vec3::Constant(kUnset), .required = true, .check = Check::Length,
                 .honour = Honour::Parent, .types = bit(ShapeType::Box)},
                member(&S::halfExtents)),
        with<S>({.key = "halfHeight", .path = "body.shape.halfHeight", .unit = "m", .value = kUnset,
                 .required = true, .check = Check::LengthOrZero,
                 .note = "half length of the core segment along body Y", .honour = Honour::Parent,
                 .types = bit(ShapeType::Capsule)},
                member(&S::halfHeight)),
        with<S>({.key = "normal", .path = "body.shape.normal", .type = Type::Vec3, .unit = "world frame",
                 .value = Vec3(0, 1, 0), .check = Check::Direction,
                 .note = "a plane has no size; it faces up unless told", .honour = Honour::Parent,
                 .types = bit(ShapeType::Plane)},
                member(&S::normal)),
        with<S>({.key = "offset", .path = "body.shape.offset", .unit = "m", .value = 0.0, .check = Check::Coordinate,
                 .note = "the points p with normal . p = offset; static bodies only", .honour = Honour::Parent,
                 .types = bit(ShapeType::Plane)},
                member(&S::offset)),
        {.key = "points", .path = "body.shape.points", .type = Type::Object, .unit = "m, array of `[x, y, z]`, body frame",
         .required = true, .note = "coordinates within +-1e7; at least 4 points not all in one plane; the shape is their hull",
         .honour = Honour::Parent, .types = bit(ShapeType::Convex), .ownCode = true},
        {.key = "vertices", .path = "body.shape.vertices", .type = Type::Object,
         .unit = "m, array of `[x, y, z]`, body frame", .required = true,
         .note = "non-empty, coordinates within +-1e7; static bodies only", .honour = Honour::Parent,
         .types = bit(ShapeType::Mesh), .ownCode = true},
        {.key = "indices", .path = "body.shape.indices", .type = Type::Object, .unit = "flat array of integers",
         .required = true,
         .note = "a non-empty multiple of 3 (one triangle per three, counter-clockwise seen from outside); each < the "
                 "number of vertices; no zero-area triangle",
         .honour = Honour::Parent, .types = bit(ShapeType::Mesh), .ownCode = true},
        {.key = "shapes", .path = "body.shape.shapes", .type = Type::Object, .unit = "array of child shapes",
         .required = true,
         .note = "at least one child; children are `sphere`, `box`, `capsule` or `convex` (no plane, mesh or nested compound)",
         .honour = Honour::Parent, .types = bit(ShapeType::Compound), .ownCode = true},
        with<S>({.key = "position", .path = "body.shape.position", .type = Type::Vec3, .unit = "m, body frame",
                 .value = Vec3(0, 0, 0), .check = Check::Coordinate, .note = "where the shape sits on the body",
                 .honour = Honour::Parent, .save = Save::WhenNotDefault},
                member(&S::position)),
        with<S>({.key = "orientation", .path = "body.shape.orientation", .type = Type::Quat, .unit = "`[w, x, y, z]`",
                 .value = Quat::Identity(), .check = Check::UnitQuaternion,
                 .note = "the shape's rotation in the body frame", .honour = Honour::Parent,
                 .save = Save::WhenNotDefault},
                member(&S::orientation)),
        // A compound child's own density and surface, each overriding the body's key of the same name.
        with<S>({.key = "density", .path = "body.shape.shapes.density", .unit = "kg/m^3",
                 .defaultText = "the body's `density`, else (when the child names its own `material`) that material's "
                                "density, else the body material's",
                 .check = Check::Positive,
                 .note = "this child's own density (mass properties combine by the parallel-axis theorem)",
                 .honour = Honour::Parent, .save = Save::WhenSet, .childOnly = true},
                member(&S::density)),
        {.key = "material", .path = "body.shape.shapes.material", .type = Type::String, .unit = "name",
         .defaultText = "the body's `material`",
         .note = "a name defined in `materials`: this child's friction and restitution (mixed per pair of touching "
                 "shapes, as bodies' are)",
         .save = Save::WhenSet, .childOnly = true, .ownCode = true},
        with<S>({.key = "isTrigger", .path = "body.shape.shapes.isTrigger", .type = Type::Bool,
                 .defaultText = "the body's `isTrigger`",
                 .note = "`true`: this child is a sensor: it reports trigger enter / exit and never pushes; the body's "
                         "other children still collide",
                 .save = Save::WhenSet, .childOnly = true},
                member(&S::isTrigger)),
        with<S>({.key = "layer", .path = "body.shape.shapes.layer", .type = Type::Bits, .unit = "bits",
                 .defaultText = "the body's `layer`", .note = "this child's collision layer bits", .save = Save::WhenSet,
                 .childOnly = true},
                member(&S::layer)),
        with<S>({.key = "mask", .path = "body.shape.shapes.mask", .type = Type::Bits, .unit = "bits",
                 .defaultText = "the body's `mask`",
                 .note = "the layers this child collides with (`layersCollide` between this child and each shape of "
                         "the other body)",
                 .save = Save::WhenSet, .childOnly = true},
                member(&S::mask)),
    };
    return rows;
}

}  // namespace anyphys::schema
