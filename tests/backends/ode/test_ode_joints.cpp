// ODE joints at the peer level, against closed forms (mirrors tests/backends/native/test_joints.cpp):
// every type's position, speed and reactions measured the anyphys way, signs checked explicitly.
#include <gtest/gtest.h>
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include "anyphys/anyphys.hpp"
#include "anyphys/backends.hpp"
#include "ode_tuning.hpp"
#include "ode_world.hpp"
#include "../../period_meter.hpp"

namespace anyphys::ode {
namespace {

using anyphys::test::PeriodMeter;  // the period from downward zero crossings

constexpr double kG = 9.81;
constexpr double kPi = std::numbers::pi;
constexpr double kDt = 1.0 / 60.0;

// A body of `mass` kg with isotropic inertia, no shape unless `shape` (joints only).
std::unique_ptr<BodyPeer> body(OdeWorld& world, const Vec3& position, double mass = 1.0, double inertia = 1e-4,
                               const std::optional<ShapeDef>& shape = std::nullopt) {
    BodyPeerDef d;
    d.def.position = position;
    d.def.allowSleep = false;
    d.mass = {mass, Vec3::Constant(inertia)};
    if (shape) d.shapes.push_back({*shape, Transform{}, nullptr});
    return world.createBody(d);
}

std::unique_ptr<OdeWorld> jointWorld(Effects effects = Effect::Gravity | Effect::Joints,
                                     Solver solver = Solver::ProjectedGaussSeidel, int substeps = 1,
                                     int iterations = 0) {
    WorldSettings s;
    s.solver = solver;
    s.substeps = substeps;
    if (iterations > 0) s.iterations = iterations;
    // Unset iterations resolved as the layer does (the backend's default, 50).
    auto world = std::make_unique<OdeWorld>(withBackendDefaults(s, backendInfo("ode").capabilities));
    world->setEffects(effects);
    return world;
}

// The joint frame in the world at `anchor` with orientation `frame` (X the joint axis), as
// frameA of a world-held joint, and the same frame in the body's frame (identity orientation).
JointPeerDef heldToWorld(JointType type, BodyPeer& b, const Vec3& bodyPosition, const Vec3& anchor,
                         const Quat& frame = Quat::Identity()) {
    JointPeerDef d;
    d.type = type;
    d.bodyB = &b;
    d.frameA = {anchor, frame};
    d.frameB = {anchor - bodyPosition, frame};
    return d;
}

// X along world +Z (hinge axes of the pendulums, which swing in the XY plane).
const Quat kXAlongZ(Eigen::AngleAxisd(-0.5 * kPi, Vec3::UnitY()));

// Complete elliptic integral of the first kind by the arithmetic-geometric mean.
double ellipticK(double k) {
    double a = 1.0, b = std::sqrt(1.0 - k * k);
    for (int i = 0; i < 30; ++i) {
        const double an = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = an;
    }
    return kPi / (2.0 * a);
}

void run(OdeWorld& world, double seconds, const std::function<void(double)>& each = {}) {
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < steps; ++i) {
        world.step(i * kDt, kDt);
        if (each) each((i + 1) * kDt);
    }
}

// ---- isolated pairs ---------------------------------------------------------------------------

// A free body of `mass` kg with principal moments `inertia` (no shape), posed and moving.
std::unique_ptr<BodyPeer> freeBody(OdeWorld& world, const Vec3& position, const Quat& orientation, double mass,
                                   const Vec3& inertia, const Vec3& v = Vec3::Zero(), const Vec3& w = Vec3::Zero()) {
    BodyPeerDef d;
    d.def.position = position;
    d.def.orientation = orientation;
    d.def.linearVelocity = v;
    d.def.angularVelocity = w;
    d.def.allowSleep = false;
    d.mass = {mass, inertia};
    return world.createBody(d);
}

// Angular momentum about the origin and kinetic energy of a body (its principal inertia given).
Vec3 angularMomentum(const BodyPeer& b, double mass, const Vec3& inertia) {
    const BodyState s = b.state();
    const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
    return r * inertia.asDiagonal() * r.transpose() * s.angularVelocity + mass * s.position.cross(s.linearVelocity);
}
double kineticEnergy(const BodyPeer& b, double mass, const Vec3& inertia) {
    const BodyState s = b.state();
    const Vec3 wBody = s.orientation.conjugate() * s.angularVelocity;
    return 0.5 * mass * s.linearVelocity.squaredNorm() + 0.5 * wBody.dot(inertia.asDiagonal() * wBody);
}

// A joint between A and B with its frame at `anchor` in the world, X along `axis` and Y along
// `axle` (unit, perpendicular).
JointPeerDef pairJoint(JointType type, BodyPeer& a, BodyPeer& b, const Vec3& anchor, const Vec3& axis,
                       const Vec3& axle) {
    Eigen::Matrix3d m;
    m << axis, axle, axis.cross(axle);
    const Quat frame(m);
    const auto local = [&](const BodyPeer& body) {
        const BodyState s = body.state();
        return Transform{s.orientation.conjugate() * (anchor - s.position), (s.orientation.conjugate() * frame).normalized()};
    };
    JointPeerDef d;
    d.type = type;
    d.bodyA = &a;
    d.bodyB = &b;
    d.frameA = local(a);
    d.frameB = local(b);
    return d;
}

// ---- hinge ----------------------------------------------------------------------------------

// How far a rigid ODE joint lets a body at speed v on a radius L drift off its circle: each step
// the linearised rows let it move v h along the tangent, d = v^2 h^2 / (2 L) outward, and ERP
// removes that fraction of the gap per step, so the gap settles near d / ERP (the joints' ERP,
// kJointErp).
double radialDrift(double v, double L, double h, double erp = kJointErp) { return v * v * h * h / (2.0 * L * erp); }

// A hinge pendulum of length 1 m (a 1 kg bob, I = 4e-3 kg m^2 about its centre: a 10 cm ball)
// released at rest: period against 4 sqrt(L'/g) K(sin(theta0/2)), L' = (I + m L^2) / (m L).
TEST(OdeJoints, HingePendulumPeriodMatchesEllipticIntegral) {
    for (Solver solver : {Solver::ProjectedGaussSeidel, Solver::Direct})
        for (int substeps : {1, 4})
            for (double amplitude : {0.1, 1.0, 2.0}) {
                auto world = jointWorld(Effect::Gravity | Effect::Joints, solver, substeps);
                SCOPED_TRACE(std::string(toString(solver)) + " x" + std::to_string(substeps));
                const double L = 1.0, I = 4e-3;
                const Vec3 start(L * std::sin(amplitude), -L * std::cos(amplitude), 0.0);
                auto bob = body(*world, start, 1.0, I);
                auto hinge = world->createJoint(heldToWorld(JointType::Hinge, *bob, start, Vec3::Zero(), kXAlongZ));
                const double exact = 4.0 * std::sqrt((I + L * L) / L / kG) * ellipticK(std::sin(0.5 * amplitude));
                PeriodMeter meter;
                double worstRadius = 0.0, worstZ = 0.0, lowest = 0.0;
                run(*world, 20.0, [&](double t) {
                    const Vec3 p = bob->state().position;
                    meter.add(t, kDt, p.x());
                    worstRadius = std::max(worstRadius, std::abs(p.norm() - L));
                    worstZ = std::max(worstZ, std::abs(p.z()));
                    lowest = std::min(lowest, hinge->position());
                });
                const double period = meter.period();
                std::cout << "[ MEASURED ] ode " << toString(solver) << " x" << substeps << " hinge pendulum, amplitude "
                          << amplitude << ": period " << period << " s (exact " << exact << ", "
                          << 100.0 * (period / exact - 1.0) << " %), radius error " << worstRadius << " m\n";
                // Up to 1 rad: 0.5 %. ODE's semi-implicit Euler changes the period by O((omega h)^2),
                // a few 1e-4 at one step of 1/60 s; 0.5 % is a phase error of 10 ms per second.
                // At 2 rad the bob passes the bottom at 5.2 m/s: each step the joint's rows let it
                // drift off its circle (radialDrift) and pull it back over the next steps, a lag
                // that costs energy every swing. Measured at one step: -1.0 % (pgs) and -0.7 %
                // (direct) with the joints' ERP 0.8 (-9.6 % and -7.4 % with the world's 0.2);
                // bound 2 %, and 0.5 % with 4 substeps (measured 0.006 %: the drift falls as h^2).
                const double bound = amplitude <= 1.0 || substeps > 1 ? 0.005 : 0.02;
                EXPECT_NEAR(period, exact, bound * exact)
                    << toString(solver) << " x" << substeps << ", amplitude " << amplitude;
                // The anchor holds within twice the ERP-limited drift at the fastest point (measured
                // 0.6 to 1.6 times: quickstep's unconverged rows add to it).
                const double vMax = std::sqrt(2.0 * kG * L * (1.0 - std::cos(amplitude)));
                EXPECT_LT(worstRadius, 2.0 * radialDrift(vMax, L, kDt / substeps) + 1e-6);
                EXPECT_LT(worstZ, 1e-6);  // the hinge holds the plane (its rows are exact out of it)
                // Measured from the pose, about +Z: the bob released at +amplitude swings through
                // the bottom to the other side, an angle of -2 amplitude from its start (10 %: the
                // energy the correction takes at 2 rad).
                EXPECT_NEAR(lowest, -2.0 * amplitude, 0.1 * amplitude);
            }
}

// A motor spins a flywheel up at its maximum torque: w = tau t / I until the target speed,
// reached at t* = I w / tau, not before. Positive motor speed turns B positively about X.
TEST(OdeJoints, HingeMotorReachesTargetSpeedAtTorqueLimit) {
    for (double sign : {1.0, -1.0}) {
        auto world = jointWorld(Effect::Joints);
        const double I = 0.5, tau = 2.0, target = 10.0 * sign;  // t* = 2.5 s
        auto wheel = body(*world, Vec3::Zero(), 1.0, I);
        JointPeerDef d = heldToWorld(JointType::Hinge, *wheel, Vec3::Zero(), Vec3::Zero(), kXAlongZ);
        d.motor = JointMotor{target, tau};
        auto hinge = world->createJoint(d);
        double fastest = 0.0;
        run(*world, 1.0, [&](double t) { fastest = std::max(fastest, std::abs(hinge->speed()) - tau * t / I); });
        // After 1 s at its limit: tau t / I (1e-6: the motor row saturates exactly at FMax).
        EXPECT_NEAR(wheel->state().angularVelocity.z(), sign * tau / I, 1e-6);
        EXPECT_NEAR(hinge->speed(), sign * tau / I, 1e-6);
        EXPECT_LT(fastest, 1e-6);  // never faster than the torque allows
        EXPECT_GT(sign * hinge->position(), 0.0);  // positive speed, positive angle
        // Angle = tau t^2 / (2 I) in semi-implicit Euler's steps: (n (n + 1) / 2) h^2 tau / I.
        EXPECT_NEAR(hinge->position(), sign * 60.0 * 61.0 / 2.0 * kDt * kDt * tau / I, 1e-6);
        // The reaction torque is the motor's: -tau about X on... B receives +tau (about Z).
        EXPECT_NEAR(hinge->reactionTorque().z(), sign * tau, 1e-6);
        run(*world, 3.0);
        EXPECT_NEAR(hinge->speed(), target, 1e-6);
    }
}

// The solvers the stop tests run: ODE's direct solver (dWorldStep), quickstep at the backend's
// 50 iterations, and quickstep at 200. Bodies hung on a long lever with a small inertia of their
// own (a 10 cm ball on a 1 m arm: m L^2 / I = 250) are where quickstep converges slowly: an
// angular stop row acts on the ball's own inertia and reaches the arm only through the anchor's
// rows, iteration by iteration.
struct SolverCase {
    Solver solver;
    int iterations;
    double overshoot;  // rad, the bound on passing a stop in these tests
    std::string name() const { return std::string(toString(solver)) + " " + std::to_string(iterations) + " it"; }
};
// The stop rows are speculative (see ode_joints.hpp) and, on a body swinging on an arm, act at
// its centre. Measured on the hinge and cone tests below, the worst pass of a stop: direct 3e-6
// rad; quickstep 0.0014 rad at 50 iterations (as purely angular rows it was 0.09 rad, and 0.15
// rad with a 50 N m motor pushing into the stop), 2e-4 at 200. Bounds: 0.01 rad direct and at
// 200 iterations, 0.02 at 50 (a 50 N m motor against the stop leaves the arm 0.009 rad short
// of it: the motor's angular row converges slowly on the ball's small inertia).
const SolverCase kStopSolvers[] = {{Solver::Direct, 0, 0.01},
                                   {Solver::ProjectedGaussSeidel, 50, 0.02},
                                   {Solver::ProjectedGaussSeidel, 200, 0.01}};

// Limits hold: a pendulum swings into both stops, a motor pushes into one, and a wide range past
// pi holds too; the angle stays within [lower, upper] up to the solver's overshoot.
TEST(OdeJoints, HingeLimitsHold) {
    for (const SolverCase& c : kStopSolvers) {
        auto world = jointWorld(Effect::Gravity | Effect::Joints, c.solver, 1, c.iterations);
        const Vec3 start(0, -1, 0);
        auto bob = body(*world, start, 1.0, 4e-3);
        JointPeerDef d = heldToWorld(JointType::Hinge, *bob, start, Vec3::Zero(), kXAlongZ);
        d.limits = JointLimits{-0.3, 0.5};
        auto hinge = world->createJoint(d);
        bob->setLinearVelocity({4.0, 0, 0});  // would swing to 1.4 rad without the limit
        double lowest = 0.0, highest = 0.0;
        const auto track = [&](double) {
            lowest = std::min(lowest, hinge->position());
            highest = std::max(highest, hinge->position());
        };
        run(*world, 3.0, track);
        // A motor pushing past the lower stop (50 N m against gravity's 2.9 N m).
        hinge->setMotor(JointMotor{-5.0, 50.0});
        run(*world, 2.0);
        const double held = hinge->position();
        std::cout << "[ MEASURED ] ode " << c.name() << " hinge limits [-0.3, 0.5]: swung [" << lowest << ", "
                  << highest << "], motor-held at " << held << "\n";
        EXPECT_LT(highest, 0.5 + c.overshoot) << c.name();
        EXPECT_GT(lowest, -0.3 - c.overshoot) << c.name();
        EXPECT_GT(highest, 0.45) << c.name();  // it did reach the upper stop
        EXPECT_LT(lowest, -0.25) << c.name();  // and the lower one
        EXPECT_NEAR(held, -0.3, c.overshoot) << c.name();
        // Wide limits past pi: the measured angle is unwrapped, so the stop at 4 rad holds.
        hinge->setLimits(JointLimits{-4.0, 4.0});
        hinge->setMotor(JointMotor{3.0, 10.0});
        highest = -10.0;
        run(*world, 4.0, [&](double) { highest = std::max(highest, hinge->position()); });
        std::cout << "[ MEASURED ] ode " << c.name() << " hinge limits [-4, 4], 10 N m motor: highest " << highest << "\n";
        EXPECT_GT(highest, 3.9) << c.name();  // drove past pi
        EXPECT_LT(highest, 4.0 + c.overshoot) << c.name();
    }
}

// A hinge spring (no gravity): torsional oscillation at sqrt(k / I).
TEST(OdeJoints, HingeSpringFrequency) {
    auto world = jointWorld(Effect::Joints);
    const double k = 8.0, I = 0.5;
    auto wheel = body(*world, Vec3::Zero(), 1.0, I);
    JointPeerDef d = heldToWorld(JointType::Hinge, *wheel, Vec3::Zero(), Vec3::Zero(), kXAlongZ);
    d.spring = JointSpringSI{k, 0.0};
    auto hinge = world->createJoint(d);
    wheel->setAngularVelocity({0, 0, 0.5});
    PeriodMeter meter;
    run(*world, 10.0, [&](double t) { meter.add(t, kDt, hinge->position()); });
    const double exact = 2.0 * kPi * std::sqrt(I / k);
    std::cout << "[ MEASURED ] ode hinge spring: period " << meter.period() << " s (exact " << exact << ")\n";
    // The spring is ODE's implicit ERP / CFM row: implicit Euler lengthens the period by
    // O((omega h)^2) = 1e-3 here and damps it slightly; 1 % bound.
    EXPECT_NEAR(meter.period(), exact, 0.01 * exact);
}

// ---- reactions --------------------------------------------------------------------------------

// A body hanging still from a ball joint reports the joint's pull m g on it (N), upward, whatever
// the step and the substeps.
TEST(OdeJoints, ReactionOfHangingBodyIsItsWeight) {
    for (Solver solver : {Solver::ProjectedGaussSeidel, Solver::Direct})
        for (int substeps : {1, 4}) {
            auto world = jointWorld(Effect::Gravity | Effect::Joints, solver, substeps);
            const Vec3 start(0, -1, 0);
            auto b = body(*world, start, 2.0);
            auto ball = world->createJoint(heldToWorld(JointType::Ball, *b, start, Vec3::Zero()));
            run(*world, 2.0);
            // At rest the mean force is exactly m g (1e-3 relative: what is left of the
            // settling of ERP's correction); no sideways force, no torque about the anchor
            // (the force passes through it).
            EXPECT_NEAR(ball->reactionForce().y(), 2.0 * kG, 1e-3 * 2.0 * kG) << toString(solver) << " x" << substeps;
            EXPECT_NEAR(ball->reactionForce().x(), 0.0, 1e-6);
            EXPECT_NEAR(ball->reactionTorque().norm(), 0.0, 1e-6);
            // A fixed joint holding the same body off-centre: force m g, and a torque about the
            // anchor that holds the body's weight on its lever: r x F with r = COM - anchor.
            auto world2 = jointWorld(Effect::Gravity | Effect::Joints, solver, substeps);
            const Vec3 at(0.5, 0, 0);
            auto c = body(*world2, at, 2.0, 0.1);
            auto fixed = world2->createJoint(heldToWorld(JointType::Fixed, *c, at, Vec3::Zero()));
            run(*world2, 2.0);
            EXPECT_NEAR(fixed->reactionForce().y(), 2.0 * kG, 1e-3 * 2.0 * kG);
            // The joint's torque on B about its anchor balances gravity's: +m g L about Z.
            EXPECT_NEAR(fixed->reactionTorque().z(), 2.0 * kG * 0.5, 1e-3 * 2.0 * kG * 0.5);
        }
}

// ---- slider -----------------------------------------------------------------------------------

// A slider holding a mass on a spring along X (no gravity): oscillates at sqrt(k/m) / 2 pi.
TEST(OdeJoints, SliderSpringFrequency) {
    for (int substeps : {1, 4}) {
        auto world = jointWorld(Effect::Joints, Solver::ProjectedGaussSeidel, substeps);
        const double k = 40.0, m = 2.0;
        auto b = body(*world, Vec3::Zero(), m, 0.1);
        JointPeerDef d = heldToWorld(JointType::Slider, *b, Vec3::Zero(), Vec3::Zero());
        d.spring = JointSpringSI{k, 0.0};
        auto slider = world->createJoint(d);
        b->setLinearVelocity({0.5, 0.3, 0});  // the y part is removed by the slider
        PeriodMeter meter;
        double amplitude = 0.0;
        run(*world, 10.0, [&](double t) {
            meter.add(t, kDt, slider->position());
            amplitude = std::max(amplitude, slider->position());
        });
        const double exact = 2.0 * kPi * std::sqrt(m / k);
        std::cout << "[ MEASURED ] ode slider spring x" << substeps << ": period " << meter.period() << " s (exact "
                  << exact << "), amplitude " << amplitude << " m (undamped " << 0.5 / std::sqrt(k / m) << ")\n";
        // Implicit Euler lengthens the period by O((omega h)^2) = 1e-3 at one step; 0.5 %.
        EXPECT_NEAR(meter.period(), exact, 0.005 * exact);
        EXPECT_NEAR(b->state().position.y(), 0.0, 1e-6);
        // The amplitude: v0 / omega, less implicit Euler's numerical damping over 10 s
        // (a factor (1 + (omega h)^2)^(-n/2), 8 % at one step of 1/60 s); 10 %.
        EXPECT_NEAR(amplitude, 0.5 / std::sqrt(k / m), 0.1 * 0.5 / std::sqrt(k / m));
    }
}

// Slider motor and limits: positive speed moves B along +X; the stops hold.
TEST(OdeJoints, SliderMotorAndLimits) {
    auto world = jointWorld(Effect::Joints);
    auto b = body(*world, Vec3(1, 2, 3), 2.0, 0.1);
    // Axis along world +Y (X of the frame turned +90 degrees about Z).
    JointPeerDef d = heldToWorld(JointType::Slider, *b, Vec3(1, 2, 3), Vec3(1, 2, 3),
                                 Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitZ())));
    d.motor = JointMotor{1.0, 4.0};  // 2 m/s^2 up to 1 m/s: reached at 0.5 s
    d.limits = JointLimits{-0.5, 1.5};
    auto slider = world->createJoint(d);
    run(*world, 0.25);
    EXPECT_NEAR(slider->speed(), 0.5, 1e-6);  // F t / m, at the force limit
    EXPECT_NEAR(b->state().linearVelocity.y(), 0.5, 1e-6);
    EXPECT_NEAR(slider->reactionForce().y(), 4.0, 1e-6);  // the motor's force on B
    double highest = 0.0;
    run(*world, 3.0, [&](double) { highest = std::max(highest, slider->position()); });
    // 1 m/s into the stop: the speculative stop row lets it close exactly the gap (1e-5 m: the
    // row's CFM, 1e-6 m/N, gives about 4e-6 m under the motor's 4 N).
    EXPECT_LT(highest, 1.5 + 1e-5);
    EXPECT_NEAR(slider->position(), 1.5, 1e-3);  // resting against the stop, motor pushing
    slider->setMotor(JointMotor{-1.0, 4.0});
    run(*world, 4.0);
    EXPECT_NEAR(slider->position(), -0.5, 1e-3);
    EXPECT_NEAR(b->state().position.x(), 1.0, 1e-9);
}

