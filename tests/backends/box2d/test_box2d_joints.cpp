// Box2D joints at the peer level, in the XY plane, against closed forms (the contract suite checks
// every backend through World; these pin down what box2d_joints.cpp does with each Box2D joint:
// frames, signs, the springs of hinges and sliders (second Box2D joints), reactions over
// substeps). Every tolerance says why it holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "anyphys/backends.hpp"
#include "box2d_test_helpers.hpp"
#include "box2d_world.hpp"

namespace anyphys::box2d::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 1.0 / 60.0;

// Joint frames with X along +Z or -Z (hinges), or along a direction in the plane.
const Quat kXUp(Eigen::AngleAxisd(-0.5 * kPi, Vec3::UnitY()));   // X -> +Z
const Quat kXDown(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitY()));  // X -> -Z
Quat xAlong(double angle) { return Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())); }  // X in the plane

std::unique_ptr<Box2dWorld> jointWorld(Effects effects = Effect::Gravity | Effect::Joints, int substeps = 1) {
    WorldSettings s = planarSettings();
    s.substeps = substeps;
    // Unset solver settings resolved as the layer does (8 velocity iterations per Box2D step).
    auto world = std::make_unique<Box2dWorld>(withBackendDefaults(s, backendInfo("box2d").capabilities));
    world->setEffects(effects);
    return world;
}

// A body without shapes (joints only) of the given mass and moment about Z, or a box when `half`
// is given (for contacts).
std::unique_ptr<BodyPeer> body(Box2dWorld& world, const Vec3& position, double mass = 1.0, double inertia = 1e-2,
                               const Vec3& half = Vec3::Zero()) {
    BodyPeerDef d;
    d.def.position = position;
    d.def.allowSleep = false;
    d.mass = {mass, Vec3::Constant(inertia)};
    if (!half.isZero()) {
        d.def.shape = ShapeDef::box(half);
        d.shapes.push_back({ShapeDef::box(half), Transform{}, nullptr});
    }
    return world.createBody(d);
}

// A joint holding `b` (at `bodyPosition`, identity orientation) to the world, frame at `anchor`.
JointPeerDef heldToWorld(JointType type, BodyPeer& b, const Vec3& bodyPosition, const Vec3& anchor,
                         const Quat& frame = kXUp) {
    JointPeerDef d;
    d.type = type;
    d.bodyB = &b;
    d.frameA = {anchor, frame};
    d.frameB = {anchor - bodyPosition, frame};
    return d;
}

void run(Box2dWorld& world, double seconds, double dt = kDt) {
    const int steps = static_cast<int>(std::lround(seconds / dt));
    for (int i = 0; i < steps; ++i) world.step(i * dt, dt);
}

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

// Mean period of a signal from its downward zero crossings (interpolated within the step).
template <class Signal>
double measurePeriod(Box2dWorld& world, Signal signal, double duration, double dt = kDt) {
    double t = 0.0, previous = signal(), first = -1.0, last = -1.0;
    int crossings = 0;
    while (t < duration) {
        world.step(t, dt);
        t += dt;
        const double x = signal();
        if (previous > 0.0 && x <= 0.0) {
            const double crossing = t - dt * x / (x - previous);
            if (first < 0.0) first = crossing;
            last = crossing;
            ++crossings;
        }
        previous = x;
    }
    return crossings > 1 ? (last - first) / (crossings - 1) : 0.0;
}

// ---- hinge ---------------------------------------------------------------------------------

// A hinge pendulum of 1 m (a 1 kg bob with I = 4e-3 kg m^2) released at rest from several
// amplitudes: the period against 4 sqrt(L'/g) K(sin(theta0/2)), L' = (I + m L^2) / (m L), and the
// energy lost over 20 s. Both hinge axes (+Z and -Z) give the same motion.
// Box2D 2.4 solves the joint at the velocity level and corrects positions afterwards without
// touching velocities: each Box2D step projects the bob's velocity, tangent to the circle at the
// last step's position, onto the new tangent, a loss of about (omega h)^2 of the kinetic energy a
// step. The swing decays (at 1/60 s: half the energy in 20 s at 1 rad) and its period shortens
// toward the small-amplitude one. So the period is taken over the first swing, and the bounds are
// the measured cost of the solver, printed, with room for rounding only, still failing if the
// joint stops holding or the loss grows; substeps cut the loss as h:
//   1 substep:  period 0.5 % at 0.1 rad (the loss is (omega h)^2 = 3e-5 of a small swing), 1 % at
//               1 rad (measured -0.56 %), 10 % at 2 rad (measured -8.6 %, half a swing's decay);
//   8 substeps: 0.5 % up to 1 rad (measured -0.08 %), 2.5 % at 2 rad (measured -1.6 %).
// The energy may only go down (the projection removes energy), by at most the listed fraction of
// the swing's energy; sampled at the end, it may read up to about omega h / 2 of the swing high
// (3 % at 1/60 s, omega = 3.1 rad/s): semi-implicit Euler's energy oscillates that much within a
// swing.
TEST(Box2dJoints, HingePendulumPeriodMatchesEllipticIntegral) {
    struct Case {
        int substeps;
        double amplitude, periodBound, lossBound;
    };
    for (const Case& c : {Case{1, 0.1, 0.005, 0.1}, Case{1, 1.0, 0.01, 0.6}, Case{1, 2.0, 0.10, 0.8},
                          Case{8, 0.1, 0.005, 0.02}, Case{8, 1.0, 0.005, 0.15}, Case{8, 2.0, 0.025, 0.3}})
        for (const Quat& frame : {kXUp, kXDown}) {
            const std::string name = std::to_string(c.substeps) + " substeps, amplitude " + std::to_string(c.amplitude) +
                                     (frame.isApprox(kXUp) ? ", axis +Z" : ", axis -Z");
            SCOPED_TRACE(name);
            auto world = jointWorld(Effect::Gravity | Effect::Joints, c.substeps);
            const double L = 1.0, I = 4e-3;
            const Vec3 start(L * std::sin(c.amplitude), -L * std::cos(c.amplitude), 0.0);
            auto bob = body(*world, start, 1.0, I);
            auto hinge = world->createJoint(heldToWorld(JointType::Hinge, *bob, start, Vec3::Zero(), frame));
            const auto energy = [&] {
                const BodyState s = bob->state();
                return 0.5 * s.linearVelocity.squaredNorm() + 0.5 * I * s.angularVelocity.squaredNorm() + kG * s.position.y();
            };
            const double e0 = energy(), swing = kG * L * (1.0 - std::cos(c.amplitude));
            const double exact = 4.0 * std::sqrt((I + L * L) / L / kG) * ellipticK(std::sin(0.5 * c.amplitude));
            double t = 0.0, previous = start.x(), radiusError = 0.0;
            std::vector<double> crossings;
            while (t < 20.0) {
                world->step(t, kDt);
                t += kDt;
                const double x = bob->state().position.x();
                if (previous > 0.0 && x <= 0.0) crossings.push_back(t - kDt * x / (x - previous));
                previous = x;
                radiusError = std::max(radiusError, std::abs(bob->state().position.norm() - L));
            }
            ASSERT_GE(crossings.size(), 2u);
            const double first = crossings[1] - crossings[0];
            const double mean = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
            const double loss = (e0 - energy()) / swing;
            report("hinge pendulum, " + name + ": first period (exact " + std::to_string(exact) + ")", first, "s");
            report("hinge pendulum, " + name + ": mean period over 20 s", mean, "s");
            report("hinge pendulum, " + name + ": energy lost in 20 s (of the swing's)", loss);
            EXPECT_NEAR(first, exact, c.periodBound * exact);
            EXPECT_GT(loss, -0.03);
            EXPECT_LT(loss, c.lossBound);
            // The anchor holds: Box2D's position correction stops at b2_linearSlop (5 mm); single
            // precision adds nothing comparable at 1 m.
            EXPECT_LT(radiusError, 5e-3);
            // The angle is the bob's turn about the axis, right-handed (the bob swings through
            // the bottom, +x to -x, turning about world -Z: negative about +Z).
            EXPECT_NEAR(hinge->position(), (frame.isApprox(kXUp) ? 1.0 : -1.0) * (std::atan2(bob->state().position.x(),
                                                                                             -bob->state().position.y()) - c.amplitude), 1e-5);
        }
}

