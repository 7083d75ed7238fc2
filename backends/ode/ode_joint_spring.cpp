#include "ode_joint_spring.hpp"

#include <algorithm>

#include <Eigen/Dense>

#include "ode_body.hpp"

namespace anyphys::ode {
namespace {

// Soft: k h^2 K n at most this (see the header).
constexpr double kExplicitSpring = 0.5;

bool moves(const OdeBody* body) { return body && body->isDynamic() && body->id(); }

// I^-1 in the world, I the body's principal inertia (its frame is ODE's body frame); a zero
// moment is a locked direction.
Eigen::Matrix3d worldInverseInertia(const OdeBody& body) {
    const Eigen::Matrix3d r = body.state().orientation.toRotationMatrix();
    const Vec3 inertia = body.massProperties().inertia;
    Vec3 inverse = Vec3::Zero();
    for (int i = 0; i < 3; ++i)
        if (inertia[i] > 0.0) inverse[i] = 1.0 / inertia[i];
    return r * inverse.asDiagonal() * r.transpose();
}

double inverseMassOf(const OdeBody* body, const SpringLine& line, const Vec3& at) {
    if (!moves(body)) return 0.0;
    if (line.angular) return line.axis.dot(worldInverseInertia(*body) * line.axis);
    const Vec3 arm = (at - body->state().position).cross(line.axis);
    return 1.0 / body->mass() + arm.dot(worldInverseInertia(*body) * arm);
}

void push(const OdeBody* body, const SpringLine& line, const Vec3& at, double amount) {
    if (!moves(body) || !body->isActive()) return;  // a sleeping body would keep it for later
    const Vec3 v = amount * line.axis;
    if (line.angular)
        dBodyAddTorque(body->id(), v.x(), v.y(), v.z());
    else
        dBodyAddForceAtPos(body->id(), v.x(), v.y(), v.z(), at.x(), at.y(), at.z());
}

// A constraint row's Jacobian: B's linear and angular parts, then A's.
using Row = Eigen::Matrix<double, 12, 1>;

// The inverse mass matrix of one body (zero if it does not move), world frame.
Eigen::Matrix<double, 6, 6> inverseMassMatrix(const OdeBody* body) {
    Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
    if (!moves(body)) return m;
    m.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / body->mass();
    m.bottomRightCorner<3, 3>() = worldInverseInertia(*body);
    return m;
}

Row pointRow(const Vec3& direction, const Vec3& anchor, const OdeBody* a, const OdeBody* b) {
    Row row = Row::Zero();
    const auto armOf = [&](const OdeBody* body) { return moves(body) ? Vec3(anchor - body->state().position) : Vec3::Zero(); };
    row << direction, armOf(b).cross(direction), -direction, -armOf(a).cross(direction);
    return row;
}

Row angularRow(const Vec3& axis) {
    Row row = Row::Zero();
    row << Vec3::Zero(), axis, Vec3::Zero(), -axis;
    return row;
}

}  // namespace

double hingeInverseInertia(const Vec3& axis, const Vec3& anchor, const OdeBody* a, const OdeBody* b) {
    Eigen::Matrix<double, 12, 12> inverseMass = Eigen::Matrix<double, 12, 12>::Zero();
    inverseMass.topLeftCorner<6, 6>() = inverseMassMatrix(b);
    inverseMass.bottomRightCorner<6, 6>() = inverseMassMatrix(a);
    // Row 0 the spring, then the pin: three point rows and the two aligning the axes.
    const Vec3 y = axis.unitOrthogonal(), z = axis.cross(y);
    Eigen::Matrix<double, 6, 12> j;
    j.row(0) = angularRow(axis).transpose();
    for (int i = 0; i < 3; ++i) j.row(1 + i) = pointRow(Vec3::Unit(i), anchor, a, b).transpose();
    j.row(4) = angularRow(y).transpose();
    j.row(5) = angularRow(z).transpose();
    const Eigen::Matrix<double, 6, 6> k = j * inverseMass * j.transpose();
    // The Schur complement K_ss - K_sp K_pp^-1 K_ps; the pin's rows may be dependent (a body held
    // to the world has fewer free directions than rows): the least-squares solution.
    const Eigen::Matrix<double, 5, 5> pin = k.bottomRightCorner<5, 5>();
    const Eigen::Matrix<double, 5, 1> coupling = k.block<5, 1>(1, 0);
    const Eigen::Matrix<double, 5, 1> x = pin.completeOrthogonalDecomposition().solve(coupling);
    const double alone = k(0, 0);
    if (!x.allFinite()) return alone;
    return std::clamp(alone - coupling.dot(x), 0.0, alone);
}

double inverseMassAlong(const SpringLine& line, const OdeBody* a, const OdeBody* b) {
    return inverseMassOf(a, line, line.atA) + inverseMassOf(b, line, line.atB);
}

bool springStepsExplicitly(double k, double h, double inverseMass, int springsOnBusierBody) {
    return k * h * h * inverseMass * springsOnBusierBody <= kExplicitSpring;
}

SpringPush pushSpring(const SpringLine& line, double stiffness, const OdeBody* a, const OdeBody* b) {
    const double onB = -stiffness * line.stretch;
    push(b, line, line.atB, onB);
    push(a, line, line.atA, -onB);
    SpringPush pushed;
    if (line.angular) {
        pushed.torque = onB * line.axis;
    } else {
        pushed.force = onB * line.axis;
        pushed.torque = (line.atB - b->state().position).cross(pushed.force);
    }
    return pushed;
}

}  // namespace anyphys::ode