// A slider spring between two free bodies (no gravity): its force acts on both at B's anchor,
// so the pair keeps its angular momentum, and the pair turns as B oscillates. A 3 kg ball at the
// origin, a 2 kg ball at (1, 0, 0) moving 0.5 m/s along the axis (+Y): linearised, the period is
// 2 pi / sqrt(k (mu + I) / (mu I)), mu the reduced mass and I the balls' own moments (the arm
// turns with the pair): 0.2298 s; the spring pushing at the centres gave sqrt(mu / k)'s 1.088 s
// and Lz from 1.0 down to -0.2. Then a box turned off the axes, on a diagonal axis.
TEST(OdeJoints, SliderSpringBetweenTwoBodiesKeepsAngularMomentum) {
    const double k = 40.0, mA = 3.0, mB = 2.0;
    const Vec3 iA = Vec3::Constant(0.4 * mA * 0.2 * 0.2), iB = Vec3::Constant(0.4 * mB * 0.1 * 0.1);
    {
        auto world = jointWorld(Effect::Joints);
        auto a = freeBody(*world, Vec3::Zero(), Quat::Identity(), mA, iA);
        auto b = freeBody(*world, Vec3(1, 0, 0), Quat::Identity(), mB, iB, Vec3(0, 0.5, 0));
        JointPeerDef d = pairJoint(JointType::Slider, *a, *b, Vec3(1, 0, 0), Vec3::UnitY(), -Vec3::UnitX());
        d.spring = JointSpringSI{k, 0.0};
        auto slider = world->createJoint(d);
        const double l0 = (angularMomentum(*a, mA, iA) + angularMomentum(*b, mB, iB)).z();
        double worst = 0.0;
        PeriodMeter meter;
        run(*world, 5.0, [&](double t) {
            meter.add(t, kDt, slider->position());
            const double l = (angularMomentum(*a, mA, iA) + angularMomentum(*b, mB, iB)).z();
            worst = std::max(worst, std::abs(l - l0));
        });
        const double mu = mA * mB / (mA + mB), inertia = iA.z() + iB.z();
        const double exact = 2.0 * kPi / std::sqrt(k * (mu + inertia) / (mu * inertia));
        std::cout << "[ MEASURED ] ode pair slider spring: period " << meter.period() << " s (linearised " << exact
                  << "), max |Lz - L0| " << worst << " (L0 " << l0 << ")\n";
        // omega h = 0.46: semi-implicit Euler shortens the period by about 1 % (2 asin(omega h
        // / 2) / h); the swing (2 cm on a 1 m arm) adds little nonlinearity: 2.5 %.
        EXPECT_NEAR(meter.period(), exact, 0.025 * exact);
        // L: only the rows' drift correction (ERP on gaps of 1e-6 m) moves it; 1e-3 of L0.
        EXPECT_LT(worst, 1e-3 * std::abs(l0));
    }
    {
        auto world = jointWorld(Effect::Joints);
        const Vec3 iBox = mB / 3.0 * Vec3(0.2 * 0.2 + 0.3 * 0.3, 0.1 * 0.1 + 0.3 * 0.3, 0.1 * 0.1 + 0.2 * 0.2);
        const Vec3 axis = Vec3(1, -2, 0.5).normalized();
        const Quat turned(Eigen::AngleAxisd(1.0, Vec3(0.3, 0.7, -0.2).normalized()));
        auto a = freeBody(*world, Vec3(0, 2, 3), Quat::Identity(), mA, iA);
        auto b = freeBody(*world, Vec3(1, 2, 3), turned, mB, iBox, 0.5 * axis);
        JointPeerDef d = pairJoint(JointType::Slider, *a, *b, Vec3(1, 2, 3), axis, axis.unitOrthogonal());
        d.spring = JointSpringSI{k, 0.0};
        auto slider = world->createJoint(d);
        const Vec3 l0 = angularMomentum(*a, mA, iA) + angularMomentum(*b, mB, iBox);
        double worst = 0.0;
        run(*world, 10.0, [&](double) {
            worst = std::max(worst, (angularMomentum(*a, mA, iA) + angularMomentum(*b, mB, iBox) - l0).norm());
        });
        std::cout << "[ MEASURED ] ode pair slider spring, diagonal: max |L - L0| " << worst << " (|L0| " << l0.norm()
                  << ")\n";
        // About 1.1 with the spring at the centres. Measured 0.033: ODE's implicit gyroscopic
        // step of the box's own spin does not keep its L exactly (with an isotropic B this case
        // keeps L to 1e-14); 2 % of |L0|.
        EXPECT_LT(worst, 0.02 * l0.norm());
    }
}