// Angle and speed follow the contract's right-hand rule about frame X, whatever Box2D's +Z: a
// body spinning at +1 rad/s about world +Z reads +1 on a hinge about +Z and -1 about -Z.
TEST(Box2dJoints, HingeAngleIsRightHandedAboutFrameX) {
    for (const Quat& frame : {kXUp, kXDown}) {
        auto world = jointWorld(Effect::Joints);
        auto wheel = body(*world, Vec3::Zero(), 1.0, 0.5);
        auto hinge = world->createJoint(heldToWorld(JointType::Hinge, *wheel, Vec3::Zero(), Vec3::Zero(), frame));
        EXPECT_DOUBLE_EQ(hinge->position(), 0.0);
        wheel->setAngularVelocity(Vec3(0, 0, 1.0));
        run(*world, 4.0);  // past pi: the angle is not wrapped
        const double sign = frame.isApprox(kXUp) ? 1.0 : -1.0;
        // Float angles and velocities: 1e-5 relative.
        EXPECT_NEAR(hinge->speed(), sign * 1.0, 1e-5);
        EXPECT_NEAR(hinge->position(), sign * 4.0, 4e-5);
    }
}

// A motor spins a flywheel up at its maximum torque: w = tau t / I until the target speed, reached
// at t* = I w / tau = 2.5 s, never faster. Positive motor speed gives a positive angle rate about
// either hinge axis.
TEST(Box2dJoints, HingeMotorReachesTargetSpeedAtTorqueLimit) {
    for (const Quat& frame : {kXUp, kXDown}) {
        auto world = jointWorld(Effect::Joints);
        const double I = 0.5, tau = 2.0, target = 10.0;
        auto wheel = body(*world, Vec3::Zero(), 1.0, I);
        JointPeerDef d = heldToWorld(JointType::Hinge, *wheel, Vec3::Zero(), Vec3::Zero(), frame);
        d.motor = JointMotor{target, tau};
        auto hinge = world->createJoint(d);
        double t = 0.0, worstExcess = 0.0;
        for (int i = 0; i < 60; ++i) {
            world->step(t, kDt);
            t += kDt;
            worstExcess = std::max(worstExcess, hinge->speed() - tau * t / I);
        }
        // After 1 s at the torque limit all along: tau t / I (float sums of 60 steps: 1e-5).
        EXPECT_NEAR(hinge->speed(), tau * 1.0 / I, 1e-5 * target);
        EXPECT_LT(worstExcess, 1e-5 * target);  // never above the torque-limited ramp
        EXPECT_GT(hinge->position(), 0.0);
        // The reaction torque is the motor's: tau (N m), on B, about the axis (world +Z or -Z).
        const double sign = frame.isApprox(kXUp) ? 1.0 : -1.0;
        EXPECT_NEAR(hinge->reactionTorque().z(), sign * tau, 1e-4 * tau);
        run(*world, 2.0);  // t = 3 s > t*
        EXPECT_NEAR(hinge->speed(), target, 1e-5 * target);
    }
}

