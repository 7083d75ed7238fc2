#pragma once
// Enumerations of the value layer and their scene-file names (the names are a contract:
// scene files, the command-line tool and capability tables all use them).
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace anyphys {

enum class BodyType { Static, Kinematic, Dynamic };

/// Time integrators for free-body motion (native backend; others declare what they honour).
enum class Integrator {
    ExplicitEuler,      ///< x += h v(t), v += h a(t): first order, gains energy
    SemiImplicitEuler,  ///< v += h a(t), x += h v(t+h): first order, symplectic
    Verlet,             ///< velocity Verlet: second order, symplectic
    Midpoint,           ///< explicit midpoint (RK2): second order
    RK4,                ///< classic Runge-Kutta: fourth order
};

/// How the gyroscopic term omega x (I omega) of Euler's equations is treated, per body.
enum class GyroscopicMode {
    None,      ///< omitted: world angular velocity stays constant without torque
    Explicit,  ///< part of the derivative evaluated by the integrator
    Implicit,  ///< backward Euler on the body-frame angular velocity, one Newton solve per body
};

/// Constraint solvers (used once contacts and joints exist).
enum class Solver {
    SoftStep,             ///< substepped soft constraints with relax pass (Box2D v3 style)
    ProjectedGaussSeidel, ///< sequential impulses with an iteration count
    Direct,               ///< an engine's global (direct / LCP) solver where it has one
};

enum class ShapeType {
    Sphere,    ///< radius
    Box,       ///< halfExtents
    Capsule,   ///< radius, halfHeight along body Y
    Plane,     ///< normal, offset; static bodies only
    Convex,    ///< the convex hull of `points`
    Mesh,      ///< triangles (`vertices`, `indices`); static bodies only
    Compound,  ///< several child shapes (`shapes`), each placed by its position / orientation
};

enum class JointType {
    Fixed,     ///< welds B to A: no relative motion
    Ball,      ///< B turns freely about the anchor (ball and socket)
    Hinge,     ///< B turns about `axis` through the anchor (revolute)
    Slider,    ///< B slides along `axis`, no turning (prismatic)
    Distance,  ///< keeps the distance between anchorA and anchorB: rigid, rope-like (min / max) or a spring
    Cone,      ///< ball joint whose swing away from `axis` is limited to a cone, and twist about it to a range
    Wheel,     ///< suspension along `axis` with spring and travel limits, free spin about `spinAxis`, drive motor
};

template <class E>
struct EnumNames;  // specialised below: static constexpr std::array<std::pair<E, std::string_view>, N> values

template <>
struct EnumNames<BodyType> {
    static constexpr std::string_view what = "body type";
    static constexpr std::array<std::pair<BodyType, std::string_view>, 3> values{{
        {BodyType::Static, "static"}, {BodyType::Kinematic, "kinematic"}, {BodyType::Dynamic, "dynamic"}}};
};
template <>
struct EnumNames<Integrator> {
    static constexpr std::string_view what = "integrator";
    static constexpr std::array<std::pair<Integrator, std::string_view>, 5> values{{
        {Integrator::ExplicitEuler, "explicit_euler"},
        {Integrator::SemiImplicitEuler, "semi_implicit_euler"},
        {Integrator::Verlet, "verlet"},
        {Integrator::Midpoint, "midpoint"},
        {Integrator::RK4, "rk4"}}};
};
template <>
struct EnumNames<GyroscopicMode> {
    static constexpr std::string_view what = "gyroscopic mode";
    static constexpr std::array<std::pair<GyroscopicMode, std::string_view>, 3> values{{
        {GyroscopicMode::None, "none"}, {GyroscopicMode::Explicit, "explicit"}, {GyroscopicMode::Implicit, "implicit"}}};
};
template <>
struct EnumNames<Solver> {
    static constexpr std::string_view what = "solver";
    static constexpr std::array<std::pair<Solver, std::string_view>, 3> values{{
        {Solver::SoftStep, "soft_step"}, {Solver::ProjectedGaussSeidel, "pgs"}, {Solver::Direct, "direct"}}};
};
template <>
struct EnumNames<ShapeType> {
    static constexpr std::string_view what = "shape type";
    static constexpr std::array<std::pair<ShapeType, std::string_view>, 7> values{{
        {ShapeType::Sphere, "sphere"}, {ShapeType::Box, "box"}, {ShapeType::Capsule, "capsule"},
        {ShapeType::Plane, "plane"}, {ShapeType::Convex, "convex"}, {ShapeType::Mesh, "mesh"},
        {ShapeType::Compound, "compound"}}};
};

template <>
struct EnumNames<JointType> {
    static constexpr std::string_view what = "joint type";
    static constexpr std::array<std::pair<JointType, std::string_view>, 7> values{{
        {JointType::Fixed, "fixed"}, {JointType::Ball, "ball"}, {JointType::Hinge, "hinge"},
        {JointType::Slider, "slider"}, {JointType::Distance, "distance"}, {JointType::Cone, "cone"},
        {JointType::Wheel, "wheel"}}};
};

template <class E>
std::string_view toString(E value) {
    for (const auto& [e, name] : EnumNames<E>::values)
        if (e == value) return name;
    return "unknown";
}

template <class E>
std::optional<E> fromString(std::string_view name) {
    for (const auto& [e, n] : EnumNames<E>::values)
        if (n == name) return e;
    return std::nullopt;
}

/// "a, b, c": the allowed names, for error messages.
template <class E>
std::string allowedNames() {
    std::string out;
    for (const auto& [e, n] : EnumNames<E>::values) {
        if (!out.empty()) out += ", ";
        out += n;
    }
    return out;
}

}  // namespace anyphys