// ---- distance ---------------------------------------------------------------------------------

// A distance joint as a rod: a pendulum keeps its length over the whole swing; with a spring it
// oscillates at sqrt(k/m).
TEST(OdeJoints, DistanceRodKeepsLengthAndSpringOscillates) {
    {
        auto world = jointWorld();
        const Vec3 start(1.5, 0, 0);
        auto bob = body(*world, start);
        JointPeerDef d;
        d.type = JointType::Distance;
        d.bodyB = bob.get();
        d.anchorA = Vec3(0, 0, 0);
        d.anchorB = Vec3::Zero();
        d.length = 1.5;
        auto rod = world->createJoint(d);
        double worst = 0.0, lowest = 0.0;
        run(*world, 10.0, [&](double) {
            worst = std::max(worst, std::abs(rod->position()));
            lowest = std::min(lowest, bob->state().position.y());
        });
        std::cout << "[ MEASURED ] ode distance rod: worst length error " << worst << " m\n";
        // At the bottom of a 1.5 m drop (5.4 m/s) the rod's ERP-limited drift (radialDrift) is
        // 3.4 mm (measured 3.4 mm); 1.5 times that.
        EXPECT_LT(worst, 1.5 * radialDrift(std::sqrt(2.0 * kG * 1.5), 1.5, kDt));
        EXPECT_LT(lowest, -1.45);  // it swung through the bottom
    }
    {
        auto world = jointWorld(Effect::Joints);
        const double k = 50.0, m = 0.5;
        auto bob = body(*world, Vec3(1, 0, 0), m);
        JointPeerDef d;
        d.type = JointType::Distance;
        d.bodyB = bob.get();
        d.anchorA = Vec3(0, 0, 0);
        d.length = 1.0;
        d.spring = JointSpringSI{k, 0.0};
        auto spring = world->createJoint(d);
        bob->setLinearVelocity({0.3, 0, 0});
        PeriodMeter meter;
        run(*world, 10.0, [&](double t) { meter.add(t, kDt, spring->position()); });
        const double exact = 2.0 * kPi * std::sqrt(m / k);
        std::cout << "[ MEASURED ] ode distance spring: period " << meter.period() << " s (exact " << exact << ")\n";
        // Implicit Euler: O((omega h)^2) = 3e-3; 1 %.
        EXPECT_NEAR(meter.period(), exact, 0.01 * exact);
    }
}