// A hinge with limits holds its angle within them: an arm released horizontal falls onto the
// lower stop (-0.5 rad about +Z; about -Z the same fall is +0.5, onto the upper stop of [-0.2, 0.5]).
// Box2D solves the stop (an angular row) and the anchor (a point row) one after the other, 8
// velocity iterations a step: the stop holds a body of moderate lever at once, but the momentum
// of a heavy bob on a long lever (m r^2 / I = 100) passes the stop until the iterations and
// position correction catch it. Bounds, from measurement, with a margin for rounding:
//   a uniform rod, anchored at its end (m r^2 / I = 3): 0.01 rad (measured 0.005);
//   a point-like bob on a 1 m arm (m r^2 / I = 100): 0.2 rad (measured 0.155; 30 iterations
//   bring it to 0.06). Unlimited, either would swing on to -pi/2, 1.07 rad past the stop.
// Once at rest, within b2_angularSlop (2 degrees, 0.035 rad) of the stop.
TEST(Box2dJoints, HingeLimitsHoldTheAngle) {
    struct Case {
        const char* name;
        double lever, inertia, bound;
    };
    for (const Case& c : {Case{"rod", 0.5, 1.0 / 12.0, 0.01}, Case{"bob", 1.0, 1e-2, 0.2}})
        for (const Quat& frame : {kXUp, kXDown}) {
            const bool up = frame.isApprox(kXUp);
            SCOPED_TRACE(std::string(c.name) + (up ? ", axis +Z" : ", axis -Z"));
            auto world = jointWorld();
            const Vec3 start(c.lever, 0.0, 0.0);
            auto arm = body(*world, start, 1.0, c.inertia);
            JointPeerDef d = heldToWorld(JointType::Hinge, *arm, start, Vec3::Zero(), frame);
            d.limits = up ? JointLimits{-0.5, 0.2} : JointLimits{-0.2, 0.5};
            auto hinge = world->createJoint(d);
            double low = 0.0, high = 0.0;
            for (int i = 0; i < 180; ++i) {
                world->step(i * kDt, kDt);
                low = std::min(low, hinge->position());
                high = std::max(high, hinge->position());
            }
            report(std::string("hinge limit overshoot, ") + c.name + (up ? ", axis +Z" : ", axis -Z"),
                   up ? -0.5 - low : high - 0.5, "rad");
            EXPECT_GE(low, d.limits->lower - c.bound);
            EXPECT_LE(high, d.limits->upper + c.bound);
            // It did reach the stop (the bounds alone would pass a joint that never moved) and
            // rests there.
            EXPECT_NEAR(hinge->position(), up ? -0.5 : 0.5, 0.035);
            // Removing the limits lets it swing down (to -pi/2 about +Z).
            hinge->setLimits(std::nullopt);
            run(*world, 0.5);
            EXPECT_GT(std::abs(hinge->position()), 0.8);
        }
}

// A torsion spring on a hinge (the backend's impulses beside the revolute, which has none): a
// flywheel oscillates at sqrt(k / I). Bound 0.5 %: the spring is soft here ((omega h)^2 = 0.011)
// and stepped explicitly, semi-implicit Euler, whose period is short by about (omega h)^2 / 24;
// an implicit one would be long by (omega h)^2 / 3 = 0.4 % (omega = 6.3 rad/s).
TEST(Box2dJoints, HingeSpringFrequency) {
    for (const Quat& frame : {kXUp, kXDown}) {
        auto world = jointWorld(Effect::Joints);
        const double I = 0.5, k = 20.0;
        auto wheel = body(*world, Vec3::Zero(), 1.0, I);
        JointPeerDef d = heldToWorld(JointType::Hinge, *wheel, Vec3::Zero(), Vec3::Zero(), frame);
        d.spring = JointSpringSI{k, 0.0};
        auto hinge = world->createJoint(d);
        wheel->setAngularVelocity(Vec3(0, 0, -1.0));  // so the angle first goes down about +Z
        const double exact = 2.0 * kPi * std::sqrt(I / k);
        const double period = measurePeriod(*world, [&] { return hinge->position() * (frame.isApprox(kXUp) ? 1.0 : -1.0); }, 10.0);
        report("hinge spring period (exact " + std::to_string(exact) + ")", period, "s");
        EXPECT_NEAR(period, exact, 0.005 * exact);
    }
}

// A torsion spring between two free flywheels (I = 0.5 and 0.25 kg m^2, no world): they counter-
// rotate at sqrt(k (1/I_A + 1/I_B)) = 5.5 rad/s (bound 0.5 %: (omega h)^2 / 3 = 0.3 %), and the
// spring's torques are equal and opposite, so the angular momentum stays what it was (float: 1e-5).
TEST(Box2dJoints, HingeSpringBetweenTwoBodies) {
    auto world = jointWorld(Effect::Joints);
    const double IA = 0.5, IB = 0.25, k = 5.0;
    auto a = body(*world, Vec3::Zero(), 1.0, IA);
    auto b = body(*world, Vec3::Zero(), 1.0, IB);
    JointPeerDef d;
    d.type = JointType::Hinge;
    d.bodyA = a.get();
    d.bodyB = b.get();
    d.frameA = d.frameB = {Vec3::Zero(), kXUp};
    d.spring = JointSpringSI{k, 0.0};
    auto hinge = world->createJoint(d);
    a->setAngularVelocity(Vec3(0, 0, 1.0));  // momentum 0.5: the pair turns at 2/3 rad/s on average
    const double momentum = IA * 1.0;
    double worst = 0.0;
    const double period = measurePeriod(*world, [&] {
        worst = std::max(worst, std::abs(IA * a->state().angularVelocity.z() + IB * b->state().angularVelocity.z() - momentum));
        return -hinge->speed();  // B falls behind A first: the rate starts negative
    }, 10.0);
    const double exact = 2.0 * kPi / std::sqrt(k * (1.0 / IA + 1.0 / IB));
    report("two-body hinge spring period (exact " + std::to_string(exact) + ")", period, "s");
    EXPECT_NEAR(period, exact, 0.005 * exact);
    EXPECT_LT(worst, 1e-5);
}

// A hinge damper (a spring of stiffness 0): a flywheel's spin decays as an implicit damper gives
// it, w_n = w_0 / (1 + h c / I)^n (float: 1e-5 relative); it does not turn rigid nor spring back.
TEST(Box2dJoints, HingeDamperWithoutStiffness) {
    auto world = jointWorld(Effect::Joints);
    const double I = 0.5, c = 0.4;
    auto wheel = body(*world, Vec3::Zero(), 1.0, I);
    JointPeerDef d = heldToWorld(JointType::Hinge, *wheel, Vec3::Zero(), Vec3::Zero());
    d.spring = JointSpringSI{0.0, c};
    auto hinge = world->createJoint(d);
    wheel->setAngularVelocity(Vec3(0, 0, 2.0));
    run(*world, 1.0);
    const double expected = 2.0 / std::pow(1.0 + kDt * c / I, 60);
    EXPECT_NEAR(hinge->speed(), expected, 1e-5 * 2.0);
    EXPECT_GT(hinge->position(), 1.0);  // it kept turning: 1.6 rad in the second
    // Reaction torque: the damper's -c w (N m, on B), a step's mean.
    EXPECT_NEAR(hinge->reactionTorque().z(), -c * expected, 0.02 * c * expected);
}

