// Validation of defs and settings (validation.hpp): the rows of the field table check each field;
// the rules that span fields or depend on a shape's type are code here.
#include "anyphys/validation.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "anyphys/checks.hpp"
#include "anyphys/error.hpp"
#include "anyphys/schema/body_fields.hpp"
#include "anyphys/schema/settings_fields.hpp"

namespace anyphys {

namespace {
using detail::kPlanarTolerance;
using detail::rotatesAboutZOnly;

// True when the points span a volume (four of them are not coplanar), relative to their extent.
bool spansVolume(const std::vector<Vec3>& p) {
    if (p.size() < 4) return false;
    double extent = 0;
    for (const Vec3& q : p) extent = std::max(extent, (q - p[0]).norm());
    if (extent == 0) return false;
    const double eps = 1e-9 * extent;
    std::size_t i1 = 0;
    for (std::size_t i = 1; i < p.size() && !i1; ++i)
        if ((p[i] - p[0]).norm() > eps) i1 = i;
    if (!i1) return false;
    const Vec3 e1 = p[i1] - p[0];
    Vec3 n = Vec3::Zero();
    for (const Vec3& q : p)
        if (const Vec3 c = e1.cross(q - p[0]); c.norm() > eps * extent && c.norm() > n.norm()) n = c;
    if (n.isZero(0)) return false;
    n.normalize();
    for (const Vec3& q : p)
        if (std::abs(n.dot(q - p[0])) > eps) return true;
    return false;
}

// A compound child's surface overrides belong to that child; on any other shape the body's own
// field is the one to set, so naming it there is refused rather than silently ignored.
void refuseSurfaceOverrides(const ShapeDef& s, const std::string& path) {
    const auto refuse = [&](const char* field, const std::string& value) {
        throw Error::invalid(path + "." + field, value,
                             std::string("allowed only on the children of a compound shape (shape.shapes[i].") + field +
                                 "); set the body's " + field + " instead");
    };
    if (s.material) refuse("material", "\"" + *s.material + "\"");
    if (s.isTrigger) refuse("isTrigger", *s.isTrigger ? "true" : "false");
    if (s.layer) refuse("layer", std::to_string(*s.layer));
    if (s.mask) refuse("mask", std::to_string(*s.mask));
}

void validatePlanarShape(const ShapeDef& s, const std::string& path, const std::string& who) {
    if (s.type == ShapeType::Plane && std::abs(s.normal.z()) > kPlanarTolerance * s.normal.norm())
        throw Error::invalid(path + ".normal", formatVec3(s.normal), "must lie in the XY plane (z = 0) in a planar world" + who);
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        const ShapeDef& child = s.shapes[i];
        const std::string childPath = path + ".shapes[" + std::to_string(i) + "]";
        if (std::abs(child.position.z()) > kPlanarTolerance)
            throw Error::invalid(childPath + ".position", formatVec3(child.position), "must have z = 0 in a planar world" + who);
        if (!rotatesAboutZOnly(child.orientation))
            throw Error::invalid(childPath + ".orientation", formatQuat(child.orientation),
                                 "must be a rotation about Z (x = y = 0) in a planar world" + who);
    }
}
}  // namespace

void validate(const ShapeDef& s, const std::string& path, bool isChild) {
    using namespace detail;
    if (!isChild) refuseSurfaceOverrides(s, path);
    // The sizes a type needs have no default: "not set" says which factory takes them.
    switch (s.type) {
        case ShapeType::Sphere:
            requireSet(path + ".radius", s.radius, "a sphere needs its radius > 0 (ShapeDef::sphere(r))");
            break;
        case ShapeType::Box:
            for (int i = 0; i < 3; ++i)
                requireSet(path + ".halfExtents[" + std::to_string(i) + "]", s.halfExtents[i],
                           "a box needs its halfExtents, each > 0 (ShapeDef::box(half))");
            break;
        case ShapeType::Capsule:
            requireSet(path + ".radius", s.radius, "a capsule needs its radius > 0 (ShapeDef::capsule(r, halfHeight))");
            requireSet(path + ".halfHeight", s.halfHeight,
                       "a capsule needs its halfHeight >= 0 (ShapeDef::capsule(r, halfHeight))");
            break;
        case ShapeType::Plane:
            for (int i = 0; i < 3; ++i)
                requireSet(path + ".normal[" + std::to_string(i) + "]", s.normal[i],
                           "a plane needs its normal (ShapeDef::plane(normal, offset))");
            break;
        default: break;
    }
    // Sizes, placement and density: the rows of this shape's type.
    schema::checkFields(schema::shapeFields(), s, path,
                        [&s](const schema::Field<ShapeDef>& f) { return (f.types & schema::bit(s.type)) != 0; });
    switch (s.type) {
        case ShapeType::Convex:
            for (std::size_t i = 0; i < s.points.size(); ++i)
                requireCoordinate(path + ".points[" + std::to_string(i) + "]", s.points[i]);
            if (!spansVolume(s.points))
                throw Error::invalid(path + ".points", std::to_string(s.points.size()) + " points",
                                     "must hold at least 4 points that are not all in one plane");
            break;
        case ShapeType::Mesh: {
            if (s.vertices.empty()) throw Error::invalid(path + ".vertices", "[]", "must not be empty");
            for (std::size_t i = 0; i < s.vertices.size(); ++i)
                requireCoordinate(path + ".vertices[" + std::to_string(i) + "]", s.vertices[i]);
            if (s.indices.empty() || s.indices.size() % 3 != 0)
                throw Error::invalid(path + ".indices", std::to_string(s.indices.size()) + " indices",
                                     "must be a non-empty multiple of 3 (three per triangle)");
            for (std::size_t i = 0; i < s.indices.size(); ++i)
                if (s.indices[i] >= s.vertices.size())
                    throw Error::invalid(path + ".indices[" + std::to_string(i) + "]", s.indices[i],
                                         "must be < the number of vertices (" + std::to_string(s.vertices.size()) + ")");
            for (std::size_t t = 0; t < s.indices.size(); t += 3) {
                const Vec3 &a = s.vertices[s.indices[t]], &b = s.vertices[s.indices[t + 1]], &c = s.vertices[s.indices[t + 2]];
                if ((b - a).cross(c - a).norm() <= 1e-12 * std::max(1.0, (b - a).squaredNorm()))
                    throw Error::invalid(path + ".indices[" + std::to_string(t) + ".." + std::to_string(t + 2) + "]",
                                         "triangle " + std::to_string(t / 3), "must not be degenerate (zero area)");
            }
            break;
        }
        case ShapeType::Compound:
            if (isChild) throw Error::invalid(path + ".type", "compound", "compound shapes cannot be nested");
            if (s.shapes.empty()) throw Error::invalid(path + ".shapes", "[]", "must hold at least one child shape");
            for (std::size_t i = 0; i < s.shapes.size(); ++i) {
                const ShapeDef& child = s.shapes[i];
                const std::string childPath = path + ".shapes[" + std::to_string(i) + "]";
                if (child.type == ShapeType::Plane || child.type == ShapeType::Mesh || child.type == ShapeType::Compound)
                    throw Error::invalid(childPath + ".type", toString(child.type),
                                         "compound children must be sphere, box, capsule or convex");
                validate(child, childPath, true);
            }
            break;
        default: break;
    }
}