// A rope (maxLength only): slack inside, the body falls freely; taut, the length never passes
// maxLength by more than the solver's residual; a range's minLength stops a body pushed inward.
TEST(OdeJoints, RopeAllowsSlackAndHoldsItsMaximum) {
    for (const Solver solver : {Solver::ProjectedGaussSeidel, Solver::Direct}) {
        auto world = jointWorld(Effect::Gravity | Effect::Joints, solver);
        const Vec3 start(0.5, 0, 0);
        auto bob = body(*world, start, 1.0, 4e-3);
        JointPeerDef d;
        d.type = JointType::Distance;
        d.bodyB = bob.get();
        d.anchorA = Vec3::Zero();
        d.length = 0.5;
        d.maxLength = 1.0;
        auto rope = world->createJoint(d);
        // Slack until the bob is 1 m from the anchor: y = -sqrt(1 - 0.25) = -0.866 m, reached
        // after t = sqrt(2 0.866 / g) = 0.42 s. Until 0.35 s, exactly free fall (1e-9: rounding).
        run(*world, 0.35);
        EXPECT_NEAR(bob->state().linearVelocity.y(), -kG * 0.35, 1e-9) << toString(solver);
        EXPECT_NEAR(rope->reactionForce().norm(), 0.0, 1e-9);
        double longest = 0.0;
        run(*world, 6.0, [&](double) { longest = std::max(longest, rope->position() + d.length); });
        std::cout << "[ MEASURED ] ode " << toString(solver) << " rope: longest " << longest << " m (max 1)\n";
        // Speculative row: the rope goes taut exactly at 1 m; what follows is the swing's drift
        // at 4.4 m/s (radialDrift, 3.4 mm; measured 4.5 mm at the world's ERP, which contact
        // rows use); twice that.
        EXPECT_LT(longest, 1.0 + 2.0 * radialDrift(std::sqrt(2.0 * kG), 1.0, kDt)) << toString(solver);
        EXPECT_GT(longest, 0.99) << toString(solver);  // it went taut
    }
    // A range [0.6, 0.8] without a spring: a body thrown toward the anchor stops at 0.6 m.
    auto world = jointWorld(Effect::Joints, Solver::Direct);
    auto b = body(*world, Vec3(0.7, 0, 0));
    JointPeerDef d;
    d.type = JointType::Distance;
    d.bodyB = b.get();
    d.length = 0.7;
    d.minLength = 0.6;
    d.maxLength = 0.8;
    auto range = world->createJoint(d);
    b->setLinearVelocity({-1.0, 0, 0});
    double shortest = 1.0, longest = 0.0;
    run(*world, 3.0, [&](double) {
        shortest = std::min(shortest, range->position() + d.length);
        longest = std::max(longest, range->position() + d.length);
    });
    // Without restitution the body stops at the bound (1e-3 m: ERP's residual) and stays.
    EXPECT_NEAR(shortest, 0.6, 1e-3);
    EXPECT_LT(longest, 0.7 + 1e-9);
    EXPECT_NEAR(range->position() + d.length, 0.6, 1e-3);
    // The hold pushed the body away from the anchor: +x on B while stopping it.
    b->setLinearVelocity({2.0, 0, 0});
    run(*world, 1.0);
    EXPECT_NEAR(range->position() + d.length, 0.8, 1e-3);  // and the maximum stops it
}