// A stiff torsion spring (1e5 N m/rad, critically damped) holds a 1 kg point-like bob (I = 1e-3
// kg m^2) on a 1 m arm against a steady 10 N push across the arm (no gravity): it rests at
// F L / k = 1e-4 rad. The spring is implicit here ((omega h)^2 = 28) and solved for the joint
// alone with its pin, on the rate the push gives the bob this substep: left out, the bob rests
// 1 + (omega h)^2 = 29 times too far. 2 % (float, and the pin's own correction), still after 2 s.
TEST(Box2dJoints, StiffHingeSpringHoldsALeverAgainstAForce) {
    for (int substeps : {1, 4}) {
        auto world = jointWorld(Effect::Joints | Effect::UserForces, substeps);
        const double m = 1.0, L = 1.0, k = 1e5, F = 10.0;
        const double c = 2.0 * std::sqrt(k * (m * L * L + 1e-3));
        auto bob = body(*world, Vec3(L, 0, 0), m, 1e-3);
        JointPeerDef d = heldToWorld(JointType::Hinge, *bob, Vec3(L, 0, 0), Vec3::Zero());
        d.spring = JointSpringSI{k, c};
        auto hinge = world->createJoint(d);
        for (int i = 0; i < 120; ++i) {
            bob->addForce(Vec3(0, F, 0));
            world->step(i * kDt, kDt);
        }
        report("lever pushed against a stiff hinge spring, " + std::to_string(substeps) + " substeps (exact " +
                   std::to_string(F * L / k) + ")",
               hinge->position(), "rad");
        EXPECT_NEAR(hinge->position(), F * L / k, 0.02 * F * L / k);
        EXPECT_NEAR(hinge->speed(), 0.0, 1e-4);
    }
}

// A lever held up by a stiff hinge spring (2e4 N m/rad, critically damped; 2 kg at 1 m, under
// gravity) comes to rest at m g L / k and falls asleep there; asleep, the hinge still reports the
// torque it holds, m g L about its anchor (1e-3 relative: float, and the lever's cos of 1e-3 rad).
TEST(Box2dJoints, SleepingLeverKeepsItsSpringTorque) {
    auto world = jointWorld(Effect::Gravity | Effect::Joints | Effect::Sleeping);
    const double m = 2.0, L = 1.0, k = 2e4;
    BodyPeerDef bd;
    bd.def.position = Vec3(L, 0, 0);
    bd.def.allowSleep = true;
    bd.mass = {m, Vec3::Constant(1e-2)};
    auto bob = world->createBody(bd);
    JointPeerDef d = heldToWorld(JointType::Hinge, *bob, Vec3(L, 0, 0), Vec3::Zero());
    d.spring = JointSpringSI{k, 2.0 * std::sqrt(k * (m * L * L + 1e-2))};
    auto hinge = world->createJoint(d);
    run(*world, 3.0);
    EXPECT_FALSE(bob->isAwake());
    EXPECT_NEAR(hinge->position(), -m * kG * L / k, 1e-3 * m * kG * L / k);
    EXPECT_NEAR(hinge->reactionTorque().z(), m * kG * L, 1e-3 * m * kG * L);
}

// A vertical slider on a spring holds a 2 kg body under gravity at the static sag m g / k below
// its start, and the joint carries its weight (the spring is solved with gravity in Box2D's
// solver). k = 100 N/m, damping ratio 0.7, 5 s to settle (e^{-zeta omega t} = 1e-8): sag within
// 1e-5 m (float), reaction within 1e-4 relative.
TEST(Box2dJoints, SliderSpringHoldsAWeight) {
    for (int substeps : {1, 4}) {
        auto world = jointWorld(Effect::Gravity | Effect::Joints, substeps);
        const double m = 2.0, k = 100.0, c = 2.0 * 0.7 * std::sqrt(k * m);
        auto b = body(*world, Vec3::Zero(), m, 0.1);
        JointPeerDef d = heldToWorld(JointType::Slider, *b, Vec3::Zero(), Vec3::Zero(), xAlong(0.5 * kPi));  // X = +Y
        d.spring = JointSpringSI{k, c};
        auto slider = world->createJoint(d);
        run(*world, 5.0);
        EXPECT_NEAR(slider->position(), -m * kG / k, 1e-5);
        EXPECT_NEAR(slider->reactionForce().y(), m * kG, 1e-4 * m * kG);
        EXPECT_NEAR(slider->reactionForce().x(), 0.0, 1e-4);
        // Removing the spring lets it fall along the slider.
        slider->setSpring(std::nullopt);
        run(*world, 0.5);
        EXPECT_LT(slider->position(), -1.0);
    }
}

// Frames arrive in the bodies' peer frames, which need not be the Box2D body frames: a bob whose
// peer frame is turned 0.7 rad about Z, and one whose principal axes put the peer frame's Z along
// world -Y (kept by the backend as a constant embedding). The hinge reads 0 at creation and then
// the bob's turn about the anchor (right-handed about +Z), as with an unturned bob (float: 1e-5).
TEST(Box2dJoints, FramesInTurnedPeerFrames) {
    for (const Quat& orientation : {Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ())),
                                    Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ()) * Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX()))}) {
        auto world = jointWorld();
        const double amplitude = 0.8;
        const Vec3 start(std::sin(amplitude), -std::cos(amplitude), 0.0);
        BodyPeerDef bd;
        bd.def.position = start;
        bd.def.orientation = orientation;
        bd.def.allowSleep = false;
        bd.mass = {1.0, Vec3::Constant(4e-3)};
        auto bob = world->createBody(bd);
        JointPeerDef d;
        d.type = JointType::Hinge;
        d.bodyB = bob.get();
        d.frameA = {Vec3::Zero(), kXUp};
        d.frameB = {orientation.conjugate() * (Vec3::Zero() - start), (orientation.conjugate() * kXUp).normalized()};
        auto hinge = world->createJoint(d);
        EXPECT_NEAR(hinge->position(), 0.0, 1e-6);
        double worst = 0.0, lowest = 0.0;
        for (int i = 0; i < 90; ++i) {
            world->step(i * kDt, kDt);
            lowest = std::min(lowest, hinge->position());
            const Vec3 p = bob->state().position;
            worst = std::max(worst, std::abs(hinge->position() - (std::atan2(p.x(), -p.y()) - amplitude)));
            EXPECT_NEAR(p.norm(), 1.0, 5e-3);  // the anchor holds at the right point of the bob
        }
        EXPECT_LT(worst, 1e-5);
        EXPECT_LT(lowest, -1.4);  // it swung through the bottom to the other side (-1.6 undamped)
    }
}

