#include "contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "anyphys/peers/gyroscopic.hpp"
#include "integrators.hpp"
#include "native_world.hpp"

namespace anyphys::native {
namespace {

// Soft-constraint coefficients for a spring of `hertz` and damping ratio `zeta` over step h
// (implicit Euler on a mass-spring-damper; see Catto, "Solver2D", 2024).
struct Softness {
    double biasRate = 0.0;
    double massScale = 1.0;
    double impulseScale = 0.0;
};

Softness makeSoft(double hertz, double zeta, double h) {
    if (hertz == 0.0) return {};
    const double omega = 2.0 * std::numbers::pi * hertz;
    const double a1 = 2.0 * zeta + h * omega;
    const double a2 = h * omega * a1;
    const double a3 = 1.0 / (1.0 + a2);
    return {omega / a1, a2 * a3, a3};
}

// Effective mass of an impulse along `dir` applied at anchors rA, rB.
double effectiveMass(const NativeBody& a, const Mat3& iA, const Vec3& rA, const NativeBody& b, const Mat3& iB,
                     const Vec3& rB, const Vec3& dir) {
    const Vec3 ra = rA.cross(dir), rb = rB.cross(dir);
    const double k = a.invMass * a.linearFreedom().cwiseProduct(dir).dot(dir) +
                     b.invMass * b.linearFreedom().cwiseProduct(dir).dot(dir) + ra.dot(iA * ra) + rb.dot(iB * rb);
    return k > 0.0 ? 1.0 / k : 0.0;
}

/// When the stored velocity of a body in free flight is the true velocity: the integrator's
/// velocity lags (semi-implicit Euler: a leapfrog, its velocity belongs half a step before its
/// position) or leads (explicit Euler) by this much; the others keep them in step.
double velocityTimeOffset(Integrator integrator, double dt) {
    switch (integrator) {
        case Integrator::SemiImplicitEuler: return -0.5 * dt;
        case Integrator::ExplicitEuler: return 0.5 * dt;
        default: return 0.0;
    }
}

/// The normal velocity after a bounce of restitution e, from the stored approach velocity `vn`.
/// Restitution acts at the instant of impact: under a constant relative acceleration `an` along
/// the normal the true velocity is vn - an * offset, it reverses to -e times that, and is stored
/// back with the same offset. So semi-implicit Euler flights rebound to e^2 of the drop height
/// rather than about 8 % lower (measured, e = 0.5, 2 m drop at dt 1/60), and exact flights are
/// left unchanged (offset 0).
double bounceVelocity(double e, double vn, double an, double offset) {
    return -e * (vn - an * offset) + an * offset;
}

Vec3 anyPerpendicular(const Vec3& n) {
    const Vec3 axis = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : Vec3::UnitY();
    return n.cross(axis).normalized();
}

// The solver's view of a body during the step.
struct Motion {
    Vec3 v, w;
    Mat3 invI;
    Vec3 invMass;  // per world axis: zero along Z in a planar world
};

}  // namespace

void ContactSolver::prepare(NativeWorld& world) {
    constraints_.clear();
    bodies_.clear();
    auto& bodies = world.bodies();
    for (auto& [key, contact] : world.contactManager().contacts()) {
        if (contact.trigger || contact.manifolds.empty()) continue;
        NativeBody &a = bodies[contact.bodyA], &b = bodies[contact.bodyB];
        const bool awakeDynamic = (a.isDynamic() && a.awake) || (b.isDynamic() && b.awake);
        if (!awakeDynamic) continue;
        for (ContactManifold& m : contact.manifolds) constraints_.push_back({&contact, &m, contact.bodyA, contact.bodyB});
        for (NativeBody* body : {&a, &b}) {
            if (!body->moves() || body->constrained) continue;
            if (!body->awake) continue;
            body->constrained = true;
            bodies_.push_back(static_cast<std::uint32_t>(body - bodies.data()));
        }
    }
}

void ContactSolver::prepareConstraint(NativeWorld& world, Constraint& c, double dt) {
    auto& bodies = world.bodies();
    const NativeBody &a = bodies[c.bodyA], &b = bodies[c.bodyB];
    const Vec3 gravity = world.effects().has(Effect::Gravity) ? world.settings().gravity : Vec3::Zero();
    const auto gravityOf = [&](const NativeBody& body) -> Vec3 {
        return body.isDynamic() ? Vec3(body.gravityScale * gravity) : Vec3::Zero();
    };
    const double offset = velocityTimeOffset(world.settings().integrator, dt);
    const Mat3 iA = a.worldInverseInertia(), iB = b.worldInverseInertia();
    ContactManifold& m = *c.manifold;
    m.tangent[0] = anyPerpendicular(m.normal);
    m.tangent[1] = m.normal.cross(m.tangent[0]);
    const double normalAcceleration = m.normal.dot(gravityOf(b) - gravityOf(a));
    for (int i = 0; i < m.pointCount; ++i) {
        ContactPointState& p = m.points[i];
        p.anchorA = p.geometry.point - a.state.position;
        p.anchorB = p.geometry.point - b.state.position;
        p.normalMass = effectiveMass(a, iA, p.anchorA, b, iB, p.anchorB, m.normal);
        p.tangentMass[0] = effectiveMass(a, iA, p.anchorA, b, iB, p.anchorB, m.tangent[0]);
        p.tangentMass[1] = effectiveMass(a, iA, p.anchorA, b, iB, p.anchorB, m.tangent[1]);
        p.maxNormalImpulse = 0.0;
        const Vec3 dv = b.state.linearVelocity + b.state.angularVelocity.cross(p.anchorB) - a.state.linearVelocity -
                        a.state.angularVelocity.cross(p.anchorA);
        p.relativeVelocity = m.normal.dot(dv);
        p.restitutionTarget = bounceVelocity(c.contact->restitution, p.relativeVelocity, normalAcceleration, offset);
    }
}

void ContactSolver::solve(NativeWorld& world, const StepInfo& step) {
    if (constraints_.empty()) return;
    auto& bodies = world.bodies();
    const WorldSettings& settings = world.settings();
    const Effects effects = world.effects();
    const bool soft = *settings.solver != Solver::ProjectedGaussSeidel;
    const int substeps = *settings.substeps;
    const double h = step.dt / substeps, invH = 1.0 / h;
    const bool friction = effects.has(Effect::Friction);
    const bool restitution = effects.has(Effect::Restitution);

    for (Constraint& c : constraints_) prepareConstraint(world, c, step.dt);

    // Velocities and inverse inertia in one dense array the inner loops touch.
    std::vector<int> slot(bodies.size(), -1);
    std::vector<Motion> motion(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        NativeBody& b = bodies[bodies_[i]];
        slot[bodies_[i]] = static_cast<int>(i);
        // stepStart poses were taken when the step began (or when the body woke).
        motion[i] = {b.state.linearVelocity, b.state.angularVelocity, b.worldInverseInertia(),
                     b.isDynamic() ? Vec3(b.invMass * b.linearFreedom()) : Vec3::Zero()};
    }
    Motion fixed{Vec3::Zero(), Vec3::Zero(), Mat3::Zero(), Vec3::Zero()};  // static or asleep partners
    const auto motionOf = [&](std::uint32_t body) -> Motion& {
        const int s = slot[body];
        if (s >= 0) return motion[s];
        fixed.v = bodies[body].state.linearVelocity;
        fixed.w = bodies[body].state.angularVelocity;
        return fixed;
    };

    // Current separation from the bodies' motion since the step began (no new collision pass).
    const auto separation = [&](const Constraint& c, const ContactPointState& p) {
        const NativeBody &a = bodies[c.bodyA], &b = bodies[c.bodyB];
        const Vec3 dA = (a.state.position - a.stepStartPosition) +
                        (a.state.orientation * a.stepStartOrientation.conjugate() * p.anchorA - p.anchorA);
        const Vec3 dB = (b.state.position - b.stepStartPosition) +
                        (b.state.orientation * b.stepStartOrientation.conjugate() * p.anchorB - p.anchorB);
        return p.geometry.separation + c.manifold->normal.dot(dB - dA);
    };
    // Static partners never move: their step-start pose is their pose.
    for (Constraint& c : constraints_)
        for (std::uint32_t i : {c.bodyA, c.bodyB})
            if (slot[i] < 0) {
                bodies[i].stepStartPosition = bodies[i].state.position;
                bodies[i].stepStartOrientation = bodies[i].state.orientation;
            }

    const auto applyImpulse = [&](const Constraint& c, const ContactPointState& p, const Vec3& impulse) {
        Motion& a = motionOf(c.bodyA);
        Motion& b = motionOf(c.bodyB);
        a.v -= a.invMass.cwiseProduct(impulse);
        a.w -= a.invI * p.anchorA.cross(impulse);
        b.v += b.invMass.cwiseProduct(impulse);
        b.w += b.invI * p.anchorB.cross(impulse);
    };
    const auto relativeVelocity = [&](const Constraint& c, const ContactPointState& p) {
        const Motion& a = motionOf(c.bodyA);
        const Motion& b = motionOf(c.bodyB);
        return Vec3(b.v + b.w.cross(p.anchorB) - a.v - a.w.cross(p.anchorA));
    };

    // Stiffness capped: a spring stiffer than a substep resolves makes unconverged Gauss-Seidel
    // ring. The cap is a quarter of the substep rate (Box2D v3's bound), but not below half the
    // step rate, where a single substep would leave stacks too soft to stand. Measured at dt 1/60
    // without sleeping: 1000-box pile at 2 substeps x 4 iterations jitters at 0.8 m/s after 10 s
    // with 60 Hz and is at rest with 30 Hz; a 10-box stack at 1 substep x 10 iterations sways 46 cm
    // at 60 Hz, stays within 1.2 cm at 30 Hz, and sags 11 cm and topples at 15 Hz.
    const double stepRate = 1.0 / step.dt;
    const double maxHertz = std::max(0.25 * substeps * stepRate, 0.5 * stepRate);
    const Softness contactSoft = makeSoft(std::min(settings.contactHertz, maxHertz), settings.contactDampingRatio, h);

    // Friction first, against the last normal impulses, then non-penetration, which matters
    // more and so gets the last word in each pass.
    const auto solveFriction = [&](const Constraint& c) {
        ContactManifold& m = *c.manifold;
        for (int i = 0; i < m.pointCount; ++i) {
            ContactPointState& p = m.points[i];
            const Vec3 dv = relativeVelocity(c, p);
            const double old0 = p.tangentImpulse[0], old1 = p.tangentImpulse[1];
            double t0 = old0 - p.tangentMass[0] * m.tangent[0].dot(dv);
            double t1 = old1 - p.tangentMass[1] * m.tangent[1].dot(dv);
            // Coulomb: the tangential impulse lies in a circle of radius mu * normal impulse.
            const double limit = c.contact->friction * p.normalImpulse;
            const double magnitude = std::hypot(t0, t1);
            if (magnitude > limit) {
                const double scale = limit / magnitude;
                t0 *= scale;
                t1 *= scale;
            }
            p.tangentImpulse[0] = t0;
            p.tangentImpulse[1] = t1;
            applyImpulse(c, p, (t0 - old0) * m.tangent[0] + (t1 - old1) * m.tangent[1]);
        }
    };
    const auto solveNormal = [&](const Constraint& c, bool useBias, bool reverse) {
        ContactManifold& m = *c.manifold;
        for (int k = 0; k < m.pointCount; ++k) {
            ContactPointState& p = m.points[reverse ? m.pointCount - 1 - k : k];
            const double s = separation(c, p);
            double bias = 0.0, massScale = 1.0, impulseScale = 0.0;
            if (s > 0.0) {
                bias = s * invH;  // speculative: allow closing exactly the gap this substep
            } else if (soft) {
                if (useBias) {
                    bias = std::max(contactSoft.biasRate * s, -settings.contactPushMaxVelocity);
                    massScale = contactSoft.massScale;
                    impulseScale = contactSoft.impulseScale;
                }
            } else {
                // Baumgarte: correct a fraction of the overlap beyond linearSlop per substep.
                bias = std::max(settings.baumgarte * invH * std::min(0.0, s + settings.linearSlop),
                                -settings.contactPushMaxVelocity);
                if (restitution && p.relativeVelocity < -settings.restitutionThreshold)
                    bias = std::min(bias, -p.restitutionTarget);
            }
            const double vn = m.normal.dot(relativeVelocity(c, p));
            const double impulse = -p.normalMass * massScale * (vn + bias) - impulseScale * p.normalImpulse;
            const double total = std::max(p.normalImpulse + impulse, 0.0);
            const double applied = total - p.normalImpulse;
            p.normalImpulse = total;
            p.maxNormalImpulse = std::max(p.maxNormalImpulse, applied);
            applyImpulse(c, p, applied * m.normal);
        }
    };
    // Sweeps alternate direction (symmetric Gauss-Seidel): a fixed order favours the first
    // points of a manifold and lets a resting box pick up a small spin it then slides on.
    const auto solvePass = [&](bool useBias, bool reverse) {
        const std::size_t n = constraints_.size();
        for (std::size_t k = 0; k < n; ++k) {
            const Constraint& c = constraints_[reverse ? n - 1 - k : k];
            if (friction) solveFriction(c);
            solveNormal(c, useBias, reverse);
        }
    };

    const Vec3 gravity = effects.has(Effect::Gravity) ? settings.gravity : Vec3::Zero();
    const bool damping = effects.has(Effect::Damping);
    const bool userForces = effects.has(Effect::UserForces);
    // In a plane the gyroscopic term w x Iw has no part about Z: the plane absorbs it.
    const bool gyroscopic = effects.has(Effect::Gyroscopic) && !settings.planar;
    const int iterations = *settings.iterations;

    for (int sub = 0; sub < substeps; ++sub) {
        // Forces from the user's callback, at this substep's state.
        world.evaluateForceHook(step.time + sub * h);
        // Integrate velocities.
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            NativeBody& b = bodies[bodies_[i]];
            if (!b.isDynamic()) continue;
            Motion& mo = motion[i];
            Vec3 accel = b.gravityScale * gravity;
            Vec3 torque = Vec3::Zero();
            if (userForces) {
                accel += b.invMass * (b.force + world.hookForce(bodies_[i]));
                torque += b.torque + world.hookTorque(bodies_[i]);
            }
            mo.v += h * accel;
            mo.w += h * (mo.invI * torque);
            if (gyroscopic && b.gyroscopic == GyroscopicMode::Implicit)
                mo.w = gyroscopic::solveImplicit(mo.w, b.state.orientation, b.inertia, h);
            else if (gyroscopic && b.gyroscopic == GyroscopicMode::Explicit)
                mo.w += h * gyroscopic::acceleration(mo.w, b.state.orientation, b.inertia);
            if (damping) {  // implicit: stable for any damping
                mo.v /= 1.0 + h * b.linearDamping;
                mo.w /= 1.0 + h * b.angularDamping;
            }
        }
        // Warm start with last step's impulses.
        for (const Constraint& c : constraints_) {
            const ContactManifold& m = *c.manifold;
            for (int i = 0; i < m.pointCount; ++i) {
                const ContactPointState& p = m.points[i];
                applyImpulse(c, p, p.normalImpulse * m.normal + p.tangentImpulse[0] * m.tangent[0] +
                                       p.tangentImpulse[1] * m.tangent[1]);
            }
        }
        for (int it = 0; it < iterations; ++it) solvePass(true, it % 2 == 1);
        // Integrate positions.
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            NativeBody& b = bodies[bodies_[i]];
            b.state.linearVelocity = motion[i].v;
            b.state.angularVelocity = motion[i].w;
            b.state.position += h * motion[i].v;
            b.state.orientation = rotateBy(b.state.orientation, motion[i].w, h);
        }
        if (soft)
            for (int it = 0; it < iterations; ++it) solvePass(false, it % 2 == 1);
    }

    // Restitution once, on the final velocities, where the approach was fast and pushed.
    if (soft && restitution) {
        for (const Constraint& c : constraints_) {
            if (c.contact->restitution == 0.0) continue;
            ContactManifold& m = *c.manifold;
            for (int i = 0; i < m.pointCount; ++i) {
                ContactPointState& p = m.points[i];
                if (p.relativeVelocity > -settings.restitutionThreshold || p.maxNormalImpulse == 0.0) continue;
                const double vn = m.normal.dot(relativeVelocity(c, p));
                const double impulse = -p.normalMass * (vn - p.restitutionTarget);
                const double total = std::max(p.normalImpulse + impulse, 0.0);
                applyImpulse(c, p, (total - p.normalImpulse) * m.normal);
                p.normalImpulse = total;
            }
        }
    }
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        NativeBody& b = bodies[bodies_[i]];
        b.state.linearVelocity = motion[i].v;
        b.state.angularVelocity = motion[i].w;
    }
}

}  // namespace anyphys::native