// Joints wake what they hold: creating a joint on a sleeping body, or changing its motor, wakes
// it; bodies joined by a joint sleep and wake together.
TEST(OdeJoints, JointsWakeTheirBodies) {
    auto world = jointWorld(Effect::Gravity | Effect::Joints | Effect::Sleeping, Solver::Direct);
    auto b = body(*world, Vec3(0, -1, 0));
    b->setAwake(false);
    ASSERT_FALSE(b->isAwake());
    JointPeerDef d = heldToWorld(JointType::Hinge, *b, Vec3(0, -1, 0), Vec3::Zero(), kXAlongZ);
    auto hinge = world->createJoint(d);
    EXPECT_TRUE(b->isAwake());
    b->setAwake(false);
    hinge->setMotor(JointMotor{1.0, 10.0});
    EXPECT_TRUE(b->isAwake());
    run(*world, 0.5);
    EXPECT_GT(hinge->position(), 0.4);  // the motor turned it (1 rad/s for 0.5 s, less the spin-up)
    // Two bodies chained to the world: waking the far one wakes the near one (one ODE island).
    auto c = body(*world, Vec3(0, -2, 0));
    JointPeerDef e;
    e.type = JointType::Ball;
    e.bodyA = b.get();
    e.bodyB = c.get();
    e.frameA = {Vec3(0, -0.5, 0), Quat::Identity()};
    e.frameB = {Vec3(0, 0.5, 0), Quat::Identity()};
    auto ball = world->createJoint(e);
    hinge->setMotor(std::nullopt);
    b->setAwake(false);
    c->setAwake(false);
    c->setLinearVelocity({1, 0, 0});
    run(*world, kDt);
    EXPECT_TRUE(b->isAwake());
    EXPECT_TRUE(c->isAwake());
}

// A static bodyB held by a dynamic bodyA (the layer allows either to be the dynamic one): the
// joint holds, reports B's side (the weight of A pulls B down: reaction -m g on B), and the
// pendulum, and a wheel held to the world, fall asleep like any body once at rest.
TEST(OdeJoints, StaticBodyBAndSleepingWithStandIns) {
    auto world = jointWorld(Effect::Gravity | Effect::Joints | Effect::Sleeping, Solver::Direct);
    BodyPeerDef fixedDef;
    fixedDef.def.type = BodyType::Static;
    fixedDef.def.position = Vec3(0, 1, 0);
    auto ceiling = world->createBody(fixedDef);
    BodyPeerDef bobDef;
    bobDef.def.position = Vec3(0, 0, 0);
    bobDef.mass = {2.0, Vec3::Constant(0.01)};
    auto bob = world->createBody(bobDef);  // allowSleep true
    JointPeerDef d;
    d.type = JointType::Ball;
    d.bodyA = bob.get();
    d.bodyB = ceiling.get();
    d.frameA = {Vec3(0, 1, 0), Quat::Identity()};
    d.frameB = {Vec3(0, 0, 0), Quat::Identity()};
    auto ball = world->createJoint(d);
    run(*world, 1.0);
    EXPECT_NEAR(bob->state().position.y(), 0.0, 1e-3);  // held
    EXPECT_NEAR(ball->reactionForce().y(), -2.0 * kG, 1e-3 * 2.0 * kG);  // what the joint applies to B
    // A wheel held to the world on a damped spring.
    auto wheel = world->createBody(bobDef);
    JointPeerDef w = heldToWorld(JointType::Wheel, *wheel, Vec3::Zero(), Vec3::Zero(),
                                 Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitZ())));
    w.spring = JointSpringSI{400.0, 60.0};
    auto wheelJoint = world->createJoint(w);
    run(*world, 10.0);
    EXPECT_FALSE(bob->isAwake());
    EXPECT_FALSE(wheel->isAwake());
    EXPECT_NEAR(wheelJoint->position(), -2.0 * kG / 400.0, 1e-3);  // asleep where the spring holds it
    // Woken, the joints still hold.
    bob->setLinearVelocity({1, 0, 0});
    wheel->setAwake(true);
    run(*world, 1.0);
    EXPECT_NEAR((bob->state().position - Vec3(0, 1, 0)).norm(), 1.0, 1e-2);
    EXPECT_NEAR(wheelJoint->position(), -2.0 * kG / 400.0, 1e-3);
}

// Between two free bodies a hinge motor turns B positively about X relative to A, and A the
// other way (the motor's torque is internal: total angular momentum stays 0).
TEST(OdeJoints, HingeMotorBetweenTwoBodiesSign) {
    auto world = jointWorld(Effect::Joints);
    auto a = body(*world, Vec3(0, 0, 0), 1.0, 0.2);
    auto b = body(*world, Vec3(0, 0, 1), 1.0, 0.1);
    JointPeerDef d;
    d.type = JointType::Hinge;
    d.bodyA = a.get();
    d.bodyB = b.get();
    d.frameA = {Vec3(0, 0, 0.5), kXAlongZ};   // axis +Z through both centres
    d.frameB = {Vec3(0, 0, -0.5), kXAlongZ};
    d.motor = JointMotor{3.0, 0.6};
    auto hinge = world->createJoint(d);
    run(*world, 0.5);
    // tau t / I_rel with 1/I_rel = 1/0.2 + 1/0.1: relative spin 0.6 x 0.5 x 15 = 4.5 rad/s is
    // past 3: the motor reached its target and holds it.
    EXPECT_NEAR(hinge->speed(), 3.0, 1e-6);
    EXPECT_GT(b->state().angularVelocity.z(), 0.0);
    EXPECT_LT(a->state().angularVelocity.z(), 0.0);
    EXPECT_NEAR(0.2 * a->state().angularVelocity.z() + 0.1 * b->state().angularVelocity.z(), 0.0, 1e-9);
    EXPECT_GT(hinge->position(), 0.0);
}