// ---- reactions ---------------------------------------------------------------------------------

// A 3 kg body hanging still from a joint reports the joint's pull on it, m g upward (N), whatever
// the step and the substeps: Box2D's impulses are summed over the substeps and divided by the step.
// Bound 1e-4 relative: at rest the impulse per Box2D step is m g h exactly up to float rounding.
TEST(Box2dJoints, ReactionOfHangingBodyIsItsWeightAtAnyStepAndSubsteps) {
    for (JointType type : {JointType::Ball, JointType::Hinge, JointType::Fixed, JointType::Distance})
        for (int substeps : {1, 4})
            for (double dt : {1.0 / 60.0, 1.0 / 30.0}) {
                SCOPED_TRACE(std::string(toString(type)) + ", substeps " + std::to_string(substeps) + ", dt " + std::to_string(dt));
                auto world = jointWorld(Effect::Gravity | Effect::Joints, substeps);
                const Vec3 start(0, -1, 0);
                auto b = body(*world, start, 3.0);
                JointPeerDef d = heldToWorld(type, *b, start, Vec3::Zero());
                if (type == JointType::Distance) {
                    d.anchorA = Vec3::Zero();
                    d.anchorB = Vec3::Zero();  // the body's centre
                    d.length = 1.0;
                }
                auto joint = world->createJoint(d);
                run(*world, 2.0, dt);
                EXPECT_NEAR(joint->reactionForce().y(), 3.0 * kG, 1e-4 * 3.0 * kG);
                EXPECT_NEAR(joint->reactionForce().x(), 0.0, 1e-4);
                EXPECT_NEAR(joint->reactionTorque().z(), 0.0, 1e-4);
            }
}

// A body welded to the world by an anchor 0.5 m to the right of its centre: the joint holds it
// with m g up at the anchor and a torque about the anchor that cancels the weight's, -0.5 m g
// (N m about +Z). Torques are about B's anchor, in the world frame.
TEST(Box2dJoints, FixedJointReactionTorqueIsAboutTheAnchor) {
    for (int substeps : {1, 4}) {
        auto world = jointWorld(Effect::Gravity | Effect::Joints, substeps);
        const Vec3 start(0, 0, 0);
        auto b = body(*world, start, 2.0, 0.1);
        auto weld = world->createJoint(heldToWorld(JointType::Fixed, *b, start, Vec3(0.5, 0, 0)));
        run(*world, 2.0);
        // Float impulses at rest: 1e-4 relative. The weld holds it (position correction: slop).
        EXPECT_NEAR(weld->reactionForce().y(), 2.0 * kG, 1e-4 * 2.0 * kG);
        EXPECT_NEAR(weld->reactionTorque().z(), -0.5 * 2.0 * kG, 1e-4 * kG);
        EXPECT_NEAR(b->state().position.y(), 0.0, 5e-3);
        EXPECT_DOUBLE_EQ(weld->position(), 0.0);
    }
}

// ---- slider ------------------------------------------------------------------------------------

// A slider along a diagonal of the plane holds a mass on a spring (a b2WheelJoint beside the
// prismatic, which has none), no gravity: it oscillates at sqrt(k/m) / 2 pi along the axis and not
// across it. Bound 0.5 %: the implicit spring's period is longer by (omega h)^2 / 3 = 0.2 %.
TEST(Box2dJoints, SliderSpringFrequency) {
    auto world = jointWorld(Effect::Joints);
    const double k = 40.0, m = 2.0, angle = 0.25 * kPi;
    const Vec3 axis(std::cos(angle), std::sin(angle), 0.0);
    auto b = body(*world, Vec3::Zero(), m, 0.1);
    JointPeerDef d = heldToWorld(JointType::Slider, *b, Vec3::Zero(), Vec3::Zero(), xAlong(angle));
    d.spring = JointSpringSI{k, 0.0};
    auto slider = world->createJoint(d);
    b->setLinearVelocity(0.5 * axis);
    double across = 0.0;
    const double period = measurePeriod(*world, [&] {
        across = std::max(across, std::abs(b->state().position.dot(Vec3(-axis.y(), axis.x(), 0))));
        return slider->position();
    }, 10.0);
    const double exact = 2.0 * kPi * std::sqrt(m / k);
    report("slider spring period (exact " + std::to_string(exact) + ")", period, "s");
    EXPECT_NEAR(period, exact, 0.005 * exact);
    EXPECT_LT(across, 1e-5);  // the prismatic holds it on the axis (float rounding)
    // The position is the offset along the axis; its rate is the speed along it.
    EXPECT_NEAR(slider->position(), b->state().position.dot(axis), 1e-6);
    EXPECT_NEAR(slider->speed(), b->state().linearVelocity.dot(axis), 1e-5);
}