void validate(const BodyDef& b, const std::string& path) {
    schema::checkFields(schema::bodyFields(), b, path, [](const auto&) { return true; });
    validate(b.shape, path + ".shape");
    if ((b.shape.type == ShapeType::Plane || b.shape.type == ShapeType::Mesh) && b.type != BodyType::Static)
        throw Error::invalid(path + ".shape.type", toString(b.shape.type),
                             "plane and mesh shapes are allowed only on static bodies (type \"static\")");
    if (b.type == BodyType::Static && (!b.linearVelocity.isZero(0) || !b.angularVelocity.isZero(0)))
        throw Error::invalid(path + (b.linearVelocity.isZero(0) ? ".angularVelocity" : ".linearVelocity"),
                             formatVec3(b.linearVelocity.isZero(0) ? b.angularVelocity : b.linearVelocity),
                             "must be zero for a static body");
}

// The rules of a body that depend on the world's settings: its initial velocities within the
// speed ceilings. `settingsPath` names the settings in messages ("WorldSettings", "settings").
void validateLimits(const BodyDef& b, const WorldSettings& s, const std::string& path,
                           const std::string& settingsPath) {
    detail::requireSpeed(path + ".linearVelocity", b.linearVelocity, s.maxSpeed, settingsPath + ".maxSpeed", "m/s");
    detail::requireSpeed(path + ".angularVelocity", b.angularVelocity, s.maxAngularSpeed,
                         settingsPath + ".maxAngularSpeed", "rad/s");
}

// The extra rules of a planar world (WorldSettings::planar): the body lies in the XY plane,
// turns about Z only and moves in the plane. Messages name the body.
void validatePlanar(const BodyDef& b, const std::string& path) {
    using namespace detail;
    const std::string who = b.name.empty() ? "" : " (body \"" + b.name + "\")";
    if (std::abs(b.position.z()) > kPlanarTolerance)
        throw Error::invalid(path + ".position", formatVec3(b.position), "must have z = 0 in a planar world" + who);
    if (!rotatesAboutZOnly(b.orientation))
        throw Error::invalid(path + ".orientation", formatQuat(b.orientation),
                             "must be a rotation about Z (x = y = 0) in a planar world" + who);
    if (std::abs(b.linearVelocity.z()) > kPlanarTolerance)
        throw Error::invalid(path + ".linearVelocity", formatVec3(b.linearVelocity),
                             "must have z = 0 in a planar world" + who);
    if (std::abs(b.angularVelocity.x()) > kPlanarTolerance || std::abs(b.angularVelocity.y()) > kPlanarTolerance)
        throw Error::invalid(path + ".angularVelocity", formatVec3(b.angularVelocity),
                             "must be about Z only (x = y = 0) in a planar world" + who);
    validatePlanarShape(b.shape, path + ".shape", who);
}

void validatePlanar(const ShapeDef& s, const std::string& path) { validatePlanarShape(s, path, ""); }

void validate(const WorldSettings& s, const std::string& path) {
    using namespace detail;
    schema::checkFields(schema::settingsFields(), s, path, [](const auto&) { return true; });
    if (s.planar && std::abs(s.gravity.z()) > kPlanarTolerance)
        throw Error::invalid(path + ".gravity", formatVec3(s.gravity), "must have z = 0 in a planar world");
    for (const auto& [name, value] : s.backendOptions) requireFinite(path + ".backendOptions." + name, value);
}

}  // namespace anyphys