// ---- cone -------------------------------------------------------------------------------------

// A cone joint: a bob thrown sideways stays within the swing limit; B spun about X stays within
// the twist limits.
TEST(OdeJoints, ConeSwingAndTwistLimitsHold) {
    for (const SolverCase& c : kStopSolvers) {
        auto world = jointWorld(Effect::Gravity | Effect::Joints, c.solver, 1, c.iterations);
        const Vec3 start(0, -1, 0);
        auto bob = body(*world, start, 1.0, 4e-3);
        // Twist axis X along -Y (down the arm at rest): the swing is the angle from hanging.
        JointPeerDef d = heldToWorld(JointType::Cone, *bob, start, Vec3::Zero(),
                                     Quat(Eigen::AngleAxisd(-0.5 * kPi, Vec3::UnitZ())));
        d.swingLimit = 0.4;
        d.twistLimits = JointLimits{-0.2, 0.3};
        auto cone = world->createJoint(d);
        bob->setLinearVelocity({3.0, 0, 2.0});  // would swing to about 1.3 rad
        bob->setAngularVelocity({0, 4.0, 0});   // about the arm: frame X is -Y, so a twist of -4 rad/s
        double worstSwing = 0.0, lowTwist = 0.0, highTwist = 0.0;
        run(*world, 5.0, [&](double) {
            worstSwing = std::max(worstSwing, cone->position());
            const Quat rel = d.frameA.orientation.conjugate() * bob->state().orientation * d.frameB.orientation;
            const double twist = 2.0 * std::atan2(rel.x(), rel.w());
            lowTwist = std::min(lowTwist, twist);
            highTwist = std::max(highTwist, twist);
        });
        std::cout << "[ MEASURED ] ode " << c.name() << " cone: worst swing " << worstSwing
                  << " rad (limit 0.4), twist [" << lowTwist << ", " << highTwist << "] (limits [-0.2, 0.3])\n";
        EXPECT_LT(worstSwing, 0.4 + c.overshoot) << c.name();
        EXPECT_GT(worstSwing, 0.35) << c.name();  // it reached the cone
        EXPECT_GT(lowTwist, -0.2 - c.overshoot) << c.name();
        EXPECT_LT(highTwist, 0.3 + c.overshoot) << c.name();
        EXPECT_LT(lowTwist, -0.15) << c.name();  // it reached the twist stop
    }
}

// ---- wheel ------------------------------------------------------------------------------------

// A wheel held to the world: suspension along +Y (frame X) with a spring oscillates at
// sqrt(k/m); the motor spins it about the axle (frame Y = world -X... see the frame) at the
// target speed with the sign of the motor; steering turns the axle.
TEST(OdeJoints, WheelSuspensionSpinAndSteering) {
    auto world = jointWorld(Effect::Joints);
    const double k = 200.0, m = 2.0, I = 0.05;
    auto wheel = body(*world, Vec3::Zero(), m, I);
    // Frame: X (suspension) along world +Y, Y (axle) along world -X, Z along +Z.
    JointPeerDef d = heldToWorld(JointType::Wheel, *wheel, Vec3::Zero(), Vec3::Zero(),
                                 Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitZ())));
    d.spring = JointSpringSI{k, 0.0};
    d.motor = JointMotor{6.0, 1.0};  // spin-up at tau / I = 20 rad/s^2: reached at 0.3 s
    d.steering = true;
    auto joint = world->createJoint(d);
    wheel->setLinearVelocity({0, 0.4, 0});
    PeriodMeter meter;
    run(*world, 0.1);
    EXPECT_NEAR(joint->speed(), 2.0, 1e-6);  // tau t / I at the torque limit
    run(*world, 5.0, [&](double t) { meter.add(t, kDt, joint->position()); });
    const double exact = 2.0 * kPi * std::sqrt(m / k);
    std::cout << "[ MEASURED ] ode wheel suspension: period " << meter.period() << " s (exact " << exact << ")\n";
    // Implicit Euler: O((omega h)^2) = 3e-3; 1 %.
    EXPECT_NEAR(meter.period(), exact, 0.01 * exact);
    EXPECT_NEAR(joint->speed(), 6.0, 1e-6);
    // The spin is about the axle, world -X: angular velocity -6 about X.
    EXPECT_NEAR(wheel->state().angularVelocity.x(), -6.0, 1e-6);
    EXPECT_NEAR(wheel->state().position.x(), 0.0, 1e-6);  // no travel across the suspension
    // Steering 0.3 rad: the axle turns about the suspension axis (world +Y) by +0.3.
    joint->setSteeringAngle(0.3);
    run(*world, 2.0);
    const Vec3 axle = wheel->state().orientation * (d.frameB.orientation * Vec3::UnitY());
    const Vec3 steered = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY())) * Vec3(-1, 0, 0);
    EXPECT_NEAR((axle - steered).norm(), 0.0, 1e-3);  // within ERP's residual of the stop
    EXPECT_NEAR(joint->speed(), 6.0, 1e-3);            // spinning about the steered axle
}

// A wheel hanging on its suspension under gravity: at rest it sags m g / k and the joint holds
// its weight (reaction m g up); its travel limits stop a wheel thrown along the suspension.
TEST(OdeJoints, WheelSagReactionAndTravelLimits) {
    for (const Solver solver : {Solver::ProjectedGaussSeidel, Solver::Direct}) {
        auto world = jointWorld(Effect::Gravity | Effect::Joints, solver);
        const double k = 400.0, m = 2.0;
        auto wheel = body(*world, Vec3::Zero(), m, 0.05);
        JointPeerDef d = heldToWorld(JointType::Wheel, *wheel, Vec3::Zero(), Vec3::Zero(),
                                     Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitZ())));  // X up, axle -X
        d.spring = JointSpringSI{k, 2.0 * std::sqrt(k * m)};  // critically damped
        d.limits = JointLimits{-0.1, 0.1};
        auto joint = world->createJoint(d);
        run(*world, 3.0);
        // Sag m g / k = 4.9 cm (1e-4 m: the spring row's CFM and ERP at rest are exact; the
        // residual is the settling of the damped motion); reaction m g (0.1 %).
        EXPECT_NEAR(joint->position(), -m * kG / k, 1e-4) << toString(solver);
        EXPECT_NEAR(joint->reactionForce().y(), m * kG, 1e-3 * m * kG) << toString(solver);
        EXPECT_NEAR(joint->reactionForce().x(), 0.0, 1e-6) << toString(solver);
        // Without the spring, thrown up at 5 m/s: the upper stop holds at +0.1 m (speculative
        // row: 1e-3, the ERP residual), then down at 5 m/s: the lower stop.
        joint->setSpring(std::nullopt);
        double highest = -1.0, lowest = 1.0;
        wheel->setLinearVelocity({0, 5.0, 0});
        run(*world, 0.3, [&](double) { highest = std::max(highest, joint->position()); });
        wheel->setLinearVelocity({0, -5.0, 0});
        run(*world, 0.3, [&](double) { lowest = std::min(lowest, joint->position()); });
        std::cout << "[ MEASURED ] ode " << toString(solver) << " wheel travel [-0.1, 0.1]: [" << lowest << ", "
                  << highest << "]\n";
        EXPECT_NEAR(highest, 0.1, 1e-3) << toString(solver);
        EXPECT_NEAR(lowest, -0.1, 1e-3) << toString(solver);
    }
}