// A slider motor drives the offset at its speed (positive: along +X of the frame) with at most
// its force: v = F t / m until the target. Float sums: 1e-5 relative.
TEST(Box2dJoints, SliderMotorAndLimits) {
    auto world = jointWorld(Effect::Joints);
    const double m = 2.0, force = 4.0, target = 1.0;  // t* = m v / F = 0.5 s
    auto b = body(*world, Vec3::Zero(), m, 0.1);
    JointPeerDef d = heldToWorld(JointType::Slider, *b, Vec3::Zero(), Vec3::Zero(), xAlong(kPi));  // X = world -X
    d.motor = JointMotor{target, force};
    d.limits = JointLimits{-0.1, 0.8};
    auto slider = world->createJoint(d);
    run(*world, 0.25);
    EXPECT_NEAR(slider->speed(), force * 0.25 / m, 1e-5);
    EXPECT_LT(b->state().linearVelocity.x(), 0.0);  // frame X is world -X
    EXPECT_NEAR(slider->reactionForce().x(), -force, 1e-4 * force);
    double high = 0.0;
    for (int i = 0; i < 120; ++i) {
        world->step(i * kDt, kDt);
        high = std::max(high, slider->position());
    }
    report("slider limit overshoot", high - 0.8, "m");
    // The motor pushes into the upper stop: held within b2_linearSlop (5 mm), resting on it.
    EXPECT_LE(high, 0.8 + 5e-3);
    EXPECT_NEAR(slider->position(), 0.8, 5e-3);
}

// ---- distance ------------------------------------------------------------------------------------

// A distance joint without a range is a rigid rod: a pendulum on it keeps its length. Bound 5 mm:
// Box2D's position correction leaves up to b2_linearSlop; measured printed.
TEST(Box2dJoints, DistanceRodKeepsItsLength) {
    auto world = jointWorld();
    const Vec3 start(1.0, 0.0, 0.0);
    auto bob = body(*world, start);
    JointPeerDef d;
    d.type = JointType::Distance;
    d.bodyB = bob.get();
    d.anchorA = Vec3::Zero();
    d.anchorB = Vec3::Zero();
    d.length = 1.0;
    d.frameA = {Vec3::Zero(), Quat::Identity()};
    d.frameB = {Vec3::Zero(), Quat::Identity()};
    auto rod = world->createJoint(d);
    double worst = 0.0;
    for (int i = 0; i < 600; ++i) {
        world->step(i * kDt, kDt);
        worst = std::max(worst, std::abs(rod->position()));
        ASSERT_NEAR(rod->position(), bob->state().position.norm() - 1.0, 1e-6);
    }
    report("distance rod length error", worst, "m");
    EXPECT_LT(worst, 5e-3);
    EXPECT_LT(bob->state().position.y(), -0.5);  // it swung (the bound is not trivially met)
}

// A rope (maxLength only) is slack inside: a bob 0.5 m from the anchor falls freely until the rope
// is taut at 1 m, then never goes beyond. Free fall checked against Box2D's own semi-implicit
// Euler, y_n = -g h^2 n (n + 1) / 2 (float: 1e-5 m).
TEST(Box2dJoints, RopeIsSlackInsideItsLength) {
    auto world = jointWorld();
    const Vec3 start(0.5, 0.0, 0.0);
    auto bob = body(*world, start);
    JointPeerDef d;
    d.type = JointType::Distance;
    d.bodyB = bob.get();
    d.anchorA = Vec3::Zero();
    d.anchorB = Vec3::Zero();
    d.length = 0.5;
    d.maxLength = 1.0;
    auto rope = world->createJoint(d);
    const int n = 12;  // 0.2 s: the fall is 0.2 m, the rope (sqrt(1 - 0.25) = 0.87 m down) is slack
    run(*world, n * kDt);
    EXPECT_NEAR(bob->state().position.y(), -kG * kDt * kDt * n * (n + 1) / 2.0, 1e-5);
    EXPECT_NEAR(bob->state().position.x(), 0.5, 1e-6);
    EXPECT_NEAR(rope->reactionForce().norm(), 0.0, 1e-6);
    double longest = 0.0;
    for (int i = 0; i < 300; ++i) {
        world->step(i * kDt, kDt);
        longest = std::max(longest, rope->position() + 0.5);
    }
    report("rope stretch beyond maxLength", longest - 1.0, "m");
    EXPECT_LT(longest, 1.0 + 5e-3);  // b2_linearSlop, as for the rod
    EXPECT_GT(longest, 0.99);        // it did become taut
}

// A distance range (minLength and maxLength) is free inside and stops at either end: a bob 0.75 m
// from the anchor, no gravity, moving inward at 1 m/s, coasts freely for 0.25 s (float: 1e-5 m)
// and stops at 0.5 m without going through (b2_linearSlop, 5 mm).
TEST(Box2dJoints, DistanceRangeIsFreeInsideAndStopsAtItsEnds) {
    auto world = jointWorld(Effect::Joints);
    auto bob = body(*world, Vec3(0.75, 0, 0));
    JointPeerDef d;
    d.type = JointType::Distance;
    d.bodyB = bob.get();
    d.length = 0.75;
    d.minLength = 0.5;
    d.maxLength = 1.0;
    auto range = world->createJoint(d);
    bob->setLinearVelocity(Vec3(-1.0, 0, 0));
    run(*world, 0.15);
    EXPECT_NEAR(range->position(), -0.15, 1e-5);  // free: 0.6 m from the anchor
    EXPECT_NEAR(range->speed(), -1.0, 1e-5);
    double shortest = 1.0;
    for (int i = 0; i < 60; ++i) {
        world->step(i * kDt, kDt);
        shortest = std::min(shortest, range->position() + 0.75);
    }
    report("distance range overshoot below minLength", 0.5 - shortest, "m");
    EXPECT_GT(shortest, 0.5 - 5e-3);
    EXPECT_NEAR(range->position() + 0.75, 0.5, 5e-3);  // it reached the stop and stays there
    EXPECT_NEAR(range->speed(), 0.0, 1e-5);
}

// A distance spring (Box2D's own soft distance joint) with no gravity: the bob oscillates along
// the line at sqrt(k/m) / 2 pi about `length`. Bound 0.5 %: implicit spring, (omega h)^2 / 3 = 0.2 %.
TEST(Box2dJoints, DistanceSpringFrequency) {
    auto world = jointWorld(Effect::Joints);
    const double k = 30.0, m = 1.5;
    auto bob = body(*world, Vec3(1, 0, 0), m);
    JointPeerDef d;
    d.type = JointType::Distance;
    d.bodyB = bob.get();
    d.anchorA = Vec3::Zero();
    d.anchorB = Vec3::Zero();
    d.length = 1.0;
    d.spring = JointSpringSI{k, 0.0};
    auto spring = world->createJoint(d);
    bob->setLinearVelocity(Vec3(0.3, 0, 0));
    const double exact = 2.0 * kPi * std::sqrt(m / k);
    const double period = measurePeriod(*world, [&] { return spring->position(); }, 10.0);
    report("distance spring period (exact " + std::to_string(exact) + ")", period, "s");
    EXPECT_NEAR(period, exact, 0.005 * exact);
}

