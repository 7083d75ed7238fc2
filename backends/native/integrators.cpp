#include "integrators.hpp"

#include <cmath>

#include "solver/body_integration.hpp"

namespace anyphys::native {
namespace {

Quat addScaled(const Quat& q, const Quat& dq, double s) {
    return Quat(q.coeffs() + s * dq.coeffs());
}

void resize(IntegratorScratch& s, std::size_t n) {
    s.stage.resize(n);
    s.k1.resize(n);
    s.k2.resize(n);
    s.k3.resize(n);
    s.k4.resize(n);
    s.d1.resize(n);
    s.d2.resize(n);
    s.d3.resize(n);
    s.d4.resize(n);
}

// The time derivative of a state: (v, dq/dt, a, alpha), stored in a BodyState's slots.
void derivative(std::span<const BodyState> states, std::span<const Acceleration> acc, std::span<BodyState> out) {
    for (std::size_t i = 0; i < states.size(); ++i) {
        out[i].position = states[i].linearVelocity;
        out[i].orientation = orientationRate(states[i].angularVelocity, states[i].orientation);
        out[i].linearVelocity = acc[i].linear;
        out[i].angularVelocity = acc[i].angular;
    }
}

// out = base + s * d; orientations are renormalised so force code sees valid rotations.
void advance(std::span<const BodyState> base, std::span<const BodyState> d, double s, std::span<BodyState> out) {
    for (std::size_t i = 0; i < base.size(); ++i) {
        out[i].position = base[i].position + s * d[i].position;
        out[i].orientation = addScaled(base[i].orientation, d[i].orientation, s).normalized();
        out[i].linearVelocity = base[i].linearVelocity + s * d[i].linearVelocity;
        out[i].angularVelocity = base[i].angularVelocity + s * d[i].angularVelocity;
    }
}

void explicitEuler(double t, double h, std::span<BodyState> x, AccelerationFn f, IntegratorScratch& s) {
    f(t, x, s.k1);
    for (std::size_t i = 0; i < x.size(); ++i) {
        BodyState& b = x[i];
        b.position += h * b.linearVelocity;
        b.orientation = addScaled(b.orientation, orientationRate(b.angularVelocity, b.orientation), h).normalized();
        b.linearVelocity += h * s.k1[i].linear;
        b.angularVelocity += h * s.k1[i].angular;
    }
}

void semiImplicitEuler(double t, double h, std::span<BodyState> x, AccelerationFn f, IntegratorScratch& s) {
    f(t, x, s.k1);
    for (std::size_t i = 0; i < x.size(); ++i) {
        BodyState& b = x[i];
        b.linearVelocity += h * s.k1[i].linear;
        b.angularVelocity += h * s.k1[i].angular;
        b.position += h * b.linearVelocity;
        // Turned by the new spin exactly, as the contact solver turns its bodies: the first-order
        // update q + h dq/dt, normalised, turns by 2 atan(w h / 2) rather than w h, so a body
        // spinning at 20 rad/s at 60 Hz fell 0.18 rad behind in a second.
        b.orientation = rotateBy(b.orientation, b.angularVelocity, h);
    }
}

// Velocity Verlet. Positions use a(t); velocities the average of a(t) and a(t+h). The new
// acceleration is evaluated with predicted velocities v + h a(t), which keeps second order
// for velocity-dependent forces (damping, gyroscopic) and is exact Verlet when forces depend
// on positions only.
void velocityVerlet(double t, double h, std::span<BodyState> x, AccelerationFn f, IntegratorScratch& s) {
    f(t, x, s.k1);
    for (std::size_t i = 0; i < x.size(); ++i) {
        BodyState& b = x[i];
        BodyState& p = s.stage[i];
        p.position = b.position + h * b.linearVelocity + 0.5 * h * h * s.k1[i].linear;
        // Rotation by the mid-step angular velocity: second order like the translation.
        p.orientation = rotateBy(b.orientation, b.angularVelocity + 0.5 * h * s.k1[i].angular, h);
        p.linearVelocity = b.linearVelocity + h * s.k1[i].linear;
        p.angularVelocity = b.angularVelocity + h * s.k1[i].angular;
    }
    f(t + h, s.stage, s.k2);
    for (std::size_t i = 0; i < x.size(); ++i) {
        BodyState& b = x[i];
        b.position = s.stage[i].position;
        b.orientation = s.stage[i].orientation;
        b.linearVelocity += 0.5 * h * (s.k1[i].linear + s.k2[i].linear);
        b.angularVelocity += 0.5 * h * (s.k1[i].angular + s.k2[i].angular);
    }
}

void midpoint(double t, double h, std::span<BodyState> x, AccelerationFn f, IntegratorScratch& s) {
    f(t, x, s.k1);
    derivative(x, s.k1, s.d1);
    advance(x, s.d1, 0.5 * h, s.stage);
    f(t + 0.5 * h, s.stage, s.k2);
    derivative(s.stage, s.k2, s.d2);
    advance(x, s.d2, h, x);
}

void rungeKutta4(double t, double h, std::span<BodyState> x, AccelerationFn f, IntegratorScratch& s) {
    f(t, x, s.k1);
    derivative(x, s.k1, s.d1);
    advance(x, s.d1, 0.5 * h, s.stage);
    f(t + 0.5 * h, s.stage, s.k2);
    derivative(s.stage, s.k2, s.d2);
    advance(x, s.d2, 0.5 * h, s.stage);
    f(t + 0.5 * h, s.stage, s.k3);
    derivative(s.stage, s.k3, s.d3);
    advance(x, s.d3, h, s.stage);
    f(t + h, s.stage, s.k4);
    derivative(s.stage, s.k4, s.d4);
    for (std::size_t i = 0; i < x.size(); ++i) {
        BodyState& b = x[i];
        const auto sum = [&](auto member) -> Vec3 {
            return (s.d1[i].*member + 2.0 * s.d2[i].*member + 2.0 * s.d3[i].*member + s.d4[i].*member);
        };
        b.position += h / 6.0 * sum(&BodyState::position);
        b.linearVelocity += h / 6.0 * sum(&BodyState::linearVelocity);
        b.angularVelocity += h / 6.0 * sum(&BodyState::angularVelocity);
        const Eigen::Vector4d dq = s.d1[i].orientation.coeffs() + 2.0 * s.d2[i].orientation.coeffs() +
                                   2.0 * s.d3[i].orientation.coeffs() + s.d4[i].orientation.coeffs();
        b.orientation = Quat(b.orientation.coeffs() + h / 6.0 * dq).normalized();
    }
}

}  // namespace

Quat orientationRate(const Vec3& w, const Quat& q) {
    const Quat omega(0.0, w.x(), w.y(), w.z());
    Quat r = omega * q;
    r.coeffs() *= 0.5;
    return r;
}

Quat rotateBy(const Quat& q, const Vec3& w, double h) {
    return renormalized(rotationFromVector(h * w) * q);
}

void integrate(Integrator method, double t, double h, std::span<BodyState> states, AccelerationFn accelerations,
               IntegratorScratch& scratch) {
    resize(scratch, states.size());
    switch (method) {
        case Integrator::ExplicitEuler: explicitEuler(t, h, states, accelerations, scratch); return;
        case Integrator::SemiImplicitEuler: semiImplicitEuler(t, h, states, accelerations, scratch); return;
        case Integrator::Verlet: velocityVerlet(t, h, states, accelerations, scratch); return;
        case Integrator::Midpoint: midpoint(t, h, states, accelerations, scratch); return;
        case Integrator::RK4: rungeKutta4(t, h, states, accelerations, scratch); return;
    }
}

}  // namespace anyphys::native
