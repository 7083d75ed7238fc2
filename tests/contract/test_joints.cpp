// Joints on every backend that declares them: closed forms measured over the whole run, with
// sleeping off. A backend without a joint type or parameter skips the test by capability.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <sstream>

#include "anyphys/joint_capabilities.hpp"
#include "contract_fixture.hpp"
#include "contact_helpers.hpp"
#include "period_meter.hpp"

namespace anyphys::test {
namespace {

// Complete elliptic integral of the first kind, by the arithmetic-geometric mean.
double ellipticK(double k) {
    double a = 1.0, b = std::sqrt(1.0 - k * k);
    for (int i = 0; i < 30; ++i) {
        const double next = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = next;
    }
    return kPi / (2.0 * a);
}

class JointTest : public ContractTest {
protected:
    bool hasJoint(const char* type) const { return caps().jointTypes.contains(type); }
    /// A contract criterion id, "planar." + id in planar worlds (a backend may miss one and not
    /// the other).
    std::string criterion(const std::string& id) const { return planarTest() ? "planar." + id : id; }
    bool hasParameter(const std::string& name) const { return caps().parameters.contains(name); }

    WorldSettings jointSettings(bool gravity = true) const {
        WorldSettings s = settings();
        if (!gravity) s.gravity = Vec3::Zero();
        return s;
    }

    /// A forearm-like limb (1 kg, 0.3 m long and thin) hanging below the origin, its top end there.
    static Body createThinLimb(World& world) {
        BodyDef limb;
        limb.shape = ShapeDef::box(Vec3(0.04, 0.15, 0.04));
        limb.mass = 1.0;
        limb.position = Vec3(0, -0.15, 0);
        limb.allowSleep = false;
        return world.createBody(limb);
    }

    // Every "joint.*" parameter and joint type a backend declares is one the layer knows.
    void checkDeclaredNames() const {
        const auto known = allJointParameters();
        for (const std::string& p : caps().parameters) {
            if (p.starts_with("joint.")) {
                EXPECT_NE(std::find(known.begin(), known.end(), p), known.end()) << "unknown joint parameter " << p;
            }
        }
        for (const std::string& type : caps().jointTypes) {
            EXPECT_TRUE(fromString<JointType>(type).has_value()) << "unknown joint type " << type;
            EXPECT_TRUE(caps().effects.has(Effect::Joints)) << "joint types declared without the joints effect";
        }
    }

    // A ball of radius r, never sleeping, at `at`.
    Body ball(World& world, const Vec3& at, double mass, double radius, const std::string& name = "") {
        BodyDef d;
        d.name = name;
        d.shape = ShapeDef::sphere(radius);
        d.mass = mass;
        d.position = at;
        d.allowSleep = false;
        return world.createBody(d);
    }

    // A box of half extents `half`, never sleeping, at `at`.
    Body box(World& world, const Vec3& at, double mass, const Vec3& half) {
        BodyDef d;
        d.shape = ShapeDef::box(half);
        d.mass = mass;
        d.position = at;
        d.allowSleep = false;
        return world.createBody(d);
    }

    /// A hinge about Z through the origin, holding `body` to the world.
    static Joint hingeToWorldAboutZ(World& world, const Body& body) {
        JointDef d;
        d.type = JointType::Hinge;
        d.bodyB = body;
        d.anchor = Vec3::Zero();
        d.axis = Vec3::UnitZ();
        return world.createJoint(d);
    }

    // Period from the times x crosses 0 going down, interpolated within the step; also the
    // largest anchor gap seen (distance of the bob from its circle) and the energy range.
    struct Swing {
        double period = 0.0, maxGap = 0.0, energyDrift = 0.0;
        double maxOffAxisSpin = 0.0;  // rad/s, the bob's spin across `hingeAxis` (when given)
    };
    // Energy is measured against `energyScale` (the swing's own energy, m g L (1 - cos theta0)):
    // the total against the anchor's height can be near zero and would magnify any change.
    // `partner`: a second body whose energy counts too (a double pendulum's lower bob).
    Swing swing(World& world, Body& bob, double length, double duration, double energyScale, const Body* partner = nullptr,
                const Vec3& hingeAxis = Vec3::Zero()) {
        Swing out;
        const auto energyOf = [](const Body& body) {
            const BodyState s = body.state();
            const double m = body.massProperties().mass;
            const Vec3 I = body.massProperties().inertia;  // a sphere: isotropic
            return 0.5 * m * s.linearVelocity.squaredNorm() + 0.5 * I.x() * s.angularVelocity.squaredNorm() +
                   m * kG * s.position.y();
        };
        const auto energy = [&] { return energyOf(bob) + (partner ? energyOf(*partner) : 0.0); };
        const double e0 = energy();
        PeriodMeter meter;
        meter.add(world.time(), world.settings().timeStep, bob.position().x());
        while (world.time() < duration) {
            world.step();
            meter.add(world.time(), world.settings().timeStep, bob.position().x());
            out.maxGap = std::max(out.maxGap, std::abs(bob.position().norm() - length));
            out.energyDrift = std::max(out.energyDrift, std::abs(energy() - e0) / energyScale);
            const Vec3 w = bob.angularVelocity();
            out.maxOffAxisSpin = std::max(out.maxOffAxisSpin, (w - w.dot(hingeAxis) * hingeAxis).norm());
        }
        out.period = meter.period();
        return out;
    }

    // A pendulum of length 1 m (a 1 kg ball of radius 0.1 m) released from `amplitude` about
    // `axis` (horizontal; +Z unless given) on a hinge or a ball joint: period against
    // 4 sqrt(L'/g) K(sin(theta0/2)), L' = (I + m L^2) / (m L) for the physical pendulum; the gap
    // and energy over 20 periods.
    void pendulum(JointType type, const Vec3& axis = Vec3::UnitZ()) {
        for (double amplitude : {0.3, 1.5}) {
            World world(jointSettings());
            const double L = 1.0, r = 0.1;
            const Vec3 start = Eigen::AngleAxisd(amplitude, axis) * Vec3(0, -L, 0);
            Body bob = ball(world, start, 1.0, r);
            JointDef d;
            d.type = type;
            d.bodyB = bob;
            d.anchor = Vec3::Zero();
            d.axis = axis;
            Joint joint = world.createJoint(d);
            const double I = 0.4 * r * r;
            const double exact = 4.0 * std::sqrt((I + L * L) / L / kG) * ellipticK(std::sin(0.5 * amplitude));
            const bool hinge = type == JointType::Hinge;
            const Swing s = swing(world, bob, L, 20.0 * exact, kG * L * (1.0 - std::cos(amplitude)), nullptr,
                                  hinge ? axis : Vec3::Zero());
            std::cout << "[ MEASURED ] " << backend() << " " << toString(type) << " pendulum about (" << axis.transpose()
                      << "), amplitude " << amplitude << ": period " << s.period << " s (exact " << exact
                      << "), max gap " << s.maxGap * 1e3 << " mm, energy change " << 100.0 * s.energyDrift
                      << " % of the swing" << (hinge ? ", spin across the axis " + std::to_string(s.maxOffAxisSpin) + " rad/s" : "")
                      << "\n";
            // 2 cm: the anchor is held (soft constraints sag by millimetres under the swing's tension).
            EXPECT_LT(s.maxGap, 0.02) << "amplitude " << amplitude;
            // Period 1 %: a step of 1/60 s resolves a 2 s swing in 120 steps; first-order
            // integration and constraint softness move it by well under that (native: 0.05 %),
            // while a joint that stretched, slipped or drained the swing would not.
            // Energy 5 % of the swing over 20 periods: a symplectic step keeps it bounded (native:
            // 0.4 %); a joint solved on velocity only drains (ωh)^2 of it per step.
            // At 0.3 rad every engine must hold the period; energy, and both at 1.5 rad, a backend
            // may declare a known deviation (measured, with its cause), reported instead of failing.
            const bool periodOk = std::abs(s.period - exact) <= 0.01 * exact;
            const bool energyOk = s.energyDrift <= 0.05;
            const std::string where = std::string(toString(type)) + " at " + std::to_string(amplitude) + " rad: ";
            const std::string energyText = where + "energy change " + std::to_string(100.0 * s.energyDrift) + " % of the swing";
            if (amplitude < 1.0) {
                EXPECT_TRUE(periodOk) << where << "period " << s.period << " s, exact " << exact;
                expectCriterion(criterion("joints.pendulum_energy"), energyOk, energyText, std::abs(s.energyDrift));
            } else {
                expectCriterion(criterion("joints.wide_pendulum_period"), periodOk,
                                where + "period " + std::to_string(s.period) + " s, exact " + std::to_string(exact),
                                std::abs(s.period - exact) / exact);
                expectCriterion(criterion("joints.wide_pendulum_energy"), energyOk, energyText, std::abs(s.energyDrift));
            }
            // A hinge turns its body about its axis only. 1 % of the swing's fastest turn
            // (sqrt(2 g (1 - cos theta0) / L'): 0.94 rad/s at 0.3 rad, 4.3 at 1.5): measured 0 to
            // six digits on native and Bullet about either axis.
            if (hinge && axis != Vec3::UnitZ()) {
                const double fastest = std::sqrt(2 * kG * (1 - std::cos(amplitude)) * L / (I + L * L));
                expectCriterion(criterion("joints.hinge_axis_spin"), s.maxOffAxisSpin <= 0.01 * fastest,
                                where + "spin across the axis " + std::to_string(s.maxOffAxisSpin) + " rad/s, " +
                                    std::to_string(s.maxOffAxisSpin / fastest) + " of the swing's fastest " +
                                    std::to_string(fastest) + " rad/s",
                                s.maxOffAxisSpin / fastest);
            }
            EXPECT_TRUE(joint.isValid());
        }
    }

    // ---- cases run in 3D and in planar worlds (all in the XY plane, hinges about Z) ----

    void HangingBodyReactionIsItsWeightCase() {
        ANYPHYS_REQUIRE(hasJoint("ball"), "joint type ball");
        World world(jointSettings());
        const double m = 3.0;
        Body body = ball(world, Vec3(0, -1, 0), m, 0.1);
        JointDef d;
        d.type = JointType::Ball;
        d.bodyB = body;
        Joint joint = world.createJoint(d);
        for (int i = 0; i < 120; ++i) world.step();
        // Mean over the next second: 1 % (a soft joint still settling moves it by far less).
        Vec3 mean = Vec3::Zero();
        for (int i = 0; i < 60; ++i) {
            world.step();
            mean += joint.reactionForce() / 60.0;
        }
        std::cout << "[ MEASURED ] " << backend() << " hanging reaction " << mean.transpose() << " N (m g = " << m * kG << ")\n";
        EXPECT_NEAR(mean.y(), m * kG, 0.01 * m * kG);
        EXPECT_NEAR(mean.x(), 0.0, 0.01 * m * kG);
        EXPECT_NEAR(mean.z(), 0.0, 0.01 * m * kG);
    }

    void MotorReachesTargetSpeedAtTorqueLimitCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        ANYPHYS_REQUIRE(hasParameter("joint.hinge.motor"), "joint.hinge.motor");
        World world(jointSettings(false));
        const double m = 2.0, r = 0.5, I = 0.4 * m * r * r;  // 0.2 kg m^2
        const double tau = 1.0, target = 5.0;                 // t* = 1 s
        Body wheel = ball(world, Vec3::Zero(), m, r);
        JointDef d;
        d.type = JointType::Hinge;
        d.bodyB = wheel;
        d.motor = JointMotor{target, tau};
        Joint joint = world.createJoint(d);
        const double tStar = I * target / tau;
        double worstEarly = 0.0;
        while (world.time() < 2.0 * tStar) {
            world.step();
            const double t = world.time(), w = joint.speed();
            // Never faster than the torque allows (a motor that ignored maxForce would jump).
            if (t < tStar) worstEarly = std::max(worstEarly, w - tau * t / I);
        }
        std::cout << "[ MEASURED ] " << backend() << " motor: speed " << joint.speed() << " rad/s at 2 t* (target " << target
                  << "), most ahead of tau t / I: " << worstEarly << " rad/s\n";
        // 2 %: one step of torque (tau dt / I = 0.08 rad/s at 60 Hz) is the resolution of an engine
        // that applies the limit per step rather than per substep.
        EXPECT_LT(worstEarly, 0.02 * target);
        EXPECT_NEAR(joint.speed(), target, 0.01 * target);
        EXPECT_NEAR(wheel.angularVelocity().z(), target, 0.01 * target);  // positive speed: +axis
    }