// A free wheel between two free bodies (no gravity, no limits, motor or spring), co-rotating at
// 0.3 rad/s about the spin axis while B slides out along the suspension axis at 0.5 m/s relative
// to A. An ideal joint keeps L and the kinetic energy; ODE's hinge2 with its anchors fixed in
// the bodies pushed them at points parting with the travel: at 10 s Lz 92.6 (from 0.977) and
// 27 J (from 0.387 J). The suspension along Y and along Z, then resting against a travel limit.
TEST(OdeJoints, WheelBetweenTwoBodiesKeepsAngularMomentumAndEnergy) {
    const double mA = 3.0, mB = 2.0, w = 0.3;
    const Vec3 iA = Vec3::Constant(0.4 * mA * 0.2 * 0.2), iB = Vec3::Constant(0.4 * mB * 0.1 * 0.1);
    struct Case {
        Vec3 axis, spinAxis;
        bool limited;
    };
    for (const Case& c : {Case{Vec3::UnitY(), Vec3::UnitZ(), false}, Case{Vec3::UnitZ(), Vec3::UnitY(), false},
                          Case{Vec3::UnitY(), Vec3::UnitZ(), true}}) {
        auto world = jointWorld(Effect::Joints);
        // Turning about the centre of mass at w about the spin axis, B sliding out along the axis.
        const Vec3 spin = w * c.spinAxis, com(mB / (mA + mB), 0, 0);
        const auto vAt = [&](const Vec3& p) { return Vec3(spin.cross(p - com)); };
        auto a = freeBody(*world, Vec3::Zero(), Quat::Identity(), mA, iA, vAt(Vec3::Zero()) - 0.2 * c.axis, spin);
        auto b = freeBody(*world, Vec3(1, 0, 0), Quat::Identity(), mB, iB, vAt(Vec3(1, 0, 0)) + 0.3 * c.axis, spin);
        JointPeerDef d = pairJoint(JointType::Wheel, *a, *b, Vec3(1, 0, 0), c.axis, c.spinAxis);
        if (c.limited) d.limits = JointLimits{-0.1, 0.1};
        auto wheel = world->createJoint(d);
        const Vec3 l0 = angularMomentum(*a, mA, iA) + angularMomentum(*b, mB, iB);
        const double e0 = kineticEnergy(*a, mA, iA) + kineticEnergy(*b, mB, iB);
        double worstL = 0.0, worstE = 0.0;
        run(*world, 10.0, [&](double) {
            worstL = std::max(worstL, (angularMomentum(*a, mA, iA) + angularMomentum(*b, mB, iB) - l0).norm());
            if (!c.limited) worstE = std::max(worstE, std::abs(kineticEnergy(*a, mA, iA) + kineticEnergy(*b, mB, iB) - e0));
        });
        std::cout << "[ MEASURED ] ode pair wheel, axis " << c.axis.transpose() << (c.limited ? ", limited" : "")
                  << ": max |L - L0| " << worstL << " (|L0| " << l0.norm() << "), max |KE - KE0| " << worstE
                  << " J (KE0 " << e0 << ")\n";
        // L: measured 1e-13, every row now pushes both bodies at one point (against the limit
        // too, whose stop takes the impact inelastically: energy not checked there); 1e-3. The
        // energy moves by the rows' drift correction in the turning pair (measured 2.4e-4 and
        // 1.0e-3 of KE0, was 70x KE0); 3e-3.
        EXPECT_LT(worstL, 1e-3 * l0.norm());
        EXPECT_LT(worstE, 3e-3 * e0);
        if (c.limited) {
            EXPECT_LT(wheel->position(), 0.1 + 1e-3);
        }
    }
}

// A planar world (each body on ODE's plane-2D joint): a hinge about Z is a pendulum in the
// plane, with the small-amplitude period 2 pi sqrt(L'/g) and the bob kept in z = 0.
TEST(OdeJoints, PlanarHingePendulum) {
    WorldSettings s;
    s.planar = true;
    OdeWorld world(withBackendDefaults(s, backendInfo("ode").capabilities));
    world.setEffects(Effect::Gravity | Effect::Joints);
    const double L = 1.0, I = 4e-3, amplitude = 0.1;
    const Vec3 start(L * std::sin(amplitude), -L * std::cos(amplitude), 0.0);
    auto bob = body(world, start, 1.0, I);
    auto hinge = world.createJoint(heldToWorld(JointType::Hinge, *bob, start, Vec3::Zero(), kXAlongZ));
    PeriodMeter meter;
    double lowest = 0.0;
    run(world, 10.0, [&](double t) {
        meter.add(t, kDt, bob->state().position.x());
        lowest = std::min(lowest, hinge->position());
    });
    const double exact = 4.0 * std::sqrt((I + L * L) / L / kG) * ellipticK(std::sin(0.5 * amplitude));
    EXPECT_NEAR(meter.period(), exact, 0.005 * exact);  // as the 3D pendulum's bound
    EXPECT_NEAR(bob->state().position.z(), 0.0, 1e-12);
    EXPECT_NEAR(lowest, -2.0 * amplitude, 0.01 * amplitude);  // through the bottom to the other side
}

// A hanging chain of 20 ball-jointed links (0.1 m, 0.1 kg each) with an end mass of 10 kg (100
// links' worth): the gap that opens at the joints under the load, per solver. ODE's direct
// solver is exact per step (gaps from the CFM only: 1e-6 m/N under ~100 N); quickstep's 50
// iterations cannot carry the end load up 20 links (the figure issue 10 asks for).
TEST(OdeJoints, HangingChainWithHeavyEndGap) {
    for (const SolverCase& c : kStopSolvers) {
        auto world = jointWorld(Effect::Gravity | Effect::Joints, c.solver, 1, c.iterations);
        constexpr int kLinks = 20;
        const double link = 0.1;
        std::vector<std::unique_ptr<BodyPeer>> bodies;
        std::vector<std::unique_ptr<JointPeer>> joints;
        for (int i = 0; i < kLinks; ++i) {
            const bool end = i == kLinks - 1;
            const Vec3 at(0, -(i + 0.5) * link, 0);
            bodies.push_back(body(*world, at, end ? 10.0 : 0.1, end ? 1e-2 : 1e-4));
            JointPeerDef d;
            d.type = JointType::Ball;
            d.bodyB = bodies.back().get();
            d.frameB = {Vec3(0, 0.5 * link, 0), Quat::Identity()};
            if (i == 0) {
                d.frameA = {Vec3::Zero(), Quat::Identity()};
            } else {
                d.bodyA = bodies[i - 1].get();
                d.frameA = {Vec3(0, -0.5 * link, 0), Quat::Identity()};
            }
            joints.push_back(world->createJoint(d));
        }
        run(*world, 5.0);
        const double length = -bodies.back()->state().position.y() + 0.5 * link;
        const double stretch = length - kLinks * link;
        std::cout << "[ MEASURED ] ode " << c.name() << " chain of 20 links, end 100x: stretch " << stretch
                  << " m over " << kLinks * link << " m; top joint pulls " << joints[0]->reactionForce().y()
                  << " N (weight " << (10.0 + 1.9) * kG << " N)\n";
        // Bounds: direct 1 mm (measured 0.04 mm). Quickstep, measured: 8.0 cm at 50 iterations,
        // 1.9 cm at 200 (32 and 7.4 cm with the world's ERP 0.2), a known weakness of PGS on a
        // 100:1 mass ratio (what issue 10 asks to report), bounded at 1.5 times that so a
        // regression shows: 12 cm and 3 cm.
        const double bound = c.solver == Solver::Direct ? 1e-3 : c.iterations < 100 ? 0.12 : 0.03;
        EXPECT_LT(std::abs(stretch), bound) << c.name();
        if (c.solver == Solver::Direct) {
            // The top joint carries everything below it (0.1 %).
            EXPECT_NEAR(joints[0]->reactionForce().y(), 11.9 * kG, 1e-3 * 11.9 * kG);
        }
    }
}