// ---- wheel ----------------------------------------------------------------------------------------

// A wheel on a vertical suspension (frame X = +Y) with a spring, no gravity: the suspension
// oscillates at sqrt(k/m) / 2 pi (Box2D's own soft spring: (omega h)^2 / 3 = 0.2 %, bound 0.5 %),
// and the motor spins the wheel up to its target at its torque limit, with positive motor speed
// a positive spin about the axle (+Z or -Z).
TEST(Box2dJoints, WheelSuspensionFrequencyAndSpin) {
    for (double axleZ : {1.0, -1.0}) {
        auto world = jointWorld(Effect::Joints);
        const double m = 2.0, k = 50.0, I = 0.2, tau = 1.0, target = 5.0;
        auto wheel = body(*world, Vec3::Zero(), m, I);
        // X = +Y (suspension), Y = axle along +Z or -Z.
        Mat3 r;
        r.col(0) = Vec3::UnitY();
        r.col(1) = axleZ * Vec3::UnitZ();
        r.col(2) = r.col(0).cross(r.col(1));
        JointPeerDef d = heldToWorld(JointType::Wheel, *wheel, Vec3::Zero(), Vec3::Zero(), Quat(r));
        d.spring = JointSpringSI{k, 0.0};
        d.motor = JointMotor{target, tau};
        auto joint = world->createJoint(d);
        wheel->setLinearVelocity(Vec3(0, 0.4, 0));
        run(*world, 0.5);
        // Spin-up: tau t / I = 2.5 rad/s after 0.5 s, about the axle; float sums 1e-5.
        EXPECT_NEAR(joint->speed(), tau * 0.5 / I, 1e-5 * target);
        EXPECT_NEAR(wheel->state().angularVelocity.z(), axleZ * tau * 0.5 / I, 1e-5 * target);
        const double exact = 2.0 * kPi * std::sqrt(m / k);
        const double period = measurePeriod(*world, [&] { return joint->position(); }, 10.0);
        report("wheel suspension period (exact " + std::to_string(exact) + ")", period, "s");
        EXPECT_NEAR(period, exact, 0.005 * exact);
        EXPECT_NEAR(joint->speed(), target, 1e-5 * target);
        EXPECT_NEAR(joint->position(), wheel->state().position.y(), 1e-6);
        EXPECT_NEAR(wheel->state().position.x(), 0.0, 1e-5);  // held on the suspension line
    }
}

// Suspension travel limits hold under gravity: a wheel hanging on a soft spring drops onto its
// lower stop (X = +Y, limits [-0.05, 0.05]; the spring alone would sag m g / k = 0.39 m).
TEST(Box2dJoints, WheelSuspensionLimitsHold) {
    auto world = jointWorld();
    auto wheel = body(*world, Vec3::Zero(), 2.0, 0.2);
    Mat3 r;
    r.col(0) = Vec3::UnitY();
    r.col(1) = Vec3::UnitZ();
    r.col(2) = Vec3::UnitX();
    JointPeerDef d = heldToWorld(JointType::Wheel, *wheel, Vec3::Zero(), Vec3::Zero(), Quat(r));
    d.spring = JointSpringSI{50.0, 2.0};
    d.limits = JointLimits{-0.05, 0.05};
    auto joint = world->createJoint(d);
    double low = 0.0;
    for (int i = 0; i < 180; ++i) {
        world->step(i * kDt, kDt);
        low = std::min(low, joint->position());
    }
    report("wheel suspension limit overshoot", -0.05 - low, "m");
    EXPECT_GE(low, -0.05 - 5e-3);  // b2_linearSlop
    EXPECT_NEAR(joint->position(), -0.05, 5e-3);
    // At rest on the stop the joint carries the weight: m g up (spring plus stop).
    EXPECT_NEAR(joint->reactionForce().y(), 2.0 * kG, 1e-3 * 2.0 * kG);
}

// Changes take effect from the next step: a hanging distance rod given a spring sags to m g / k
// beyond its length, and without it is a rod again; a wheel's suspension sags m g / k for each
// stiffness it is given, and its spin coasts once the motor is removed. Settled with damping
// ratio 0.7 (e^{-zeta omega t} < 1e-6): sag within 1e-4 m (float positions), rod within
// b2_linearSlop (5 mm).
TEST(Box2dJoints, SpringAndMotorChangesTakeEffect) {
    {
        auto world = jointWorld();
        const double m = 1.0, k = 200.0, c = 2.0 * 0.7 * std::sqrt(k * m);
        auto bob = body(*world, Vec3(0, -1, 0), m);
        JointPeerDef d;
        d.type = JointType::Distance;
        d.bodyB = bob.get();
        d.length = 1.0;
        auto rod = world->createJoint(d);
        run(*world, 1.0);
        EXPECT_NEAR(rod->position(), 0.0, 5e-3);
        rod->setSpring(JointSpringSI{k, c});
        run(*world, 3.0);
        EXPECT_NEAR(rod->position(), m * kG / k, 1e-4);
        EXPECT_NEAR(rod->reactionForce().y(), m * kG, 1e-3 * m * kG);
        rod->setSpring(std::nullopt);
        run(*world, 1.0);
        EXPECT_NEAR(rod->position(), 0.0, 5e-3);
    }
    {
        auto world = jointWorld();
        const double m = 2.0;
        auto wheel = body(*world, Vec3::Zero(), m, 0.2);
        Mat3 r;
        r.col(0) = Vec3::UnitY();
        r.col(1) = Vec3::UnitZ();
        r.col(2) = Vec3::UnitX();
        JointPeerDef d = heldToWorld(JointType::Wheel, *wheel, Vec3::Zero(), Vec3::Zero(), Quat(r));
        d.motor = JointMotor{3.0, 10.0};
        auto joint = world->createJoint(d);
        for (double k : {400.0, 100.0}) {
            joint->setSpring(JointSpringSI{k, 2.0 * 0.7 * std::sqrt(k * m)});
            run(*world, 3.0);
            EXPECT_NEAR(joint->position(), -m * kG / k, 1e-4) << "k = " << k;
        }
        EXPECT_NEAR(joint->speed(), 3.0, 1e-5);
        joint->setMotor(std::nullopt);
        wheel->setAngularVelocity(Vec3(0, 0, 5.0));
        run(*world, 1.0);
        EXPECT_NEAR(joint->speed(), 5.0, 1e-5);  // free spin: nothing drives or brakes it
    }
}