    // A 2 kg box on a slider along X held by an undamped 40 N/m spring, started through its rest
    // position at 0.5 m/s (in a world without gravity): x = (v0 / omega) sin(omega t).
    static constexpr double kSpringK = 40.0, kSpringMass = 2.0, kSpringV0 = 0.5;
    // The caller first requires the slider joint and its spring.
    std::pair<Body, Joint> springOnSlider(World& world) const {
        BodyDef bd;
        bd.shape = ShapeDef::box(Vec3(0.1, 0.1, 0.1));
        bd.mass = kSpringMass;
        bd.allowSleep = false;
        bd.linearVelocity = Vec3(kSpringV0, 0, 0);
        Body body = world.createBody(bd);
        JointDef d;
        d.type = JointType::Slider;
        d.bodyB = body;
        d.axis = Vec3::UnitX();
        d.spring = JointSpring{kSpringK, 0.0};
        return {body, world.createJoint(d)};
    }

    void SliderSpringFrequencyCase() {
        ANYPHYS_REQUIRE(hasJoint("slider"), "joint type slider");
        ANYPHYS_REQUIRE(hasParameter("joint.slider.spring"), "joint.slider.spring");
        World world(jointSettings(false));
        const auto [body, joint] = springOnSlider(world);
        const double k = kSpringK, m = kSpringMass;
        PeriodMeter meter;
        double offAxis = 0.0;
        while (world.time() < 10.0) {
            world.step();
            meter.add(world.time(), world.settings().timeStep, joint.position());
            offAxis = std::max(offAxis, std::hypot(body.position().y(), body.position().z()));
        }
        const double exact = 2.0 * kPi * std::sqrt(m / k);
        const double period = meter.period();
        std::cout << "[ MEASURED ] " << backend() << " slider spring period " << period << " s (exact " << exact << ")\n";
        // 1 %: (omega dt)^2 = 3e-3 at 60 Hz bounds an implicit or explicit spring's period error.
        EXPECT_NEAR(period, exact, 0.01 * exact);
        EXPECT_LT(offAxis, 1e-3);  // the slider holds the body on its axis
    }

    // The slider spring above, undamped, for 10 s (seven periods): its swing, the largest |x| of
    // the last period, against the exact v0 / omega (nothing damps it). 2 % either way: an
    // energy-keeping step at 60 Hz ((omega h)^2 = 5.6e-3) swings within a tenth of a percent of
    // it; a spring whose stiffness is stepped implicitly (backward Euler) loses about
    // (omega h)^2 / 4 of its swing per step, three quarters over these 600 steps.
    void UndampedSpringKeepsItsSwingCase() {
        ANYPHYS_REQUIRE(hasJoint("slider"), "joint type slider");
        ANYPHYS_REQUIRE(hasParameter("joint.slider.spring"), "joint.slider.spring");
        World world(jointSettings(false));
        const auto [body, joint] = springOnSlider(world);
        const double k = kSpringK, m = kSpringMass, v0 = kSpringV0;
        expectSwingKept(world, joint, v0 / std::sqrt(k / m), 2.0 * kPi * std::sqrt(m / k), "slider spring", "m",
                        "joints.spring_swing");
    }

    // Steps an undamped spring's world to 10 s; its swing, the largest |position| of the last
    // period, must be within 2 % of `exact` (criterion `id`).
    void expectSwingKept(World& world, const Joint& joint, double exact, double period, const std::string& what,
                         const std::string& unit, const std::string& id) const {
        double last = 0.0;
        while (world.time() < 10.0) {
            world.step();
            if (world.time() > 10.0 - period) last = std::max(last, std::abs(joint.position()));
        }
        const double change = std::abs(last / exact - 1.0);
        std::cout << "[ MEASURED ] " << backend() << " undamped " << what << ": swing " << last << " " << unit
                  << " after 10 s (exact " << exact << "): " << 100.0 * change << " % off\n";
        expectCriterion(criterion(id), change <= 0.02,
                        "the swing is " + std::to_string(last) + " " + unit + " after 10 s, exact " + std::to_string(exact),
                        change);
    }

    // A 2 kg box (20 cm cube) on a 1 m arm, turning about a hinge at the origin (axis Z, no
    // gravity) held by an undamped 40 N m/rad spring, started as a rigid turn at 0.5 rad/s: the
    // angle swings by w0 / omega, omega = sqrt(k / (I + m r^2)). The arm makes the box 150 times
    // heavier to turn about the hinge than about its centre: a backend that judges the spring by
    // the box's own inertia ((omega h)^2 = 0.83 at 60 Hz) takes it for a stiff one and steps it
    // implicitly, losing about three quarters of the swing in 10 s; with the pin acting it is
    // soft ((omega h)^2 = 5.5e-3). 2 % as for the slider.
    void HingeSpringOnAnArmKeepsItsSwingCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        ANYPHYS_REQUIRE(hasParameter("joint.hinge.spring"), "joint.hinge.spring");
        World world(jointSettings(false));
        const double m = 2.0, half = 0.1, r = 1.0, k = 40.0, w0 = 0.5;
        BodyDef bd;
        bd.shape = ShapeDef::box(Vec3(half, half, half));
        bd.mass = m;
        bd.allowSleep = false;
        bd.position = Vec3(r, 0, 0);
        bd.linearVelocity = Vec3(0, w0 * r, 0);
        bd.angularVelocity = Vec3(0, 0, w0);
        Body box = world.createBody(bd);
        JointDef d;
        d.type = JointType::Hinge;
        d.bodyB = box;
        d.axis = Vec3::UnitZ();
        d.spring = JointSpring{k, 0.0};
        Joint joint = world.createJoint(d);
        const double inertia = m * (2.0 * half) * (2.0 * half) / 6.0 + m * r * r;  // about the hinge
        const double omega = std::sqrt(k / inertia);
        expectSwingKept(world, joint, w0 / omega, 2.0 * kPi / omega, "hinge spring on a 1 m arm", "rad",
                        "joints.hinge_spring_swing");
    }

    // Twelve distance springs of 500 N/m hold a 0.1 kg ball between anchors on both sides of it,
    // along X (no gravity), and it starts at 1 m/s. Each spring alone is soft for a 1/60 s step
    // ((omega h)^2 = 1.4); together they are 12 times stiffer, beyond an explicit step's reach
    // ((omega h)^2 = 16.7 > 4). Energy bounds the swing by v0 / omega = 4.1 mm; a step that gains
    // energy grows it without bound within a second (Bullet's springs, each judged alone, reached
    // 4.5e5 m/s in 0.1 s). 1.5 times that bound: an energy-keeping explicit step swings 1 /
    // sqrt(1 - (omega h)^2 / 4) as wide, 1.04 in native's substeps.
    void ManySpringsOnOneLightBodyCase() {
        ANYPHYS_REQUIRE(hasJoint("distance"), "joint type distance");
        ANYPHYS_REQUIRE(hasParameter("joint.distance.spring"), "joint.distance.spring");
        World world(jointSettings(false));
        const double m = 0.1, k = 500.0, v0 = 1.0;
        const int springs = 12;
        BodyDef bd;
        bd.shape = ShapeDef::sphere(0.02);
        bd.mass = m;
        bd.allowSleep = false;
        bd.linearVelocity = Vec3(v0, 0, 0);
        Body ball = world.createBody(bd);
        for (int i = 0; i < springs; ++i) {
            JointDef d;
            d.type = JointType::Distance;
            d.bodyB = ball;
            d.anchorA = Vec3((i % 2 ? 1.0 : -1.0) * (1.0 + 0.01 * i), 0, 0);  // left and right, each its own length
            d.anchorB = Vec3::Zero();
            d.spring = JointSpring{k, 0.0};
            world.createJoint(d);
        }
        double widest = 0.0;
        while (world.time() < 10.0) {
            world.step();  // throws if the ball diverged
            widest = std::max(widest, std::abs(ball.position().x()));
        }
        const double allowed = v0 / std::sqrt(springs * k / m);
        std::cout << "[ MEASURED ] " << backend() << " ball on " << springs << " springs: widest swing " << widest * 1e3
                  << " mm (energy allows " << allowed * 1e3 << ")\n";
        EXPECT_LE(widest, 1.5 * allowed);
        EXPECT_TRUE(std::isfinite(ball.position().x()));
    }

    void HingeLimitStopsThePendulumCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        ANYPHYS_REQUIRE(hasParameter("joint.hinge.limits"), "joint.hinge.limits");
        World world(jointSettings());
        Body bob = ball(world, Vec3(1, 0, 0), 1.0, 0.1);
        JointDef d;
        d.type = JointType::Hinge;
        d.bodyB = bob;
        d.limits = JointLimits{-0.5, 0.5};
        Joint joint = world.createJoint(d);
        double lowest = 0.0;
        for (int i = 0; i < 240; ++i) {
            world.step();
            lowest = std::min(lowest, joint.position());
        }
        std::cout << "[ MEASURED ] " << backend() << " hinge limit -0.5: deepest " << lowest << " rad, rests at "
                  << joint.position() << " rad\n";
        // 0.05 rad: the bob arrives at 3 rad/s, one step of 1/60 s is 0.05 rad of travel.
        // A point-like bob on a 1 m arm (m L^2 / I = 250) is the hard case for a limit solved apart
        // from the anchor: a backend that lets it through declares it.
        const bool held = lowest > -0.55 && std::abs(joint.position() + 0.5) < 0.02 && std::abs(joint.speed()) < 0.05;
        expectCriterion(criterion("joints.hinge_limit"), held,
                        "deepest " + std::to_string(lowest) + " rad, rests at " + std::to_string(joint.position()) +
                            " rad, speed " + std::to_string(joint.speed()) + " rad/s",
                        // in multiples of its bounds: overshoot 0.05 rad, rest 0.02 rad, speed 0.05 rad/s
                        std::max({(-0.5 - lowest) / 0.05, std::abs(joint.position() + 0.5) / 0.02,
                                  std::abs(joint.speed()) / 0.05}));
    }

    void DistanceRodAndRopeCase() {
        ANYPHYS_REQUIRE(hasJoint("distance"), "joint type distance");
        {
            World world(jointSettings());
            Body bob = ball(world, Vec3(1, 0, 0), 1.0, 0.1);
            JointDef d;
            d.type = JointType::Distance;
            d.bodyB = bob;
            d.anchorA = Vec3::Zero();
            d.anchorB = Vec3(1, 0, 0);
            Joint rod = world.createJoint(d);
            double worst = 0.0;
            for (int i = 0; i < 300; ++i) {
                world.step();
                worst = std::max(worst, std::abs(bob.position().norm() - 1.0));
            }
            std::cout << "[ MEASURED ] " << backend() << " distance rod: worst length error " << worst * 1e3 << " mm\n";
            // 1 cm: the swing's tension sags a soft rod by millimetres.
        expectCriterion(criterion("joints.distance_rod"), worst < 0.01, "worst length error " + std::to_string(worst) + " m",
                        worst);
            EXPECT_NEAR(rod.position(), bob.position().norm() - 1.0, 1e-6);
        }
        ANYPHYS_REQUIRE(hasParameter("joint.distance.maxLength"), "joint.distance.maxLength");
        {
            // Thrown upward from 1 m below the anchor, the rope goes slack: free flight, no pull.
            World world(jointSettings());
            Body bob = ball(world, Vec3(0, -1, 0), 1.0, 0.1);
            bob.setLinearVelocity(Vec3(0, 2, 0));
            JointDef d;
            d.type = JointType::Distance;
            d.bodyB = bob;
            d.anchorA = Vec3::Zero();
            d.anchorB = Vec3(0, -1, 0);
            d.minLength = 0.0;
            d.maxLength = 1.0;
            world.createJoint(d);
            for (int i = 0; i < 12; ++i) world.step();
            const double t = world.time();
            // Free flight: y = -1 + 2 t - g t^2 / 2. Semi-implicit Euler in steps of h falls g h t / 2
            // further (1.6 cm at one 60 Hz substep after 0.2 s); 2 mm beyond that.
            const double h = world.settings().timeStep / *world.settings().substeps;
            EXPECT_NEAR(bob.position().y(), -1.0 + 2.0 * t - 0.5 * kG * t * t, 0.5 * kG * h * t + 0.002);
            for (int i = 0; i < 120; ++i) world.step();
            EXPECT_LT(bob.position().norm(), 1.0 + 0.01);  // and the rope catches it
        }
    }

    void DoublePendulumNormalModesCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        for (double sign : {1.0, -1.0}) {
            World world(jointSettings());
            const double L = 1.0, theta1 = 0.05, theta2 = sign * std::sqrt(2.0) * theta1;
            const Vec3 p1(L * std::sin(theta1), -L * std::cos(theta1), 0.0);
            const Vec3 p2 = p1 + Vec3(L * std::sin(theta2), -L * std::cos(theta2), 0.0);
            Body upper = ball(world, p1, 1.0, 0.02);
            Body lower = ball(world, p2, 1.0, 0.02);
            JointDef d;
            d.type = JointType::Hinge;
            d.bodyB = upper;
            world.createJoint(d);
            d.bodyA = upper;
            d.bodyB = lower;
            d.anchor = p1;
            world.createJoint(d);
            const double w = std::sqrt(kG / L * (2.0 - sign * std::sqrt(2.0)));
            const double exact = 2.0 * kPi / w;
            // The swing's energy: m g L (1 - cos) of each bob's height above its lowest point.
            const double swingEnergy = kG * (2.0 * L * (1.0 - std::cos(theta1)) + L * (1.0 - std::cos(theta2)));
            Swing s = swing(world, upper, L, 20.0, swingEnergy, &lower);
            std::cout << "[ MEASURED ] " << backend() << " double pendulum mode " << (sign > 0 ? "slow" : "fast")
                      << ": period " << s.period << " s (exact " << exact << "), energy change over 20 s "
                      << 100.0 * s.energyDrift << " % of the swing\n";
            // Energy 5 % of the swing over 20 s, as for the single pendulum.
            expectCriterion(criterion(sign > 0 ? "joints.double_pendulum_energy_slow" : "joints.double_pendulum_energy_fast"),
                            s.energyDrift <= 0.05,
                            std::string(sign > 0 ? "slow" : "fast") + " mode: energy change " +
                                std::to_string(100.0 * s.energyDrift) + " % of the swing",
                            std::abs(s.energyDrift));
            // 1 %: the modes' small-amplitude form is exact to theta^2 / 16 ~ 2e-4 here; a joint that
            // stretched or coupled the modes wrongly would shift the period by more.
            expectCriterion(criterion(sign > 0 ? "joints.double_pendulum_slow" : "joints.double_pendulum_fast"),
                        std::abs(s.period - exact) <= 0.01 * exact,
                        "period " + std::to_string(s.period) + " s, exact " + std::to_string(exact),
                        std::abs(s.period - exact) / exact);
        }
    }

    void MotorHoldsALoadItCanCarryCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        ANYPHYS_REQUIRE(hasParameter("joint.hinge.motor"), "joint.hinge.motor");
        for (double torque : {10.0, 2.0}) {
            World world(jointSettings());
            BodyDef bar;
            bar.shape = ShapeDef::box(Vec3(0.5, 0.05, 0.05));
            bar.mass = 1.0;
            bar.position = Vec3(0.5, 0, 0);
            bar.allowSleep = false;
            Body arm = world.createBody(bar);
            JointDef d;
            d.type = JointType::Hinge;
            d.bodyB = arm;
            d.motor = JointMotor{0.0, torque};
            Joint joint = world.createJoint(d);
            double lowest = 0.0;
            for (int i = 0; i < 120; ++i) {
                world.step();
                lowest = std::min(lowest, joint.position());
            }
            std::cout << "[ MEASURED ] " << backend() << " motor " << torque << " N m holding 4.9 N m: lowest angle "
                      << lowest << " rad\n";
            if (torque > 4.905)
                EXPECT_GT(lowest, -0.01);  // a motor at speed 0 yields nothing but a step's sag
            else
                EXPECT_LT(lowest, -0.5);  // (4.9 - 2) N m net on I = 1/3 kg m^2: past half a radian in 2 s
        }
    }

    void SliderOnInclineStopsAtItsLimitCase() {
        ANYPHYS_REQUIRE(hasJoint("slider"), "joint type slider");
        ANYPHYS_REQUIRE(hasParameter("joint.slider.limits"), "joint.slider.limits");
        World world(jointSettings());
        BodyDef bd;
        bd.shape = ShapeDef::box(Vec3(0.1, 0.1, 0.1));
        bd.mass = 1.0;
        bd.allowSleep = false;
        Body body = world.createBody(bd);
        JointDef d;
        d.type = JointType::Slider;
        d.bodyB = body;
        d.axis = Vec3(std::cos(kPi / 6.0), -std::sin(kPi / 6.0), 0.0);  // downhill
        d.limits = JointLimits{-1.0, 1.0};
        Joint joint = world.createJoint(d);
        const double a = kG * 0.5, tStar = std::sqrt(2.0 / a), vStar = std::sqrt(2.0 * a);
        double tStop = -1.0, vBefore = 0.0, deepest = 0.0;
        while (world.time() < 1.5) {
            const double v = joint.speed();
            world.step();
            if (tStop < 0.0 && joint.position() >= 0.999) {
                tStop = world.time();
                vBefore = v;
            }
            deepest = std::max(deepest, joint.position());
        }
        std::cout << "[ MEASURED ] " << backend() << " slider on incline: stop at " << tStop << " s (exact " << tStar
                  << "), speed before " << vBefore << " m/s (exact " << vStar << "), past the limit "
                  << (deepest - 1.0) * 1e3 << " mm\n";
        const double dt = world.settings().timeStep;
        EXPECT_NEAR(tStop, tStar, dt);              // within the step it happens in
        EXPECT_NEAR(vBefore, vStar, 0.1 * vStar);   // sampled up to a step before: a dt of 4.9 m/s^2 (3 %)
        EXPECT_LT(deepest - 1.0, 0.01);             // 1 cm past the stop at most
        EXPECT_NEAR(joint.position(), 1.0, 0.005);  // and it rests on it
        EXPECT_NEAR(joint.speed(), 0.0, 0.02);
    }

    void WheelSuspensionAndDriveCase() {
        ANYPHYS_REQUIRE(hasJoint("wheel"), "joint type wheel");
        ANYPHYS_REQUIRE(hasParameter("joint.wheel.spring"), "joint.wheel.spring");
        ANYPHYS_REQUIRE(hasParameter("joint.wheel.motor"), "joint.wheel.motor");
        World world(jointSettings());
        const double m = 2.0, k = 200.0, r = 0.3;
        Body wheel = ball(world, Vec3::Zero(), m, r);
        JointDef d;
        d.type = JointType::Wheel;
        d.bodyB = wheel;
        d.axis = Vec3::UnitY();      // suspension
        d.spinAxis = Vec3::UnitZ();  // axle
        d.spring = JointSpring{k, 0.0};
        d.motor = JointMotor{10.0, 5.0};
        Joint joint = world.createJoint(d);
        // Released at the unloaded length: it oscillates about -m g / k with amplitude m g / k.
        const double sag = m * kG / k, omega = std::sqrt(k / m);
        double lowest = 0.0, highest = -1.0, previous = 0.0, first = -1.0, last = -1.0;
        int crossings = 0;
        const double dt = world.settings().timeStep;
        while (world.time() < 3.0) {
            world.step();
            const double y = joint.position() + sag;  // about the rest position
            lowest = std::min(lowest, joint.position());
            highest = std::max(highest, joint.position());
            if (previous > 0.0 && y <= 0.0) {
                const double t = world.time() - dt * y / (y - previous);
                if (first < 0) first = t;
                last = t;
                ++crossings;
            }
            previous = y;
        }
        const double period = crossings > 1 ? (last - first) / (crossings - 1) : 0.0;
        std::cout << "[ MEASURED ] " << backend() << " wheel: travel [" << lowest << ", " << highest << "] m (exact [" << -2 * sag
                  << ", 0]), period " << period << " s (exact " << 2 * kPi / omega << "), spin " << joint.speed()
                  << " rad/s (target 10)\n";
        // 5 % of the 0.196 m swing and of the period: an undamped spring through a joint at 60 Hz
        // ((omega dt)^2 = 0.028) keeps both to about 1 %.
        expectCriterion(criterion("joints.wheel_travel"), std::abs(lowest + 2.0 * sag) <= 0.05 * 2.0 * sag,
                        "lowest " + std::to_string(lowest) + " m, exact " + std::to_string(-2.0 * sag),
                        std::abs(lowest + 2.0 * sag) / (2.0 * sag));
        EXPECT_NEAR(period, 2.0 * kPi / omega, 0.05 * 2.0 * kPi / omega);
        // The drive: I = 0.4 m r^2 = 0.072 kg m^2 reaches 10 rad/s in 0.14 s at 5 N m.
        EXPECT_NEAR(joint.speed(), 10.0, 0.1);
        EXPECT_NEAR(wheel.angularVelocity().z(), 10.0, 0.1);  // about +axle
    }

    // Springs far stiffer than the step resolves (omega h from 5 to 500 at 60 Hz) hold a 1 kg load
    // at rest where the spring carries its weight: a ball on a slider along Y at -m g / k; a 1 m
    // rod on a hinge about Z at one end, horizontal, at -m g (L / 2) / k. Undamped and critically
    // damped: an explicit spring (the force of the step's start) diverges beyond omega h = 2.
    // `pointMass`: the hinge carries a ball on a massless 1 m arm instead (its inertia about the
    // hinge 1 000 times its own), where an iterative solver must carry the spring's torque
    // through the hinge's pin: checked as the criterion joints.stiff_hinge_lever.
    void StiffSpringsHoldTheirLoadCase(bool pointMass) {
        constexpr double m = 1.0, L = 1.0;
        struct Run {
            JointType type;
            double k, zeta;
        };
        std::vector<Run> runs;
        if (!pointMass) runs = {{JointType::Slider, 1e5, 0.0}, {JointType::Slider, 1e5, 1.0}, {JointType::Slider, 1e9, 1.0}};
        for (double zeta : {0.0, 1.0}) runs.push_back({JointType::Hinge, 1e5, zeta});
        int ran = 0;
        double worst = 0.0;  // the hinge runs' error in multiples of the bound
        std::string worstText;
        for (const Run& run : runs) {
            const bool slider = run.type == JointType::Slider;
            const char* name = slider ? "slider" : "hinge";
            if (!hasJoint(name) || !hasParameter(std::string("joint.") + name + ".spring")) continue;
            SCOPED_TRACE(std::string(name) + " k " + std::to_string(run.k) + " zeta " + std::to_string(run.zeta));
            World world(jointSettings());
            BodyDef def;
            def.mass = m;
            def.allowSleep = false;
            def.shape = slider || pointMass ? ShapeDef::sphere(0.05) : ShapeDef::box(Vec3(L / 2, 0.05, 0.05));
            def.position = slider ? Vec3::Zero() : pointMass ? Vec3(L, 0, 0) : Vec3(L / 2, 0, 0);
            const Body b = world.createBody(def);
            JointDef d;
            d.type = run.type;
            d.bodyB = b;
            d.axis = slider ? Vec3::UnitY() : Vec3::UnitZ();
            // About the joint: the ball's own inertia (1e-3 kg m^2) is left out of the lever's.
            const double inertia = slider ? m : pointMass ? m * L * L : m * (L * L + 0.01) / 12 + m * L * L / 4;
            d.spring = JointSpring{run.k, 2.0 * run.zeta * std::sqrt(run.k * inertia)};
            Joint joint = world.createJoint(d);
            double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;  // over the last second
            while (world.time() < 2.0) {
                world.step();  // throws if a body diverged
                if (world.time() <= 1.0) continue;
                lowest = std::min(lowest, joint.position());
                highest = std::max(highest, joint.position());
            }
            ++ran;
            const double expected = -m * kG * (slider ? 1.0 : pointMass ? L : L / 2) / run.k;
            const double centre = 0.5 * (lowest + highest), swing = 0.5 * (highest - lowest);
            report(backend() + " " + name + (pointMass ? " (point mass on 1 m)" : "") + " spring k " +
                       std::to_string(run.k) + " zeta " + std::to_string(run.zeta) + ": rest position (exact " +
                       std::to_string(expected) + "), centre of the last second's swing",
                   centre, slider ? "m" : "rad");
            report(backend() + " " + name + (pointMass ? " (point mass on 1 m)" : "") + " spring k " +
                       std::to_string(run.k) + " zeta " + std::to_string(run.zeta) + ": half swing (at most " +
                       std::to_string(std::abs(expected)) + ")",
                   swing, slider ? "m" : "rad");
            // The spring balances the weight about the rest position: 2 % of the deflection, or 1e-7
            // (the joint's own error correction at the anchor) where the deflection is smaller.
            // Damped, it is still there (1e-3 rad/s or m/s: well under one deflection per step).
            // Undamped, released at its unloaded length, it may swing about the rest position by
            // the deflection (energy): a solver whose stiffness is implicit damps the swing away,
            // one that resolves the spring (native's substeps, for the slider) keeps it. 10 %
            // wider at most: symplectic Euler, which keeps energy, swings 1 / sqrt(1 - (omega
            // h)^2 / 4) as wide (6 % in native's substeps, omega h = 0.66); a step that gained
            // energy would widen it swing after swing.
            const double bound = std::max(0.02 * std::abs(expected), 1e-7);
            if (!pointMass) {
                EXPECT_NEAR(centre, expected, bound);
                if (run.zeta > 0.0) {
                    EXPECT_NEAR(joint.speed(), 0.0, 1e-3);
                } else {
                    EXPECT_LE(swing, 1.1 * std::abs(expected) + bound);
                }
                continue;
            }
            // The lever's figure is a declared criterion on some backends, in this measure: the
            // same bounds in multiples (1 passes). Undamped, the lever may swing as the rod may:
            // native resolves it in its substeps with the pin acting ((omega h)^2 = 0.43) and keeps
            // the swing, 1.06 times the deflection.
            const double error =
                run.zeta > 0.0 ? std::max(std::abs(joint.position() - expected) / bound, std::abs(joint.speed()) / 1e-3)
                               : std::max(std::abs(centre - expected) / bound, swing / (1.1 * std::abs(expected) + bound));
            if (error > worst) {
                worst = error;
                worstText = "zeta " + std::to_string(run.zeta) + ": at " + std::to_string(joint.position()) + " rad (exact " +
                            std::to_string(expected) + "), speed " + std::to_string(joint.speed()) +
                            " rad/s, the last second's swing " + std::to_string(swing) + " rad about " + std::to_string(centre);
            }
        }
        ANYPHYS_REQUIRE(ran > 0, "joint.slider.spring or joint.hinge.spring");
        if (pointMass) expectCriterion(criterion("joints.stiff_hinge_lever"), worst <= 1.0, worstText, worst);
    }

    // A motor with ample torque (1 000 N m; the arm's weight asks at most m g L = 9.8 N m) turns a
    // 1 kg ball of radius 5 cm on a massless 1 m arm about Z, in a vertical plane under gravity.
    // Its inertia about the hinge is 1 000 times its own, so the motor's torque must go through
    // the hinge's pin. A motor is a velocity constraint: the arm turns at its speed throughout,
    // angle = speed x t. Checked as the criterion joints.motor_lever.
    void MotorTurnsAPointMassOnALeverCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        ANYPHYS_REQUIRE(hasParameter("joint.hinge.motor"), "joint.hinge.motor");
        constexpr double speed = 1.0;
        World world(jointSettings());
        Body bob = ball(world, Vec3(1, 0, 0), 1.0, 0.05);
        JointDef d;
        d.type = JointType::Hinge;
        d.bodyB = bob;
        d.axis = Vec3::UnitZ();
        d.motor = JointMotor{speed, 1000.0};
        Joint joint = world.createJoint(d);
        double worstSpeed = 0.0;  // |speed error| after the first 0.1 s (a spin-up of one step)
        while (world.time() < 2.0) {
            world.step();  // throws if a body diverged
            if (world.time() > 0.1) worstSpeed = std::max(worstSpeed, std::abs(joint.speed() - speed));
        }
        const double angleError = std::abs(joint.position() - speed * world.time());
        std::cout << "[ MEASURED ] " << backend() << " motor on a 1 m lever: angle " << joint.position() << " rad after "
                  << world.time() << " s (exact " << speed * world.time() << "), worst speed error " << worstSpeed
                  << " rad/s\n";
        // 1 % of the speed and 0.01 rad of the angle: a step's spin-up (at most 1 ms at 1 000 N m)
        // and the joints' own error correction are far smaller. The measure is the larger error
        // in multiples of its bound.
        const double measure = std::max(worstSpeed / 0.01, angleError / 0.01);
        expectCriterion(criterion("joints.motor_lever"), measure <= 1.0,
                        "angle " + std::to_string(joint.position()) + " rad after 2 s (exact 2), worst speed error " +
                            std::to_string(worstSpeed) + " rad/s",
                        measure);
    }

    void BreaksAboveItsForceOnlyCase() {
        ANYPHYS_REQUIRE(hasJoint("ball"), "joint type ball");
        ANYPHYS_REQUIRE(hasParameter("joint.ball.breakForce"), "joint.ball.breakForce");
        struct Recorder : ContactListener {
            std::vector<JointEvent> broken;
            void onJointBreak(const JointEvent& e) override { broken.push_back(e); }
        } recorder;
        World world(jointSettings());
        world.addListener(&recorder);
        Body strongBody = ball(world, Vec3(-1, -1, 0), 2.0, 0.1);
        Body weakBody = ball(world, Vec3(1, -1, 0), 2.0, 0.1);
        JointDef d;
        d.type = JointType::Ball;
        d.name = "strong";
        d.bodyB = strongBody;
        d.anchor = Vec3(-1, 0, 0);
        d.breakForce = 25.0;
        Joint strong = world.createJoint(d);
        d.name = "weak";
        d.bodyB = weakBody;
        d.anchor = Vec3(1, 0, 0);
        d.breakForce = 15.0;
        Joint weak = world.createJoint(d);
        for (int i = 0; i < 120; ++i) world.step();
        EXPECT_FALSE(strong.isBroken());
        EXPECT_TRUE(weak.isBroken());
        ASSERT_EQ(recorder.broken.size(), 1u);
        EXPECT_EQ(recorder.broken[0].name, "weak");
        EXPECT_GT(recorder.broken[0].force.norm(), 15.0);
        EXPECT_EQ(weak.reactionForce(), Vec3::Zero());
        // The strong joint holds its body; the weak one's falls freely.
        EXPECT_NEAR(strongBody.position().y(), -1.0, 0.01);
        EXPECT_LT(weakBody.position().y(), -5.0);
        world.removeListener(&recorder);
    }

    // A body set far from its joint (a game teleporting one limb of a ragdoll) comes back to it
    // without being flung: a 1 kg ball (radius 0.1 m) hung 1 m below the origin on a hinge about
    // Z is set 3 m to the side after half a second at rest. Put back on its circle along the line
    // to the anchor and let go, it would swing through the bottom at sqrt(2 g (L + y)) = 3.66 m/s.
    // Met: at most half as fast again (a pull that takes time lets gravity add some), and back on
    // its circle within 1 cm after 2 s. The measure is the worse of the two against its bound.
    void SetFarFromItsJointCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        World world(jointSettings());
        constexpr double kLength = 1.0;
        Body bob = ball(world, Vec3(0, -kLength, 0), 1.0, 0.1);
        hingeToWorldAboutZ(world, bob);
        for (int i = 0; i < 30; ++i) world.step();
        const Vec3 set(3.0, -kLength, 0.0);
        bob.setTransform(set, Quat::Identity());
        double fastest = 0.0;
        for (int i = 0; i < 120; ++i) {
            world.step();
            fastest = std::max(fastest, bob.linearVelocity().norm());
        }
        const double swing = std::sqrt(2.0 * kG * kLength * (1.0 + set.normalized().y()));
        const double off = std::abs(bob.position().norm() - kLength);
        const double measure = std::max(fastest / (1.5 * swing), off / 0.01);
        std::ostringstream measured;
        measured << "bob set 3 m off: fastest " << fastest << " m/s (put back and let go: " << swing << "), off its circle "
                 << off * 1e3 << " mm after 2 s";
        std::cout << "[ MEASURED ] " << backend() << " " << measured.str() << "\n";
        expectCriterion(criterion("joints.set_far"), measure < 1.0, measured.str(), measure);
    }

    /// A chain of 40 balls (0.1 kg, radius 3 cm) spaced 10 cm along `direction` from the origin,
    /// each held by a ball joint at the previous ball's centre (the first at the origin); the last
    /// ball weighs `endMass`.
    std::vector<Body> ballChain(World& world, const Vec3& direction, double endMass) {
        constexpr int kLinks = 40;
        std::vector<Body> bodies;
        Body previous;
        for (int i = 0; i < kLinks; ++i) {
            Body link = ball(world, kChainSpacing * (i + 1) * direction, i + 1 == kLinks ? endMass : 0.1, 0.03);
            JointDef d;
            d.type = JointType::Ball;
            d.bodyA = previous;
            d.bodyB = link;
            d.anchor = kChainSpacing * i * direction;
            world.createJoint(d);
            bodies.push_back(link);
            previous = link;
        }
        return bodies;
    }
    static constexpr double kChainSpacing = 0.1;

    void HangingChainHoldsTogetherCase() {
        ANYPHYS_REQUIRE(hasJoint("ball"), "joint type ball");
        for (Solver solver : caps().solvers)
        for (double endRatio : {10.0, 100.0}) {
            WorldSettings s = jointSettings();
            s.solver = solver;
            World world(s);
            const double spacing = kChainSpacing;
            const std::vector<Body> bodies = ballChain(world, Vec3::UnitX(), 0.1 * endRatio);  // horizontal: it swings
            double worst = 0.0;
            for (int i = 0; i < 300; ++i) {
                world.step();
                Vec3 last = Vec3::Zero();
                for (const Body& b : bodies) {
                    worst = std::max(worst, std::abs((b.position() - last).norm() - spacing));
                    last = b.position();
                }
            }
            std::cout << "[ MEASURED ] " << backend() << " " << toString(solver) << " chain of 40, end " << endRatio
                      << "x: worst gap " << worst * 1e3 << " mm\n";
            // Stretched but not torn: a link's length (10 cm) at the default solver, 10x end; the
            // figure is printed per solver and ratio, since iterative solvers (one substep of PGS)
            // and a 100x end stretch further; for those, two links' length. At the default solver
            // a backend that tears declares it (criteria joints.chain_gap, joints.chain_gap_heavy).
            const std::string measured = std::string(toString(solver)) + ", end " + std::to_string(endRatio) +
                                         "x: worst gap " + std::to_string(worst) + " m";
            const bool defaultSolver = solver == caps().defaultSolver;
            const std::string id = std::string(endRatio > 10.0 ? "joints.chain_gap_heavy" : "joints.chain_gap") +
                                   (defaultSolver ? "" : "." + std::string(toString(solver)));
            expectCriterion(criterion(id), worst < (defaultSolver && endRatio <= 10.0 ? 0.1 : 0.2), measured, worst);
        }
    }

    // The chain above hanging straight down at rest, its end 100 times a link (10 kg on 0.1 kg
    // links): nothing moves it, so it stays together and its energy (kinetic and m g y) never
    // rises. Native's PGS once kept Baumgarte's pull in the impulses that warm start the next
    // substep, and this chain rang up until it flew apart within half a second. Measured worst
    // gaps: native 8.8 mm (soft step), 11.9 mm (pgs); ODE 27.9 mm (pgs), 0 (direct); Bullet 15.6 mm
    // (pgs), 0 (direct); Box2D 82 mm. Bound a link's length (10 cm), as the swinging chain's; the
    // energy may rise 0.4 J (its sag only lowers it: rounding and a stretched joint's rebound).
    void HangingChainStaysAtRestCase() {
        ANYPHYS_REQUIRE(hasJoint("ball"), "joint type ball");
        for (Solver solver : caps().solvers) {
            WorldSettings s = jointSettings();
            s.solver = solver;
            World world(s);
            const double spacing = kChainSpacing;
            const std::vector<Body> bodies = ballChain(world, -Vec3::UnitY(), 10.0);
            const auto energy = [&] {
                double e = 0.0;
                for (const Body& body : bodies) {
                    const BodyState b = body.state();
                    const MassProperties mass = body.massProperties();  // a ball: one principal moment
                    e += mass.mass * (-s.gravity.dot(b.position) + 0.5 * b.linearVelocity.squaredNorm()) +
                         0.5 * mass.inertia.x() * b.angularVelocity.squaredNorm();
                }
                return e;
            };
            const double initial = energy();
            double worst = 0.0, gain = 0.0;
            for (int i = 0; i < 300 && worst < 100.0; ++i) {
                world.step();
                Vec3 last = Vec3::Zero();
                for (const Body& b : bodies) {
                    worst = std::max(worst, std::abs((b.position() - last).norm() - spacing));
                    last = b.position();
                }
                gain = std::max(gain, energy() - initial);
            }
            std::cout << "[ MEASURED ] " << backend() << " " << toString(solver) << " chain of 40 hanging at rest, end 100x: worst gap "
                      << worst * 1e3 << " mm, energy gain " << gain << " J\n";
            const std::string measured = std::string(toString(solver)) + ": worst gap " + std::to_string(worst) +
                                         " m, energy gain " + std::to_string(gain) + " J";
            const bool defaultSolver = solver == caps().defaultSolver;
            expectCriterion(criterion(std::string("joints.hanging_chain_rest") + (defaultSolver ? "" : "." + std::string(toString(solver)))),
                            worst < 0.1 && gain < 0.4, measured, worst);
        }
    }

    void CollideConnectedDecidesContactsCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        for (bool collide : {false, true}) {
            if (collide && !hasParameter("joint.hinge.collideConnected")) continue;
            World world(jointSettings(false));
            BodyDef bd;
            bd.shape = ShapeDef::box(Vec3(0.5, 0.5, 0.5));
            bd.allowSleep = false;
            bd.type = BodyType::Static;
            Body base = world.createBody(bd);
            bd.type = BodyType::Dynamic;
            bd.position = Vec3(0.8, 0, 0);
            Body arm = world.createBody(bd);
            JointDef d;
            d.type = JointType::Hinge;
            d.bodyA = base;
            d.bodyB = arm;
            d.anchor = Vec3(0.4, 0, 0);
            d.collideConnected = collide;
            world.createJoint(d);
            bool touched = false;
            for (int i = 0; i < 10; ++i) {
                world.step();
                for (const ContactEvent& e : world.lastEvents()) touched = touched || e.phase == ContactPhase::Enter;
            }
            EXPECT_EQ(touched, collide) << "collideConnected " << collide;
        }
    }

    /// A ball on a hinge whose axle sits in a static block, orbiting it at 4 m/s (6.7 cm a step,
    /// more than the ball's radius). With the block around the axle each turn passes through
    /// it; the joint excludes the pair (collideConnected false), so neither contacts nor
    /// continuous collision may stop the ball there. Without (`blockInPath` false) the block
    /// lies 10 m away and the orbit is the joint's alone. Returns the turns made in 2 s and the
    /// speed at the end.
    std::pair<double, double> orbitAroundJointedBlock(bool blockInPath) {
        World world(jointSettings(false));
        BodyDef blockDef;
        blockDef.type = BodyType::Static;
        blockDef.shape = ShapeDef::box(Vec3(0.2, 0.2, 0.2));
        if (!blockInPath) blockDef.position = Vec3(0, 10, 0);
        Body block = world.createBody(blockDef);
        const Vec3 axle(0.15, 0, 0);  // in the path: inside the block, 5 cm from its +x face
        constexpr double kRadius = 0.3, kSpeed = 4.0;
        BodyDef ballDef;
        ballDef.shape = ShapeDef::sphere(0.05);
        ballDef.position = axle + Vec3(kRadius, 0, 0);
        ballDef.linearVelocity = Vec3(0, kSpeed, 0);
        ballDef.angularVelocity = Vec3(0, 0, kSpeed / kRadius);  // the hinge turns it with the orbit
        ballDef.allowSleep = false;
        Body ball = world.createBody(ballDef);
        JointDef hinge;
        hinge.type = JointType::Hinge;
        hinge.bodyA = block;
        hinge.bodyB = ball;
        hinge.anchor = axle;
        world.createJoint(hinge);
        double turned = 0.0, angle = 0.0;
        while (world.time() < 2.0) {
            world.step();
            const Vec3 r = ball.position() - axle;
            const double now = std::atan2(r.y(), r.x());
            turned += std::remainder(now - angle, 2 * kPi);  // less than half a turn per step
            angle = now;
        }
        return {turned / (2 * kPi), ball.linearVelocity().norm()};
    }

    void ContinuousCollisionIgnoresJointedPartnersCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        const std::string missing = lacking(caps(), {ShapeType::Sphere, ShapeType::Box},
                                            Effect::Contacts | Effect::ContinuousCollision | Effect::Joints);
        ANYPHYS_REQUIRE(missing.empty(), missing);
        const auto [turns, speed] = orbitAroundJointedBlock(true);
        const auto [freeTurns, freeSpeed] = orbitAroundJointedBlock(false);
        report(backend() + " orbit through a jointed block: turns in 2 s (a lossless joint: 4.24)", turns);
        report(backend() + " the same orbit with the block away: turns in 2 s", freeTurns);
        // The block in the path changes nothing: the runs differ only in the static body's pose, so
        // by rounding. (How much speed the joint itself bleeds is the joint solver's; a block that
        // stopped the ball once a turn cost 2 %.)
        EXPECT_NEAR(turns, freeTurns, 1e-3);
        EXPECT_NEAR(speed, freeSpeed, 1e-3 * freeSpeed);
        EXPECT_GT(freeTurns, 2.0);  // it orbits at all
    }

    void MotorFasterThanTheWorldIsRefusedCase() {
        // A motor drives body B at its speed, so one faster than the world's ceiling makes a
        // diverged body (ODE aborted inside its step on a slider motor of 1e20 m/s: the body left
        // the collision grid within one substep). Refused at creation and by setMotor, naming the
        // field; the world and the joint keep what they had. At the ceiling itself it is accepted.
        int types = 0;
        for (const JointType type : {JointType::Slider, JointType::Hinge}) {
            const std::string name(toString(type));
            if (!hasJoint(name.c_str()) || !hasParameter(("joint." + name + ".motor").c_str())) continue;
            ++types;
            SCOPED_TRACE(name);
            WorldSettings settings = jointSettings(false);
            settings.maxSpeed = 50.0;         // m/s: a slider's motor speed
            settings.maxAngularSpeed = 40.0;  // rad/s: a hinge's
            const double ceiling = type == JointType::Slider ? settings.maxSpeed : settings.maxAngularSpeed;
            World world(settings);
            JointDef d;
            d.type = type;
            d.bodyB = ball(world, Vec3::Zero(), 1.0, 0.1);
            d.axis = type == JointType::Slider ? Vec3(1, 0, 0) : Vec3(0, 0, 1);  // in the plane / about Z
            d.motor = JointMotor{1.5 * ceiling, 10.0};
            try {
                world.createJoint(d);
                ADD_FAILURE() << "a motor at 1.5x the world's ceiling was accepted";
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("JointDef.motor.speed"), std::string::npos) << e.what();
            }
            EXPECT_EQ(world.jointCount(), 0u);
            d.motor = JointMotor{-ceiling, 10.0};
            Joint joint = world.createJoint(d);
            try {
                joint.setMotor(JointMotor{2.0 * ceiling, 10.0});
                ADD_FAILURE() << "setMotor at 2x the world's ceiling was accepted";
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("Joint.setMotor.speed"), std::string::npos) << e.what();
            }
            ASSERT_TRUE(joint.def().motor.has_value());
            EXPECT_EQ(joint.def().motor->speed, -ceiling) << "the refused motor replaced the old one";
            for (int i = 0; i < 30; ++i) world.step();
            // 10 N (or N m) on a 1 kg ball of 0.1 m for 0.5 s: it speeds up towards -ceiling.
            EXPECT_LT(joint.speed(), 0.0);
        }
        if (types == 0) GTEST_SKIP() << "no slider or hinge motor on this backend";
    }

    void HandlesAndValidationCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        World world(jointSettings());
        Body a = ball(world, Vec3(0, -1, 0), 1.0, 0.1, "a");
        Body b = ball(world, Vec3(0, -2, 0), 1.0, 0.1, "b");
        JointDef d;
        d.type = JointType::Hinge;
        d.bodyB = a;
        d.limits = JointLimits{1.2, 0.4};
        try {
            world.createJoint(d);
            ADD_FAILURE() << "limits lower > upper accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("limits"), std::string::npos) << e.what();
        }
        d.limits.reset();
        d.bodyA = a;  // the same body twice
        EXPECT_THROW(world.createJoint(d), Error);
        d.bodyA = Body();
        Joint top = world.createJoint(d);
        d.bodyA = a;
        d.bodyB = b;
        d.anchor = Vec3(0, -1, 0);
        Joint lower = world.createJoint(d);
        EXPECT_EQ(world.jointCount(), 2u);
        world.destroyJoint(top);
        EXPECT_FALSE(top.isValid());
        EXPECT_THROW(top.position(), Error);
        world.destroyBody(b);  // takes `lower` with it
        EXPECT_FALSE(lower.isValid());
        EXPECT_EQ(world.jointCount(), 0u);
        for (int i = 0; i < 10; ++i) world.step();
        EXPECT_LT(a.position().y(), -1.0);  // free now: falls
    }
    // `error` (m, more is worse) at 1 kg, then at 1e5 and 1e7 kg: the worst heavy figure in
    // multiples of massScalingBound of the 1 kg one. Appends "1 kg E m, 100000 kg E m, ..." to
    // `measured`.
    template <class Error>
    static double heavyTimesTheBound(const Error& error, std::ostream& measured) {
        const double light = error(1.0);
        measured << "1 kg " << light << " m";
        double times = 0.0;
        for (const double mass : {1e5, 1e7}) {
            const double heavy = error(mass);
            measured << ", " << mass << " kg " << heavy << " m";
            times = std::max(times, heavy / massScalingBound(light));
        }
        return times;
    }

    // Every mass scaled by one factor changes no motion under gravity and joints alone (each
    // reaction scales with the masses): a hinge pendulum of 1 m released at 1 rad keeps its bob
    // of 1e5 kg or 1e7 kg on its circle as it keeps one of 1 kg. A joint softness fixed in
    // absolute terms, not relative to the masses it holds, stretches in proportion to the load.
    void HeavyPendulumSwingsAsALightOneCase() {
        ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
        const double L = 1.0, amplitude = 1.0;
        const auto worstGap = [&](double mass) {
            World world(jointSettings());
            Body bob = ball(world, Vec3(L * std::sin(amplitude), -L * std::cos(amplitude), 0.0), mass, 0.1);
            hingeToWorldAboutZ(world, bob);
            return swing(world, bob, L, 5.0, kG * L * (1.0 - std::cos(amplitude))).maxGap;
        };
        std::ostringstream measured;
        measured << "worst gap with a ";
        const double times = heavyTimesTheBound(worstGap, measured);
        std::cout << "[ MEASURED ] " << backend() << " hinge pendulum over 5 s: " << measured.str() << "\n";
        expectCriterion(criterion("joints.heavy_pendulum"), times <= 1.0,
                        measured.str() + " (" + std::to_string(times) + " x the bound)", times);
    }

    // How far a joint of `type` holding a 10 cm ball of `mass` kg under gravity lets it off the
    // path the joint allows, worst over 3 s (m): a pendulum (ball, distance rod) off its 1 m
    // circle; a ball welded 1 m out (fixed) off its place; a ball sliding along X at 1 m/s
    // (slider) off the axis; a bob on a 1 m arm dropped onto a hinge limit, past it (arc length).
    double heavyJointError(JointType type, double mass) {
        World world(jointSettings());
        const bool pendulum = type == JointType::Ball || type == JointType::Distance;
        const Vec3 start = pendulum ? Vec3(std::sin(1.0), -std::cos(1.0), 0.0)
                           : type == JointType::Slider ? Vec3::Zero()
                                                       : Vec3(1, 0, 0);
        Body bob = ball(world, start, mass, 0.1);
        JointDef d;
        d.type = type;
        d.bodyB = bob;
        if (type == JointType::Distance) d.anchorB = start;
        if (type == JointType::Slider) {
            d.axis = Vec3::UnitX();
            bob.setLinearVelocity(Vec3(1, 0, 0));
        }
        if (type == JointType::Hinge) d.limits = JointLimits{-0.5, 0.5};
        Joint joint = world.createJoint(d);
        double worst = 0.0;
        while (world.time() < 3.0) {
            world.step();
            const Vec3 p = bob.position();
            switch (type) {
                case JointType::Ball:
                case JointType::Distance: worst = std::max(worst, std::abs(p.norm() - 1.0)); break;
                case JointType::Fixed: worst = std::max(worst, (p - start).norm()); break;
                case JointType::Slider: worst = std::max(worst, std::hypot(p.y(), p.z())); break;
                default: worst = std::max(worst, -0.5 - joint.position()); break;  // hinge, 1 m arm
            }
        }
        return worst;
    }

    void HeavyBodiesHoldTheirJointsAsLightOnesCase() {
        const std::pair<JointType, const char*> cases[] = {{JointType::Fixed, "fixed"},
                                                           {JointType::Ball, "ball"},
                                                           {JointType::Distance, "distance"},
                                                           {JointType::Slider, "slider"},
                                                           {JointType::Hinge, "hinge"}};
        std::ostringstream measured;
        double times = 0.0;
        int tried = 0;
        for (const auto& [type, name] : cases) {
            if (!hasJoint(name) || (type == JointType::Hinge && !hasParameter("joint.hinge.limits"))) continue;
            ++tried;
            measured << (tried > 1 ? "; " : "") << name << (type == JointType::Hinge ? " at its limit" : "") << ": ";
            const auto error = [&, type = type](double mass) { return heavyJointError(type, mass); };
            times = std::max(times, heavyTimesTheBound(error, measured));
        }
        ANYPHYS_REQUIRE(tried > 0, "joint type fixed, ball, distance, slider or hinge with limits");
        std::cout << "[ MEASURED ] " << backend() << " heavy joints over 3 s: " << measured.str() << "\n";
        expectCriterion(criterion("joints.heavy_joints"), times <= 1.0,
                        measured.str() + " (" + std::to_string(times) + " x the bound)", times);
    }
};

