#pragma once
// What each field does to one body, as pure functions of the body's geometry and state: the world's
// field stage (api/src/world_fields.cpp) calls them for every awake dynamic body and hands the
// results to the backend as forces and impulses.
#include <optional>
#include <vector>

#include "anyphys/fields/field_def.hpp"
#include "anyphys/fields/field_shape.hpp"
#include "anyphys/fields/submerged_volume.hpp"

namespace anyphys {

/// A body as the fields see it: its primitives in the frame of the centre of mass and principal
/// axes (the frame whose state the backend reports), its volume, mass, principal inertia and drag
/// coefficient.
struct FieldBody {
    std::vector<FieldShape> shapes;
    double volume = 0.0;             ///< m^3, sum of the primitives' volumes
    double mass = 0.0;               ///< kg
    Vec3 inertia = Vec3::Zero();     ///< kg m^2, principal moments
    double dragCoefficient = 0.47;   ///< the body's, or the default of its (first) shape
};

/// The state of that frame: pose of the centre of mass and principal axes, and velocities.
struct FieldState {
    Transform pose;
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
};

/// A force at the centre of mass and a torque about it (world frame).
struct FieldForce {
    Vec3 force = Vec3::Zero();
    Vec3 torque = Vec3::Zero();
    FieldForce& operator+=(const FieldForce& o) { force += o.force; torque += o.torque; return *this; }
};

// ---- drag (drag.cpp) ------------------------------------------------------------------------
/// The area (m^2) of the shape's silhouette seen along the unit direction `d` (world frame), for
/// a primitive at `pose`: a sphere pi r^2; a box sum_k |n_k . d| A_k over its three face pairs
/// (A_k the face area); a capsule pi r^2 + 4 r h sin(theta), theta between d and its axis (the
/// stadium it projects to); a convex hull half the sum over its faces of |n_f . d| A_f. All exact.
double projectedArea(const FieldShape& shape, const Quat& bodyOrientation, const Vec3& d);
/// The body's frontal area along d: the sum over its primitives (a compound whose children hide
/// one another is overestimated by the hidden part).
double projectedArea(const FieldBody& body, const Quat& bodyOrientation, const Vec3& d);
/// Quadratic drag on the body moving at `relativeVelocity` through air of density rho:
/// F = -0.5 rho Cd A |v| v at the centre of mass (no torque).
FieldForce quadraticDrag(const FieldBody& body, const Quat& bodyOrientation, const Vec3& relativeVelocity,
                         double rho);
/// Still air (a `drag` field).
FieldForce dragForce(const FieldDef& field, const FieldBody& body, const FieldState& state);

// ---- wind (wind.cpp) ------------------------------------------------------------------------
/// Moving air (a `wind` field): quadratic drag on v - field.velocity.
FieldForce windForce(const FieldDef& field, const FieldBody& body, const FieldState& state);

// ---- buoyancy (buoyancy.cpp) ----------------------------------------------------------------
/// Archimedes' force -fluidDensity V g at the centre of buoyancy (so a torque about the centre of
/// mass), plus the fluid's drag: -m linearDrag f v and -I angularDrag f w, f = V / body volume.
FieldForce buoyancyForce(const FieldDef& field, const FieldBody& body, const FieldState& state, const Vec3& gravity);

// ---- explosion (explosion.cpp) --------------------------------------------------------------
/// The point of the body's surface nearest to `point` (world frame), or `point` itself when it
/// is inside the body. Exact for every primitive (a hull: the nearest of its faces seen from the point).
Vec3 nearestSurfacePoint(const FieldBody& body, const Transform& pose, const Vec3& point);
/// The impulse magnitude at distance d from the centre: impulse (1 - d / radius) within the radius, else 0.
double explosionImpulse(const FieldDef& field, double distance);
/// The impulse on one body and where it acts, or nothing when the body is out of reach. The
/// direction is from the centre to that point (from the centre to the centre of mass when the
/// centre is inside the body, straight up if they coincide). Whether static geometry shields the
/// body is the world's to decide (a ray cast from the centre to the point).
struct ExplosionHit {
    Vec3 impulse = Vec3::Zero();  ///< N s, world frame
    Vec3 point = Vec3::Zero();    ///< where it acts: the surface point nearest the centre
};
std::optional<ExplosionHit> explosionHit(const FieldDef& field, const FieldBody& body, const FieldState& state);

}  // namespace anyphys