// ---- pairs, lifetime, effects, sleep --------------------------------------------------------

// Two overlapping boxes joined by a hinge: without collideConnected Box2D makes no contact between
// them; with it, they touch (and are reported).
TEST(Box2dJoints, CollideConnectedDecidesContactsBetweenThePair) {
    for (bool collide : {false, true}) {
        auto world = jointWorld(Effect::Joints | Effect::Contacts);
        world->setMaterialTable(MaterialTable{});
        const Vec3 half(0.5, 0.5, 0.5);
        auto a = body(*world, Vec3(0, 0, 0), 1.0, 0.2, half);
        auto b = body(*world, Vec3(0.6, 0, 0), 1.0, 0.2, half);
        JointPeerDef d;
        d.type = JointType::Hinge;
        d.bodyA = a.get();
        d.bodyB = b.get();
        d.frameA = {Vec3(0.3, 0, 0), kXUp};
        d.frameB = {Vec3(-0.3, 0, 0), kXUp};
        d.collideConnected = collide;
        auto hinge = world->createJoint(d);
        int pairs = 0;
        for (int i = 0; i < 10; ++i) {
            world->step(i * kDt, kDt);
            ContactReport report;
            world->reportContacts(report);
            pairs += static_cast<int>(report.pairs.size());
        }
        if (collide)
            EXPECT_GT(pairs, 0);
        else
            EXPECT_EQ(pairs, 0);
    }
}

// Destroying a joint frees its body (it falls as if never held) and the world keeps stepping; a
// joint whose body is destroyed first (a peer dropped without the layer) is let go cleanly.
TEST(Box2dJoints, DestroyLeavesTheWorldStepping) {
    auto world = jointWorld();
    const Vec3 start(0, -1, 0);
    auto b = body(*world, start);
    auto joint = world->createJoint(heldToWorld(JointType::Hinge, *b, start, Vec3::Zero()));
    run(*world, 0.5);
    EXPECT_NEAR(b->state().position.y(), -1.0, 5e-3);  // held
    world->destroyJoint(*joint);
    joint.reset();
    run(*world, 0.5);
    EXPECT_LT(b->state().position.y(), -2.0);  // falls: 1.2 m in 0.5 s

    auto c = body(*world, start);
    auto other = world->createJoint(heldToWorld(JointType::Slider, *c, start, Vec3::Zero(), xAlong(0.5 * kPi)));
    c.reset();  // the body goes first: the joint is let go with it
    run(*world, 0.5);
    EXPECT_DOUBLE_EQ(other->position(), 0.0);
    EXPECT_TRUE(other->reactionForce().isZero());
    world->destroyJoint(*other);  // harmless on a joint already let go
    other.reset();
    auto kept = world->createJoint(heldToWorld(JointType::Fixed, *b, b->state().position, b->state().position));
    kept.reset();  // a peer dropped without destroyJoint drops its b2Joint
    run(*world, 0.1);
    EXPECT_TRUE(b->state().position.allFinite());
}

// Joints act only while the world simulates them (Effect::Joints): off, the body falls freely;
// on again, the joint pulls its anchor back together (Box2D's position correction, at most
// b2_maxLinearCorrection = 0.2 m a step) and holds it.
TEST(Box2dJoints, JointsFollowTheJointsEffect) {
    auto world = jointWorld(Effect::Gravity);
    const Vec3 start(0, -1, 0);
    auto b = body(*world, start);
    auto joint = world->createJoint(heldToWorld(JointType::Ball, *b, start, Vec3::Zero()));
    run(*world, 0.2);
    EXPECT_LT(b->state().position.y(), -1.1);  // not held: 0.2 m of fall
    world->setEffects(Effect::Gravity | Effect::Joints);
    run(*world, 1.0);
    EXPECT_NEAR(b->state().position.y(), -1.0, 5e-3);  // back on its anchor (b2_linearSlop)
    EXPECT_NEAR(joint->reactionForce().y(), kG, 1e-3 * kG);  // holding it, at rest again
}

// A joint wakes its bodies when created and when its motor changes; joined bodies sleep and wake
// together (one Box2D island).
TEST(Box2dJoints, JointsWakeTheirBodies) {
    auto world = jointWorld(Effect::Joints | Effect::Sleeping);
    BodyPeerDef def;
    def.def.allowSleep = true;
    def.mass = {1.0, Vec3::Constant(0.1)};
    auto a = world->createBody(def);
    def.def.position = Vec3(1, 0, 0);
    auto b = world->createBody(def);
    run(*world, 2.0);
    ASSERT_FALSE(a->isAwake());
    ASSERT_FALSE(b->isAwake());
    JointPeerDef d;
    d.type = JointType::Hinge;
    d.bodyA = a.get();
    d.bodyB = b.get();
    d.frameA = {Vec3(0.5, 0, 0), kXUp};
    d.frameB = {Vec3(-0.5, 0, 0), kXUp};
    auto hinge = world->createJoint(d);
    EXPECT_TRUE(a->isAwake());
    EXPECT_TRUE(b->isAwake());
    run(*world, 2.0);
    ASSERT_FALSE(a->isAwake());  // at rest: both asleep, together
    ASSERT_FALSE(b->isAwake());
    hinge->setMotor(JointMotor{1.0, 5.0});
    EXPECT_TRUE(a->isAwake());
    EXPECT_TRUE(b->isAwake());
    run(*world, 0.5);
    EXPECT_GT(hinge->speed(), 0.5);  // the motor turns B against A
}

}  // namespace
}  // namespace anyphys::box2d::test