TEST_P(JointTest, HingePendulumPeriodMatchesEllipticIntegral) {
    ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
    pendulum(JointType::Hinge);
}

// The same hinge about a horizontal axis between x and z: a joint's rows must not care which
// way its axis points in the world.
TEST_P(JointTest, HingePendulumAboutADiagonalAxisMatchesEllipticIntegral) {
    ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
    pendulum(JointType::Hinge, Vec3(1, 0, 1).normalized());
}

TEST_P(JointTest, BallPendulumPeriodMatchesEllipticIntegral) {
    ANYPHYS_REQUIRE(hasJoint("ball"), "joint type ball");
    pendulum(JointType::Ball);
}

// A body hanging still from a ball joint: the joint pulls it up with m g (N), whatever the
// engine's substeps and units.
TEST_P(JointTest, HangingBodyReactionIsItsWeight) { HangingBodyReactionIsItsWeightCase(); }

// A motor spins a flywheel (no gravity) at its maximum torque: w = tau t / I until the target,
// reached at t* = I w / tau, not before; then it holds the target speed.
TEST_P(JointTest, MotorReachesTargetSpeedAtTorqueLimit) { MotorReachesTargetSpeedAtTorqueLimitCase(); }

// A slider with a spring holds a mass (no gravity) that oscillates at sqrt(k/m) / 2 pi.
TEST_P(JointTest, SliderSpringFrequency) { SliderSpringFrequencyCase(); }
TEST_P(JointTest, UndampedSpringKeepsItsSwing) { UndampedSpringKeepsItsSwingCase(); }
TEST_P(JointTest, HingeSpringOnAnArmKeepsItsSwing) { HingeSpringOnAnArmKeepsItsSwingCase(); }
TEST_P(JointTest, ManySpringsOnOneLightBodyStayStable) { ManySpringsOnOneLightBodyCase(); }