// ---- contacts, lifetime -----------------------------------------------------------------------

// Two overlapping boxes joined by a ball joint: with collideConnected false they produce no
// contacts; true, they do.
TEST(OdeJoints, CollideConnectedFalseStopsContactsBetweenThePair) {
    for (bool collide : {false, true}) {
        auto world = jointWorld(Effect::Joints | Effect::Contacts | Effect::Events);
        auto a = body(*world, Vec3(0, 0, 0), 1.0, 0.1, ShapeDef::box(Vec3(0.5, 0.5, 0.5)));
        auto b = body(*world, Vec3(0.8, 0, 0), 1.0, 0.1, ShapeDef::box(Vec3(0.5, 0.5, 0.5)));
        JointPeerDef d;
        d.type = JointType::Ball;
        d.bodyA = a.get();
        d.bodyB = b.get();
        d.frameA = {Vec3(0.4, 0, 0), Quat::Identity()};
        d.frameB = {Vec3(-0.4, 0, 0), Quat::Identity()};
        d.collideConnected = collide;
        auto joint = world->createJoint(d);
        ContactReport report;
        std::size_t pairs = 0;
        run(*world, 0.5, [&](double) {
            report.clear();
            world->reportContacts(report);
            pairs += report.pairs.size();
        });
        if (collide) {
            EXPECT_GT(pairs, 0u);
        } else {
            EXPECT_EQ(pairs, 0u);
        }
        // Without contacts pushing them apart the joint keeps them overlapping.
        if (!collide) {
            EXPECT_NEAR((b->state().position - a->state().position).norm(), 0.8, 1e-6);
        }
        world->destroyJoint(*joint);
        joint.reset();
        if (!collide) {
            // The pair collides again once the joint is gone.
            pairs = 0;
            run(*world, 0.1, [&](double) {
                report.clear();
                world->reportContacts(report);
                pairs += report.pairs.size();
            });
            EXPECT_GT(pairs, 0u);
        }
    }
}

// Destroying joints (every type, mid-motion) leaves the world stepping, the bodies free.
TEST(OdeJoints, DestroyLeavesTheWorldStepping) {
    auto world = jointWorld();
    auto a = body(*world, Vec3(0, 0, 0), 1.0, 0.1);
    auto b = body(*world, Vec3(1, 0, 0), 1.0, 0.1);
    std::vector<std::unique_ptr<JointPeer>> joints;
    for (JointType type : {JointType::Fixed, JointType::Ball, JointType::Hinge, JointType::Slider, JointType::Distance,
                           JointType::Cone, JointType::Wheel}) {
        JointPeerDef d = heldToWorld(type, *b, Vec3(1, 0, 0), Vec3(0.5, 0, 0));
        d.bodyA = a.get();
        d.frameA = {Vec3(0.5, 0, 0), Quat::Identity()};
        d.length = 1.0;
        d.anchorB = Vec3::Zero();
        joints.push_back(world->createJoint(d));
    }
    run(*world, 0.5);
    for (auto& j : joints) {
        world->destroyJoint(*j);
        j.reset();
        run(*world, 0.1);
    }
    const Vec3 v = b->state().linearVelocity;
    run(*world, 0.5);
    // Free fall of both: velocity changes by g t exactly.
    EXPECT_NEAR(b->state().linearVelocity.y() - v.y(), -kG * 0.5, 1e-9);
    EXPECT_TRUE(std::isfinite(a->state().position.norm()));
}

// Effect::Joints off: the joints do nothing (free fall), on again: they hold.
TEST(OdeJoints, JointsEffectTurnsJointsOff) {
    auto world = jointWorld(Effect::Gravity);
    const Vec3 start(0, -1, 0);
    auto b = body(*world, start);
    auto ball = world->createJoint(heldToWorld(JointType::Ball, *b, start, Vec3::Zero()));
    run(*world, 0.5);
    EXPECT_NEAR(b->state().linearVelocity.y(), -kG * 0.5, 1e-9);
    EXPECT_EQ(ball->reactionForce(), Vec3::Zero());
    world->setEffects(Effect::Gravity | Effect::Joints);
    b->setTransform(start, Quat::Identity());
    b->setLinearVelocity(Vec3::Zero());
    run(*world, 1.0);
    EXPECT_NEAR(b->state().position.y(), -1.0, 1e-3);
}

// ODE takes back ERP (0.8) x a joint's anchor gap per step as a velocity, without bound. A
// 40-link ball chain (0.1 kg balls 10 cm apart, a 1 kg end, released horizontal) tears at one
// step of 1/60 s (the declared joints.chain_gap); its links were then pulled back harder each
// step: in 5 s they flew at up to 282 m/s (pgs) and 186 m/s (direct), the chain gaining 1.1e4 and
// 6.5e3 J (the catalogue's chain_40: 1.7 km/s). With the pull capped at kJointPushMaxVelocity the
// torn chain stays a chain of falling balls: fastest 31.0 and 32.2 m/s, gaining nothing (pgs) and
// at most 27 J (direct). Bounds: 40 m/s (Bullet's torn catalogue chain whips at 22 and 31 m/s,
// 42 and 29 before its joints' pull was capped too; native's whole one at 14.4) and 60 J (the 27 measured, twice over).
TEST(OdeJoints, ATornChainIsNotFlungApartByItsJoints) {
    for (const Solver solver : {Solver::ProjectedGaussSeidel, Solver::Direct}) {
        SCOPED_TRACE(toString(solver));
        WorldSettings s;
        s.backend = "ode";
        s.solver = solver;
        anyphys::World world(s);
        std::vector<anyphys::Body> links;
        anyphys::Body previous;
        for (int i = 0; i < 40; ++i) {
            BodyDef d;
            d.shape = ShapeDef::sphere(0.03);
            d.mass = i == 39 ? 1.0 : 0.1;
            d.position = Vec3(0.1 * (i + 1), 0.0, 0.0);
            d.allowSleep = false;
            const anyphys::Body link = world.createBody(d);
            JointDef j;
            j.type = JointType::Ball;
            j.bodyA = previous;
            j.bodyB = link;
            j.anchor = Vec3(0.1 * i, 0.0, 0.0);
            world.createJoint(j);
            links.push_back(link);
            previous = link;
        }
        const auto energy = [&] {
            double e = 0.0;
            for (std::size_t i = 0; i < links.size(); ++i) {
                const anyphys::Body& b = links[i];
                const double mass = i + 1 == links.size() ? 1.0 : 0.1;
                e += mass * (0.5 * b.linearVelocity().squaredNorm() + kG * b.position().y());
            }
            return e;
        };
        const double start = energy();
        double fastest = 0.0, mostGained = 0.0;
        for (int step = 0; step < 300; ++step) {
            world.step();
            for (const anyphys::Body& b : links) fastest = std::max(fastest, b.linearVelocity().norm());
            mostGained = std::max(mostGained, energy() - start);
        }
        std::cout << "[ MEASURED ] ode torn chain (" << toString(solver) << "): fastest link " << fastest
                  << " m/s, most energy gained " << mostGained << " J\n";
        EXPECT_LT(fastest, 40.0);
        EXPECT_LT(mostGained, 60.0);
    }
}

}  // namespace
}  // namespace anyphys::ode