// A hinge limit stops a pendulum released horizontally at -0.5 rad, and holds it there against
// gravity; the angle never passes the stop by more than a few hundredths of a radian.
TEST_P(JointTest, HingeLimitStopsThePendulum) { HingeLimitStopsThePendulumCase(); }

// A rigid distance joint keeps its length; a rope (maxLength only) lets the body come closer.
TEST_P(JointTest, DistanceRodAndRope) { DistanceRodAndRopeCase(); }

// A conical pendulum on a ball joint: a bob (near a point mass) on a 1 m arm at 30 deg from the
// vertical, circling at w^2 = g / (L cos a), keeps its cone angle and its period over 10 s.
TEST_P(JointTest, ConicalPendulumKeepsItsCone) {
    ANYPHYS_REQUIRE(hasJoint("ball"), "joint type ball");
    World world(jointSettings());
    const double L = 1.0, alpha = kPi / 6.0;
    const double w = std::sqrt(kG / (L * std::cos(alpha)));
    const Vec3 start(L * std::sin(alpha), -L * std::cos(alpha), 0.0);
    Body bob = ball(world, start, 1.0, 0.02);  // I / (m L^2) = 1.6e-4: a point mass to that order
    // The whole rigid pendulum turns about the vertical: the bob's spin matches its orbit.
    bob.setAngularVelocity(Vec3(0, w, 0));
    bob.setLinearVelocity(Vec3(0, w, 0).cross(start));
    JointDef d;
    d.type = JointType::Ball;
    d.bodyB = bob;
    world.createJoint(d);
    double worstAngle = 0.0;
    while (world.time() < 10.0) {
        world.step();
        const Vec3 p = bob.position();
        worstAngle = std::max(worstAngle, std::abs(std::atan2(std::hypot(p.x(), p.z()), -p.y()) - alpha));
    }
    // Where it is after 10 s: the orbit's phase against w t.
    const Vec3 p = bob.position();
    const double phase = std::atan2(-p.z(), p.x());  // turning +Y carries +X toward -Z
    const double expected = std::remainder(w * world.time(), 2.0 * kPi);
    const double phaseError = std::abs(std::remainder(phase - expected, 2.0 * kPi));
    std::cout << "[ MEASURED ] " << backend() << " conical pendulum: worst cone angle error " << worstAngle
              << " rad, phase error after 10 s " << phaseError << " rad\n";
    // 0.02 rad of cone angle (1 deg) and 0.1 rad of phase after 34 turns (0.05 %): a first-order
    // step keeps a circular orbit to that; a drifting or damping joint would open or close it.
    expectCriterion(criterion("joints.conical_pendulum"), worstAngle < 0.02 && phaseError < 0.1,
                    "cone angle error " + std::to_string(worstAngle) + " rad, phase error " + std::to_string(phaseError) + " rad",
                    std::max(worstAngle / 0.02, phaseError / 0.1));  // in multiples of the bound
}

// A disc spinning fast about its symmetry axis, held by a ball joint on that axis half a metre
// from its centre, with the axis level: a gyroscope. Nothing acts about the axis (the pivot's
// force and gravity pass through it), so Euler's equations keep the spin about it exactly, and
// nothing adds energy. Native's joint passes turned the disc through the step's first inertia
// while its anchor turned with it: as the axis tipped, the spin grew from 100 to 100.64 rad/s
// and the energy by 9 J in 10 s. Not checked here: the axis should stay level as it precesses,
// and on every backend it sinks, an error of first order in the step that splits the joint from
// the gyroscopic term (native 16 cm in 10 s at 60 Hz, 1.4 cm at 960 Hz; ODE and Bullet hang
// straight down within 10 s). Tried on native and not kept: joint passes that move the disc through
// the linearised implicit step's inverse inertia, (I + h G)^-1 with G the term's Jacobian, so that
// the joint's impulse turns as the spin turns it. With G whole the disc climbed and gained up to
// 990 J; with G / 2 it sank only 1.8 cm in 10 s at 100 rad/s and 60 Hz, but with one substep it
// climbed 35 cm (gaining 3.5 J), and at 1 000 rad/s 6 to 12 cm. A non-symmetric inverse inertia
// gives up the projection that keeps a joint pass from adding energy.
TEST_P(JointTest, GyroscopeOnAPivotKeepsItsSpin) {
    ANYPHYS_REQUIRE(hasJoint("ball"), "joint type ball");
    ANYPHYS_REQUIRE(caps().gyroscopicModes.count(GyroscopicMode::Implicit), "gyroscopic mode implicit");
    World world(jointSettings());
    Body disc = box(world, Vec3(0.5, 1.0, 0.0), 1.0, Vec3(0.05, 0.5, 0.5));  // moments 1/6 about X, 0.0842 across it
    disc.setAngularVelocity(Vec3(100.0, 0.0, 0.0));
    JointDef d;
    d.type = JointType::Ball;
    d.bodyB = disc;
    d.anchor = Vec3(0.0, 1.0, 0.0);
    world.createJoint(d);
    const auto spin = [&] { return disc.angularVelocityLocal().x(); };
    const auto energy = [&] {  // 1 kg: kinetic (turning and moving) and potential
        return 0.5 * disc.angularVelocity().dot(disc.angularMomentum()) + 0.5 * disc.linearVelocity().squaredNorm() +
               kG * disc.position().y();
    };
    const double E0 = energy();
    double worstSpin = 0.0, mostEnergy = 0.0;
    while (world.time() < 10.0) {
        world.step();
        worstSpin = std::max(worstSpin, std::abs(spin() - 100.0));
        mostEnergy = std::max(mostEnergy, energy() - E0);
    }
    std::cout << "[ MEASURED ] " << backend() << " gyroscope at 100 rad/s: worst spin error " << worstSpin
              << " rad/s, most energy gained " << mostEnergy << " J of " << E0 << " J, height after 10 s "
              << disc.position().y() << " m\n";
    // 1e-3 rad/s: the spin is exact in Euler's equations; ODE and Bullet keep it to 1e-4. 0.01 J
    // of 843: a first-order step may lose energy to its joint and its implicit gyroscopic term,
    // never gain it.
    EXPECT_LT(worstSpin, 1e-3);
    EXPECT_LT(mostEnergy, 0.01);
}

// A double pendulum (two 1 kg bobs, 1 m arms, hinges about Z) started in each small-amplitude
// normal mode, theta2 = +-sqrt(2) theta1: periods 2 pi / w with w^2 = (g / L)(2 -+ sqrt(2)).
TEST_P(JointTest, DoublePendulumNormalModes) { DoublePendulumNormalModesCase(); }

// A hinge motor at zero speed holds a horizontal arm (a 1 m, 1 kg bar pinned at one end: 4.9 N m
// of load) when its torque suffices (10 N m) and lets it fall when it does not (2 N m).
TEST_P(JointTest, MotorHoldsALoadItCanCarry) { MotorHoldsALoadItCanCarryCase(); }

// A slider down a frictionless 30 deg incline (gravity along the axis: g sin 30 = 4.905 m/s^2)
// reaches its 1 m limit at t* = sqrt(2 / 4.905) = 0.639 s at v = 3.13 m/s, and stops there.
TEST_P(JointTest, SliderOnInclineStopsAtItsLimit) { SliderOnInclineStopsAtItsLimitCase(); }

// A cone joint (swing limit 0.5 rad about -Y, the hanging direction) holds a bob that is swung
// hard sideways: the swing never passes the cone; twist limits hold a spin about the axis.
TEST_P(JointTest, ConeLimitsHoldSwingAndTwist) {
    ANYPHYS_REQUIRE(hasJoint("cone"), "joint type cone");
    ANYPHYS_REQUIRE(hasParameter("joint.cone.swingLimit"), "joint.cone.swingLimit");
    ANYPHYS_REQUIRE(hasParameter("joint.cone.twistLimits"), "joint.cone.twistLimits");
    World world(jointSettings());
    BodyDef limb;  // a 1 m limb hanging from the shoulder at the origin
    limb.shape = ShapeDef::box(Vec3(0.05, 0.5, 0.05));
    limb.mass = 2.0;
    limb.position = Vec3(0, -0.5, 0);
    limb.allowSleep = false;
    limb.linearVelocity = Vec3(4, 0, 2);   // thrown sideways: it would swing past 1 rad
    limb.angularVelocity = Vec3(0, 6, 0);  // and twisted about its length
    Body body = world.createBody(limb);
    JointDef d;
    d.type = JointType::Cone;
    d.bodyB = body;
    d.axis = Vec3(0, -1, 0);
    d.swingLimit = 0.5;
    d.twistLimits = JointLimits{-0.3, 0.3};
    Joint joint = world.createJoint(d);
    double worstSwing = 0.0, worstTwist = 0.0;
    for (int i = 0; i < 180; ++i) {
        world.step();
        worstSwing = std::max(worstSwing, joint.position());
        // Twist: B's X axis against A's about the limb's current direction.
        const Quat q = body.orientation();
        const Vec3 along = q * Vec3(0, -1, 0);
        const Quat swingOnly = Quat::FromTwoVectors(Vec3(0, -1, 0), along);
        const Quat twist = swingOnly.conjugate() * q;  // about -Y
        worstTwist = std::max(worstTwist, std::abs(2.0 * std::atan2(-twist.y(), twist.w())));
    }
    std::cout << "[ MEASURED ] " << backend() << " cone 0.5 rad / twist 0.3 rad: worst swing " << worstSwing
              << " rad, worst twist " << worstTwist << " rad\n";
    // 0.05 rad: the limb arrives at about 4 rad/s, a 60 Hz step travels 0.07 rad of it; a
    // speculative stop closes within the step, a reactive one within the next.
    EXPECT_LT(worstSwing, 0.55);
    EXPECT_LT(worstTwist, 0.35);
}

// A cone with twist limits and a free swing: a limb thrown over the top passes a half-turn
// swing, where the twist has no meaning; the joint must neither blow up nor let go.
TEST_P(JointTest, ConeTwistLimitsSurviveAHalfTurnSwing) {
    ANYPHYS_REQUIRE(hasJoint("cone"), "joint type cone");
    ANYPHYS_REQUIRE(hasParameter("joint.cone.twistLimits"), "joint.cone.twistLimits");
    World world(jointSettings());
    BodyDef limb;
    limb.shape = ShapeDef::box(Vec3(0.05, 0.5, 0.05));
    limb.mass = 2.0;
    limb.position = Vec3(0, -0.5, 0);
    limb.allowSleep = false;
    limb.linearVelocity = Vec3(8, 0, 0.5);  // over the top: 8 m/s at the centre, 1.6 m needed
    limb.angularVelocity = Vec3(0, 3, -16);
    Body body = world.createBody(limb);
    JointDef d;
    d.type = JointType::Cone;
    d.bodyB = body;
    d.axis = Vec3(0, -1, 0);
    d.twistLimits = JointLimits{-0.3, 0.3};
    Joint joint = world.createJoint(d);
    double widest = 0.0, worstGap = 0.0;
    bool finite = true;
    for (int i = 0; i < 240; ++i) {
        world.step();
        widest = std::max(widest, joint.position());
        const Vec3 anchor = body.position() + body.orientation() * Vec3(0, 0.5, 0);
        worstGap = std::max(worstGap, anchor.norm());
        finite = finite && std::isfinite(worstGap);
    }
    std::cout << "[ MEASURED ] " << backend() << " cone, twist limits only: widest swing " << widest
              << " rad, worst anchor gap " << worstGap * 1e3 << " mm\n";
    EXPECT_TRUE(finite);
    EXPECT_GT(widest, 2.8);      // it did swing over (near a half turn)
    EXPECT_LT(worstGap, 0.05);   // 5 cm: held through it (native 11 mm, Bullet 17, ODE 41)
}

// A hinge wrenched 120 degrees off its axis (a limb pinched in a pile is wrenched so) turns back
// to it: a hinge has one rest pose. Native's old lock rows held B's frame Y and Z perpendicular
// to the axis, which a hinge turned right over also satisfies: wrenched past a right angle it came
// to rest upside down; and at wide errors those rows had little lever left (the soak's pile blew
// up from a pinched elbow: PinchedPileFromTheSoakRunStaysWhole).
TEST_P(JointTest, BodySetFarFromItsJointComesBack) { SetFarFromItsJointCase(); }

TEST_P(JointTest, HingeWrenchedOffItsAxisTurnsBack) {
    ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
    World world(jointSettings(false));
    Body body = createThinLimb(world);
    hingeToWorldAboutZ(world, body);
    // Turned 120 degrees about X around the anchor: the anchor still coincides, the axis does not.
    const Quat wrench(Eigen::AngleAxisd(120.0 * kDegree, Vec3::UnitX()));
    body.setTransform(wrench * Vec3(0, -0.15, 0), wrench);
    double fastestSpin = 0.0, worstGap = 0.0;
    for (int i = 0; i < 120; ++i) {
        world.step();
        fastestSpin = std::max(fastestSpin, body.angularVelocity().norm());
        worstGap = std::max(worstGap, (body.position() + body.orientation() * Vec3(0, 0.15, 0)).norm());
    }
    const double offAxis = std::acos(std::clamp((body.orientation() * Vec3::UnitZ()).z(), -1.0, 1.0));
    std::cout << "[ MEASURED ] " << backend() << " hinge wrenched 120 deg off its axis: fastest spin " << fastestSpin
              << " rad/s, worst anchor gap " << worstGap * 1e3 << " mm, off axis after 2 s " << offAxis / kDegree << " deg\n";
    // Back on its axis (not turned over: 180 deg) within a degree after 2 s, and held at the
    // anchor on the way: within a third of the limb (10 cm; native 1.3 cm, Bullet 2.0, ODE 5.1:
    // its joints correct by ERP, so they open while the limb turns back).
    EXPECT_LT(offAxis, 1.0 * kDegree);
    EXPECT_LT(worstGap, 0.1);
    // Bounded spin: turning 2.1 rad back takes no more than the joint's stiffness times the error
    // (native: 2 x 60 Hz softness, damping ratio 2: 135 /s x 2.1 rad = 280 rad/s within a step,
    // none left at its end); the pile that blew up reached 5e4 rad/s.
    EXPECT_LT(fastestSpin, 300.0);
}

// A fixed joint and a slider wrenched far from their rest pose turn back to it: each has one rest
// orientation (the relative rotation at creation), whatever the axis and size of the wrench. Rows
// that hold only some components of the relative rotation can also rest at a half turn, or lose
// their lever on the way, as native's hinge did (HingeWrenchedOffItsAxisTurnsBack); native's
// fixed and slider rows hold 2 x the vector part of the relative rotation along world axes, and
// this checks they do not. Measured: every backend back within 1e-9 deg after 2 s.
TEST_P(JointTest, FixedAndSliderWrenchedFarTurnBack) {
    const struct {
        JointType type;
        const char* name;
    } joints[] = {{JointType::Fixed, "fixed"}, {JointType::Slider, "slider"}};
    const struct {
        Vec3 axis;
        double degrees;
    } wrenches[] = {{Vec3::UnitX(), 120.0}, {Vec3::UnitY(), 150.0}, {Vec3(1, 1, 1).normalized(), 170.0}};
    for (const auto& joint : joints) {
        if (!hasJoint(joint.name)) {
            std::cout << "[ SKIPPED ] " << backend() << " has no joint type " << joint.name << "\n";
            continue;
        }
        for (const auto& wrench : wrenches) {
            World world(jointSettings(false));
            Body body = createThinLimb(world);
            JointDef d;
            d.type = joint.type;
            d.bodyB = body;
            d.anchor = Vec3::Zero();
            d.axis = Vec3::UnitY();  // the slider's free direction: along the limb
            world.createJoint(d);
            const Quat turn(Eigen::AngleAxisd(wrench.degrees * kDegree, wrench.axis));
            body.setTransform(turn * Vec3(0, -0.15, 0), turn);
            double fastestSpin = 0.0;
            for (int i = 0; i < 120; ++i) {
                world.step();
                fastestSpin = std::max(fastestSpin, body.angularVelocity().norm());
            }
            const double left = Eigen::AngleAxisd(body.orientation()).angle();
            std::cout << "[ MEASURED ] " << backend() << " " << joint.name << " wrenched " << wrench.degrees
                      << " deg about (" << wrench.axis.transpose() << "): fastest spin " << fastestSpin
                      << " rad/s, rotation left after 2 s " << left / kDegree << " deg\n";
            // Back to its rest orientation within a degree after 2 s (a joint resting at a half
            // turn would leave 180 degrees).
            EXPECT_LT(left, 1.0 * kDegree) << joint.name << " wrenched " << wrench.degrees << " deg";
            // Bounded spin: 2.1 to 3 rad of error at a stiffness of about 135 /s is under 400
            // rad/s (measured: ODE 24, Bullet 51; native's relax passes leave no spin at the end
            // of the step); the soak's pile that blew up reached 5e4 rad/s.
            EXPECT_LT(fastestSpin, 400.0) << joint.name << " wrenched " << wrench.degrees << " deg";
        }
    }
}

// A wheel on its suspension (spring along Y) under a static frame: it sags by m g / k, bounces
// at sqrt(k / m), and its motor spins it up about the axle to the target speed.
TEST_P(JointTest, WheelSuspensionAndDrive) { WheelSuspensionAndDriveCase(); }

// Springs far stiffer than the step resolves hold a hanging load at m g / k, undamped or damped.
TEST_P(JointTest, StiffSpringsHoldTheirLoad) { StiffSpringsHoldTheirLoadCase(false); }
TEST_P(JointTest, StiffHingeSpringHoldsAPointMassOnALever) { StiffSpringsHoldTheirLoadCase(true); }
// A motor turns a point-like mass on a 1 m arm at its speed.
TEST_P(JointTest, MotorTurnsAPointMassOnALever) { MotorTurnsAPointMassOnALeverCase(); }

// A joint breaks at its stated force, not below: a 2 kg body (load 19.6 N) hangs from a joint
// rated 25 N, and from one rated 15 N that breaks, telling listeners and the handle.
TEST_P(JointTest, BreaksAboveItsForceOnly) { BreaksAboveItsForceOnlyCase(); }

// Two boxes welded by a fixed joint, tossed and spun without gravity, keep their relative pose
// and move as the same two boxes made one compound body.
TEST_P(JointTest, FixedJointHoldsTheRelativePose) {
    ANYPHYS_REQUIRE(hasJoint("fixed"), "joint type fixed");
    ANYPHYS_REQUIRE(caps().gyroscopicModes.contains(GyroscopicMode::Implicit), "gyroscopic mode implicit");
    // Two boxes (1 kg and 3 kg, 1 x 0.5 x 0.5 m, side by side along X) welded at x = 0, and the
    // same two boxes as one compound body: both start in the same rigid motion (centre of mass
    // at 1 m/s up, spinning at (0.5, 2, 1) rad/s), with no gravity, and must move alike.
    const Vec3 omega(0.5, 2.0, 1.0), v0(0, 1, 0), com(0.25, 0, 0);
    World welded(jointSettings(false));
    BodyDef bd;
    bd.shape = ShapeDef::box(Vec3(0.5, 0.25, 0.25));
    bd.allowSleep = false;
    bd.gyroscopic = GyroscopicMode::Implicit;
    const auto boxAt = [&](const Vec3& at, double mass) {
        bd.position = at;
        bd.mass = mass;
        bd.linearVelocity = v0 + omega.cross(at - com);
        bd.angularVelocity = omega;
        return welded.createBody(bd);
    };
    Body a = boxAt(Vec3(-0.5, 0, 0), 1.0);
    Body b = boxAt(Vec3(0.5, 0, 0), 3.0);
    JointDef d;
    d.type = JointType::Fixed;
    d.bodyA = a;
    d.bodyB = b;
    d.anchor = Vec3::Zero();
    welded.createJoint(d);

    World single(jointSettings(false));
    BodyDef cd;
    const double volume = 1.0 * 0.5 * 0.5;
    ShapeDef left = ShapeDef::box(Vec3(0.5, 0.25, 0.25)).placed(Vec3(-0.5, 0, 0), Quat::Identity());
    ShapeDef right = ShapeDef::box(Vec3(0.5, 0.25, 0.25)).placed(Vec3(0.5, 0, 0), Quat::Identity());
    left.density = 1.0 / volume;
    right.density = 3.0 / volume;
    cd.shape = ShapeDef::compound({left, right});
    cd.allowSleep = false;
    cd.gyroscopic = GyroscopicMode::Implicit;
    cd.linearVelocity = v0;
    cd.angularVelocity = omega;
    Body compound = single.createBody(cd);

    double worstGap = 0.0, worstTurn = 0.0;
    for (int i = 0; i < 120; ++i) {
        welded.step();
        single.step();
        const Vec3 rel = a.orientation().conjugate() * (b.position() - a.position());
        worstGap = std::max(worstGap, (rel - Vec3(1, 0, 0)).norm());
        worstTurn = std::max(worstTurn, a.orientation().angularDistance(b.orientation()));
    }
    const Vec3 weldedCom = 0.25 * a.position() + 0.75 * b.position();
    const double comError = (weldedCom - compound.centerOfMass()).norm();
    const double turnError = a.orientation().angularDistance(compound.orientation());
    std::cout << "[ MEASURED ] " << backend() << " fixed joint: worst offset " << worstGap * 1e3 << " mm, turn "
              << worstTurn << " rad; after 2 s against the compound: centre of mass " << comError * 1e3
              << " mm, orientation " << turnError << " rad\n";
    // 1 cm and 0.02 rad while spinning at 2.3 rad/s: a weld, not a hinge.
    EXPECT_LT(worstGap, 0.01);
    EXPECT_LT(worstTurn, 0.02);
    // Like one rigid body: the centre of mass within 1 cm (it moves in a straight line either
    // way) and the tumbling orientation within 0.05 rad after 2 s (4.6 rad turned; both runs use
    // the first-order implicit gyroscopic step, so they differ only by the weld's compliance).
    expectCriterion(criterion("joints.fixed_vs_compound"), comError < 0.01 && turnError < 0.05,
                    "centre of mass " + std::to_string(comError) + " m, orientation " + std::to_string(turnError) + " rad");
}

// A hanging chain of 40 links (0.1 kg, 10 cm apart) with an end mass 10x and 100x a link, held
// by ball joints, released horizontal: the largest gap between joined anchors over 5 s, per
// backend and solver. Long chains with heavy ends are where iterative solvers stretch.
TEST_P(JointTest, HangingChainHoldsTogether) { HangingChainHoldsTogetherCase(); }
TEST_P(JointTest, HangingChainStaysAtRest) { HangingChainStaysAtRestCase(); }
TEST_P(JointTest, HeavyPendulumSwingsAsALightOne) { HeavyPendulumSwingsAsALightOneCase(); }

// The same for the other joint types and a hinge's limit: a heavy body's joint holds it as well
// as a light one's (see massScalingBound), whatever the mass.
TEST_P(JointTest, HeavyBodiesHoldTheirJointsAsLightOnes) { HeavyBodiesHoldTheirJointsAsLightOnesCase(); }

// collideConnected false (the default): two jointed, overlapping boxes never touch; true: they do.
TEST_P(JointTest, CollideConnectedDecidesContacts) { CollideConnectedDecidesContactsCase(); }

// ... and continuous collision too: a fast body sweeping through its jointed partner is not
// stopped there. Before, an ODE sweep that ignored the joint froze a ragdoll's upper arm at its
// own chest for good (a 0.28 m gap in the ragdoll pile; this orbit made 0.37 turns of its 3.85),
// and native's stopped the ball at the block's face once a turn (4.13 turns of 4.22).
TEST_P(JointTest, ContinuousCollisionIgnoresJointedPartners) { ContinuousCollisionIgnoresJointedPartnersCase(); }

// The layer's rules, the same on every backend: stale handles, a body's joints die with it,
// bad defs are refused naming the field, and the world stays usable.
TEST_P(JointTest, HandlesAndValidation) { HandlesAndValidationCase(); }
TEST_P(JointTest, MotorFasterThanTheWorldIsRefused) { MotorFasterThanTheWorldIsRefusedCase(); }

// What a backend declares of joints is spelled as the layer names it, so the layer's checks
// (and `anyphys backends`) mean what they say.
TEST_P(JointTest, DeclaredJointCapabilitiesUseTheLayersNames) { checkDeclaredNames(); }

// A joint type or field the backend lacks: strict refuses naming the joint and what is missing,
// and changes nothing; lenient warns once and runs without it.
TEST_P(JointTest, StrictRefusesAndLenientWarnsForWhatIsMissing) {
    // The first type this backend lacks, else the first parameter of a type it has.
    std::optional<JointDef> lacking;
    std::string missing;
    JointDef probe;
    probe.anchor = Vec3::Zero();
    for (const auto& [type, name] : EnumNames<JointType>::values) {
        if (!caps().jointTypes.contains(std::string(name))) {
            probe.type = type;
            if (type == JointType::Distance) probe.anchorB = Vec3(0, -1, 0);
            lacking = probe;
            missing = "joint type " + std::string(name);
            break;
        }
    }
    if (!lacking && !hasParameter("joint.hinge.spring")) {
        probe.type = JointType::Hinge;
        probe.spring = JointSpring{10.0, 0.0};
        lacking = probe;
        missing = "joint.hinge.spring";
    }
    if (!lacking) GTEST_SKIP() << "backend " << backend() << " declares every joint type and the hinge spring";
    for (CapabilityPolicy policy : {CapabilityPolicy::Strict, CapabilityPolicy::Lenient}) {
        WorldSettings s = jointSettings();
        s.capabilityPolicy = policy;
        World world(s);
        std::vector<std::string> warnings;
        world.setWarningHandler([&warnings](const std::string& w) { warnings.push_back(w); });
        JointDef d = *lacking;
        d.name = "probe";
        d.bodyB = ball(world, Vec3(0, -1, 0), 1.0, 0.1);
        if (policy == CapabilityPolicy::Strict) {
            try {
                world.createJoint(d);
                ADD_FAILURE() << "strict policy accepted a missing " << missing;
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
                EXPECT_NE(std::string(e.what()).find("probe"), std::string::npos) << e.what();
            }
            EXPECT_EQ(world.jointCount(), 0u);
        } else {
            Joint joint = world.createJoint(d);
            EXPECT_TRUE(joint.isValid());
            ASSERT_EQ(warnings.size(), 1u);
            EXPECT_NE(warnings[0].find(missing), std::string::npos) << warnings[0];
        }
        world.step();  // the world stays usable either way
    }
}

ANYPHYS_CONTRACT_SUITE(JointTest);

// The planar versions: every case whose motion stays in the XY plane, in a planar world (Box2D's
// revolute, prismatic, distance, weld and wheel joints; a ball joint there is a hinge about Z).
class PlanarJointTest : public JointTest {
protected:
    bool planarTest() const override { return true; }
};

TEST_P(PlanarJointTest, HingePendulumPeriodMatchesEllipticIntegral) {
    ANYPHYS_REQUIRE(hasJoint("hinge"), "joint type hinge");
    pendulum(JointType::Hinge);
}
TEST_P(PlanarJointTest, DeclaredJointCapabilitiesUseTheLayersNames) { checkDeclaredNames(); }
TEST_P(PlanarJointTest, HangingBodyReactionIsItsWeight) { HangingBodyReactionIsItsWeightCase(); }
TEST_P(PlanarJointTest, MotorReachesTargetSpeedAtTorqueLimit) { MotorReachesTargetSpeedAtTorqueLimitCase(); }
TEST_P(PlanarJointTest, SliderSpringFrequency) { SliderSpringFrequencyCase(); }
TEST_P(PlanarJointTest, UndampedSpringKeepsItsSwing) { UndampedSpringKeepsItsSwingCase(); }
TEST_P(PlanarJointTest, HingeSpringOnAnArmKeepsItsSwing) { HingeSpringOnAnArmKeepsItsSwingCase(); }
TEST_P(PlanarJointTest, ManySpringsOnOneLightBodyStayStable) { ManySpringsOnOneLightBodyCase(); }
TEST_P(PlanarJointTest, HingeLimitStopsThePendulum) { HingeLimitStopsThePendulumCase(); }
TEST_P(PlanarJointTest, ContinuousCollisionIgnoresJointedPartners) { ContinuousCollisionIgnoresJointedPartnersCase(); }
TEST_P(PlanarJointTest, DistanceRodAndRope) { DistanceRodAndRopeCase(); }
TEST_P(PlanarJointTest, DoublePendulumNormalModes) { DoublePendulumNormalModesCase(); }
TEST_P(PlanarJointTest, MotorHoldsALoadItCanCarry) { MotorHoldsALoadItCanCarryCase(); }
TEST_P(PlanarJointTest, SliderOnInclineStopsAtItsLimit) { SliderOnInclineStopsAtItsLimitCase(); }
TEST_P(PlanarJointTest, WheelSuspensionAndDrive) { WheelSuspensionAndDriveCase(); }
TEST_P(PlanarJointTest, StiffSpringsHoldTheirLoad) { StiffSpringsHoldTheirLoadCase(false); }
TEST_P(PlanarJointTest, StiffHingeSpringHoldsAPointMassOnALever) { StiffSpringsHoldTheirLoadCase(true); }
TEST_P(PlanarJointTest, MotorTurnsAPointMassOnALever) { MotorTurnsAPointMassOnALeverCase(); }
TEST_P(PlanarJointTest, BreaksAboveItsForceOnly) { BreaksAboveItsForceOnlyCase(); }
TEST_P(PlanarJointTest, HeavyPendulumSwingsAsALightOne) { HeavyPendulumSwingsAsALightOneCase(); }
TEST_P(PlanarJointTest, HeavyBodiesHoldTheirJointsAsLightOnes) { HeavyBodiesHoldTheirJointsAsLightOnesCase(); }
TEST_P(PlanarJointTest, HangingChainHoldsTogether) { HangingChainHoldsTogetherCase(); }
TEST_P(PlanarJointTest, HangingChainStaysAtRest) { HangingChainStaysAtRestCase(); }
TEST_P(PlanarJointTest, CollideConnectedDecidesContacts) { CollideConnectedDecidesContactsCase(); }
TEST_P(PlanarJointTest, HandlesAndValidation) { HandlesAndValidationCase(); }
TEST_P(PlanarJointTest, BodySetFarFromItsJointComesBack) { SetFarFromItsJointCase(); }
TEST_P(PlanarJointTest, MotorFasterThanTheWorldIsRefused) { MotorFasterThanTheWorldIsRefusedCase(); }

ANYPHYS_CONTRACT_SUITE(PlanarJointTest);

}  // namespace
}  // namespace anyphys::test
