// The built-in scenes. Each is small, named, and where the exact motion is known in closed form
// it carries that solution, so tests, benchmarks and `anyphys compare` measure error against
// physics rather than against another engine.
#include "anyphys/containers/scene_catalogue.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <numbers>

#include "anyphys/error.hpp"
#include "catalogue_parts.hpp"

namespace anyphys {
namespace {

using namespace catalogue_parts;

/// Rotation by a constant world-frame angular velocity w for time t, applied to q0.
Quat rotateConstant(const Quat& q0, const Vec3& w, double t) {
    const double speed = w.norm();
    if (speed == 0.0) return q0;
    return (Quat(Eigen::AngleAxisd(speed * t, w / speed)) * q0).normalized();
}

/// Exact motion of torque-free, undamped bodies under uniform gravity whose angular velocity
/// stays constant (spheres, cubes, or no spin): a parabola and a steady rotation.
std::function<std::optional<BodyState>(const std::string&, double)> ballisticReference(const Scene& scene) {
    auto defs = std::make_shared<std::map<std::string, BodyDef>>();
    for (const BodyDef& def : scene.bodies) (*defs)[def.name] = def;
    const Vec3 gravity = scene.settings.gravity;
    return [defs, gravity](const std::string& body, double t) -> std::optional<BodyState> {
        const auto it = defs->find(body);
        if (it == defs->end()) return std::nullopt;
        const BodyDef& def = it->second;
        const Vec3 g = def.type == BodyType::Dynamic ? Vec3(gravity * def.gravityScale) : Vec3::Zero();
        BodyState s;
        s.position = def.position + def.linearVelocity * t + 0.5 * g * t * t;
        s.linearVelocity = def.linearVelocity + g * t;
        s.angularVelocity = def.angularVelocity;
        s.orientation = rotateConstant(def.orientation, def.angularVelocity, t);
        return s;
    };
}

/// A thin plate whose principal moments are exactly diag(1, 2, 3) kg m^2 (given explicitly; the
/// plate shape, 12 kg, 1.414 x 1 x 0.02 m, has nearly these moments).
BodyDef racketBody(const std::string& name) {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::box(Vec3(std::sqrt(0.5), 0.5, 0.01));
    def.mass = 12.0;
    def.inertia = Vec3(1.0, 2.0, 3.0);
    def.gyroscopic = GyroscopicMode::Implicit;
    return def;
}

CatalogueScene projectile() {
    CatalogueScene c;
    c.name = "projectile";
    c.description = "ball thrown at (10,10,0) m/s under g = 10 m/s^2; lands back at height 0 at t = 2 s";
    c.duration = 2.0;
    c.scene.settings.gravity = Vec3(0, -10, 0);
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef ball = sphereBody("ball", 0.5, 1.0);
    ball.linearVelocity = Vec3(10, 10, 0);
    c.scene.bodies.push_back(ball);
    c.reference = ballisticReference(c.scene);
    c.conservesEnergy = true;
    // L stays exactly zero (no spin), so a relative drift is meaningless: not flagged.
    return c;
}

CatalogueScene torqueFreeSpin() {
    CatalogueScene c;
    c.name = "torque_free_spin";
    c.description = "box with inertia diag(1,2,3) spinning near its major axis, no gravity: |L| and energy conserved";
    c.duration = 10.0;
    c.scene.settings.gravity = Vec3::Zero();
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef box = racketBody("box");
    box.angularVelocity = Vec3(0.3, 0.2, 4.0);  // world frame = body frame at t = 0
    c.scene.bodies.push_back(box);
    // The orientation has no elementary closed form, so there is no reference; the
    // conservation laws measure the integrator instead.
    c.conservesEnergy = true;
    c.conservesAngularMomentum = true;
    return c;
}

/// The same spin with the gyroscopic term handed to the integrator, so the integrators' orders
/// show in the conservation of |L| and energy (the implicit mode is integrator-independent).
CatalogueScene torqueFreeSpinExplicit() {
    CatalogueScene c = torqueFreeSpin();
    c.name = "torque_free_spin_explicit";
    c.description = "torque_free_spin with gyroscopic \"explicit\": the integrator carries the rotation";
    c.scene.bodies.front().gyroscopic = GyroscopicMode::Explicit;
    return c;
}

CatalogueScene intermediateAxisFlip() {
    CatalogueScene c;
    c.name = "intermediate_axis_flip";
    c.description = "tennis racket: spin (0.01,5,0) rad/s about the intermediate axis of diag(1,2,3) reverses near t = 2.6 s";
    c.duration = 6.0;
    c.scene.settings.gravity = Vec3::Zero();
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef racket = racketBody("racket");
    racket.angularVelocity = Vec3(0.01, 5.0, 0.0);  // identity orientation: body frame = world frame
    c.scene.bodies.push_back(racket);
    c.conservesEnergy = true;
    c.conservesAngularMomentum = true;
    return c;
}

CatalogueScene dampedMotion() {
    constexpr double c0 = 0.5;  // 1/s, both dampings
    CatalogueScene c;
    c.name = "damped_motion";
    c.description = "sphere sliding at 4 m/s and spinning at 2 rad/s with damping 0.5/s, no gravity: exponential decay";
    c.duration = 4.0;
    c.scene.settings.gravity = Vec3::Zero();
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef ball = sphereBody("ball", 0.5, 1.0);
    ball.linearVelocity = Vec3(4, 0, 0);
    ball.angularVelocity = Vec3(0, 0, 2);  // a sphere is isotropic: no gyroscopic coupling
    ball.linearDamping = c0;
    ball.angularDamping = c0;
    c.scene.bodies.push_back(ball);
    const BodyDef def = ball;
    // dv/dt = -c v  =>  v = v0 e^{-ct}, p = p0 + v0 (1 - e^{-ct}) / c; the same for the spin.
    c.reference = [def](const std::string& body, double t) -> std::optional<BodyState> {
        if (body != def.name) return std::nullopt;
        const double decay = std::exp(-c0 * t);
        const double travelled = (1.0 - decay) / c0;  // integral of e^{-cs} ds over [0, t]
        BodyState s;
        s.position = def.position + def.linearVelocity * travelled;
        s.linearVelocity = def.linearVelocity * decay;
        s.angularVelocity = def.angularVelocity * decay;
        s.orientation = rotateConstant(def.orientation, def.angularVelocity, travelled);
        return s;
    };
    return c;
}

CatalogueScene freeFallDrop() {
    CatalogueScene c;
    c.name = "free_fall_drop";
    c.description = "ball with gravityScale 0.5 dropped from 10 m under default gravity: falls with g/2";
    c.duration = 1.0;
    BodyDef ball = sphereBody("ball", 0.5, 1.0);
    ball.position = Vec3(0, 10, 0);
    ball.gravityScale = 0.5;
    c.scene.bodies.push_back(ball);
    c.reference = ballisticReference(c.scene);
    c.conservesEnergy = true;
    return c;
}

CatalogueScene freeBodies() {
    CatalogueScene c;
    c.name = "free_bodies";
    c.description = "benchmark load: 1000 spinning cubes thrown upwards under default gravity, nothing to collide";
    c.duration = 1.0;
    c.scene = freeBodiesScene(1000);
    c.reference = ballisticReference(c.scene);  // cubes are isotropic: the spin stays constant
    c.conservesEnergy = true;
    c.conservesAngularMomentum = true;
    return c;
}

// ---- contact scenes ----------------------------------------------------------------------------

CatalogueScene bouncingBall() {
    constexpr double kRestitution = 0.5, kRadius = 0.5, kStart = 5.0;
    CatalogueScene c;
    c.name = "bouncing_ball";
    c.description = "ball (r 0.5 m, restitution 0.5) dropped from a centre height of 5 m onto the ground: "
                    "first rebound e^2 = 0.25 of the 4.5 m drop";
    c.duration = 5.0;
    c.scene.settings.timeStep = 1.0 / 60.0;
    c.scene.materials.add("rubber", Material{0.6, kRestitution, 1000.0});
    c.scene.bodies.push_back(groundPlane());  // default material: restitution 0; the rule "max" gives 0.5
    BodyDef ball = sphereBody("ball", kRadius, 1.0);
    ball.position = Vec3(0, kStart, 0);
    ball.material = "rubber";
    c.scene.bodies.push_back(ball);
    // Impact at sqrt(2 g 4.5) = 9.4 m/s, far above the 1 m/s restitution threshold.
    SceneCheck check{"rebound/drop", "", kRestitution * kRestitution, 0.05 * kRestitution * kRestitution,
                     "5 %: what an engine bouncing off the step-start speed may miss at 9.4 m/s (2 g dt / v + "
                     "g dt / (2 e v) = 5.2 %, by where in the step the ball lands); the contract holds a bounce "
                     "off the impact speed to 5.3 mm (slop and apex sampling)", {}, ""};
    check.makeProbe = [radius = kRadius] { return std::make_unique<ReboundProbe>(1, radius); };
    check.criterion = "restitution.rebound_height";
    c.check = check;
    return c;
}

CatalogueScene slopeSlide() {
    constexpr double kAngle = std::numbers::pi / 6.0, kFriction = 0.3, kG = 9.81, kHalf = 0.25;
    const double accel = kG * (std::sin(kAngle) - kFriction * std::cos(kAngle));  // 2.356 m/s^2
    const Quat tilt(Eigen::AngleAxisd(kAngle, Vec3::UnitZ()));
    const Vec3 normal = tilt * Vec3::UnitY(), uphill = tilt * Vec3::UnitX();

    CatalogueScene c;
    c.name = "slope_slide";
    c.description = "box released on a 30 deg slope, friction 0.3: slides with a = g (sin 30 - 0.3 cos 30) = 2.356 m/s^2";
    c.duration = 1.5;  // slides 2.65 m of the 8 m slope: still on it at the end
    c.scene.settings.timeStep = 1.0 / 60.0;
    c.scene.materials.add("slope", Material{kFriction, 0.0, 1000.0});
    c.scene.materials.add("block", Material{kFriction, 0.0, 1000.0});  // geometric mean: 0.3
    BodyDef slope;
    slope.name = "slope";
    slope.type = BodyType::Static;
    slope.shape = ShapeDef::box(Vec3(4.0, 0.5, 2.0));  // 8 m long, 1 m thick, centred at the origin
    slope.orientation = tilt;
    slope.material = "slope";
    c.scene.bodies.push_back(slope);
    BodyDef block;
    block.name = "block";
    block.shape = ShapeDef::box(Vec3(kHalf, kHalf, kHalf));
    block.orientation = tilt;  // flat on the slope
    block.position = uphill * 2.5 + normal * (0.5 + kHalf);  // resting on the top face, 2.5 m up from its middle
    block.material = "block";
    c.scene.bodies.push_back(block);

    const BodyDef start = block;
    const Vec3 downhill = -uphill;
    c.reference = [start, downhill, accel](const std::string& body, double t) -> std::optional<BodyState> {
        if (body != start.name) return std::nullopt;
        BodyState s;
        s.position = start.position + 0.5 * accel * t * t * downhill;
        s.linearVelocity = accel * t * downhill;
        s.orientation = start.orientation;  // slides without turning
        return s;
    };
    c.check = endpointCheck(
        SceneCheck{"slide accel", "m/s^2", accel, 0.05 * accel, "5 %: the contract's bound on the slide acceleration", {},
                   "slope.kinetic_acceleration"},
        [downhill](const std::vector<BodyState>& first, const std::vector<BodyState>& last, double t) {
            // s = a t^2 / 2 from rest, so the mean acceleration over the run is 2 s / t^2.
            return t > 0 ? 2.0 * (last[1].position - first[1].position).dot(downhill) / (t * t) : 0.0;
        });
    return c;
}

CatalogueScene boxStack10() {
    constexpr int kBoxes = 10;
    CatalogueScene c;
    c.name = "box_stack_10";
    c.description = "10 unit boxes stacked on the ground with no gap, sleeping off: must stand; top box's largest sideways drift over 10 s";
    c.duration = 10.0;
    c.scene.settings.timeStep = 1.0 / 60.0;
    c.scene.bodies.push_back(groundPlane());
    for (int i = 0; i < kBoxes; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "box_%02d", i);
        c.scene.bodies.push_back(unitBox(name, Vec3(0, 0.5 + i, 0)));
        c.scene.bodies.back().allowSleep = false;  // sleep would freeze the stack before drift shows
    }
    c.check = worstOverRunCheck(
        SceneCheck{"top drift", "m", 0.0, 0.01, "1 cm sideways at any time: the contract's bound for a standing stack", {},
                   "stack10.top_drift"},
        maxHorizontalDrift({static_cast<std::size_t>(kBoxes)}));
    return c;
}

CatalogueScene pyramid20() {
    constexpr int kRows = 20;
    CatalogueScene c;
    c.name = "pyramid_20";
    c.description = "pyramid of 210 unit boxes, 20 rows, base 20, no gaps, sleeping off: must stand for 5 s (largest sideways drift over the run)";
    c.duration = 5.0;
    c.scene.settings.timeStep = 1.0 / 60.0;
    c.scene.bodies.push_back(groundPlane());
    for (int row = 0; row < kRows; ++row) {
        const int count = kRows - row;
        for (int i = 0; i < count; ++i) {
            char name[40];
            std::snprintf(name, sizeof name, "box_r%02d_%02d", row, i);
            const double x = i - 0.5 * (count - 1);  // each row centred on x = 0, boxes side by side
            c.scene.bodies.push_back(unitBox(name, Vec3(x, 0.5 + row, 0)));
            c.scene.bodies.back().allowSleep = false;
        }
    }
    c.check = worstOverRunCheck(
        SceneCheck{"max box drift", "m", 0.0, 0.01,
                   "1 cm sideways at any time: nothing pushes a symmetric pyramid sideways, and its rows spread only "
                   "as the contacts below compress (by at most linearSlop, 5 mm, each), so more is solver error",
                   {}, "pyramid20.drift"},
        maxHorizontalDrift(dynamicBodies(c.scene)));
    return c;
}

CatalogueScene boxGrid1000() {
    CatalogueScene c;
    c.name = "box_grid_1000";
    c.description = "benchmark load: 10x10x10 unit boxes 1.2 m apart dropped from 1 m onto the ground: settles in 5 s";
    c.duration = 5.0;
    c.scene = boxGridScene(10, 10, 10, 1.2, 1.0);
    const std::vector<std::size_t> boxes = dynamicBodies(c.scene);
    c.check = endpointCheck(
        SceneCheck{"max speed", "m/s", 0.0, 0.05, "0.05 m/s: the default sleep threshold; slower counts as settled", {}, ""},
        [boxes](const std::vector<BodyState>&, const std::vector<BodyState>& last, double) {
            double fastest = 0.0;
            for (std::size_t i : boxes) {
                const double v = last[i].linearVelocity.norm();
                if (!(v <= fastest)) fastest = v;
            }
            return fastest;
        });
    c.compareByDefault = false;  // 300 steps of a 1000-box pile per integrator: run it by name
    return c;
}

/// The same scene as a planar world (XY plane, rotation about Z), runnable on 2D backends. Only
/// for scenes whose bodies already lie in the plane z = 0 and turn about Z.
CatalogueScene planar(CatalogueScene c) {
    c.name += "_planar";
    c.description = "planar (XY) " + c.description;
    c.scene.settings.planar = true;
    if (c.check && !c.check->criterion.empty()) c.check->criterion = "planar." + c.check->criterion;
    return c;
}

CatalogueScene boxGrid1000Planar() {
    CatalogueScene c = boxGrid1000();
    c.name = "box_grid_1000_planar";
    c.description = "benchmark load, planar: 50x20 unit boxes 1.2 m apart in the XY plane dropped from 1 m onto the ground";
    const auto check = c.check;
    c.scene = boxGridScene(50, 20, 1, 1.2, 1.0);
    c.scene.settings.planar = true;
    c.check = check;  // the fastest body at the end; body 0 is still the ground
    return c;
}

// ---- joint scenes --------------------------------------------------------------------------------

/// Period of an oscillation: the mean time between downward crossings of `level` by one
/// coordinate of one body (interpolated within the step). 0 until two crossings were seen.
class PeriodProbe : public SceneProbe {
public:
    PeriodProbe(std::size_t body, int axis, double level) : body_(body), axis_(axis), level_(level) {}
    void observe(double time, const std::vector<BodyState>& states) override {
        const double x = states.at(body_).position[axis_] - level_;
        if (previousTime_ >= 0.0 && previous_ > 0.0 && x <= 0.0) {
            const double crossing = previousTime_ + (time - previousTime_) * previous_ / (previous_ - x);
            if (count_ == 0) first_ = crossing;
            last_ = crossing;
            ++count_;
        }
        if (!std::isfinite(x)) broken_ = true;
        previous_ = x;
        previousTime_ = time;
    }
    double value() const override {
        if (broken_) return std::numeric_limits<double>::quiet_NaN();
        return count_ > 1 ? (last_ - first_) / (count_ - 1) : 0.0;
    }

private:
    std::size_t body_;
    int axis_;
    double level_;
    double previous_ = 0.0, previousTime_ = -1.0, first_ = 0.0, last_ = 0.0;
    int count_ = 0;
    bool broken_ = false;
};

/// Largest |distance - spacing| between consecutive bodies of a chain hung from `anchor`, over
/// the whole run: how far the joints let the links apart (or together).
class ChainGapProbe : public SceneProbe {
public:
    ChainGapProbe(std::vector<std::size_t> links, Vec3 anchor, double spacing)
        : links_(std::move(links)), anchor_(anchor), spacing_(spacing) {}
    void observe(double, const std::vector<BodyState>& states) override {
        Vec3 previous = anchor_;
        for (std::size_t i : links_) {
            const double gap = std::abs((states.at(i).position - previous).norm() - spacing_);
            if (!(gap <= worst_)) worst_ = gap;  // keeps a NaN visible
            previous = states.at(i).position;
        }
    }
    double value() const override { return worst_; }

private:
    std::vector<std::size_t> links_;
    Vec3 anchor_;
    double spacing_;
    double worst_ = 0.0;
};

double ellipticK(double k) {  // complete elliptic integral of the first kind (AGM)
    double a = 1.0, b = std::sqrt(1.0 - k * k);
    for (int i = 0; i < 30; ++i) {
        const double next = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = next;
    }
    return std::numbers::pi / (2.0 * a);
}

CatalogueScene hingePendulum() {
    constexpr double kLength = 1.0, kRadius = 0.1, kAmplitude = 1.0, kG = 9.81;
    const double inertia = 0.4 * kRadius * kRadius;  // a 1 kg ball
    const double period = 4.0 * std::sqrt((inertia + kLength * kLength) / kLength / kG) * ellipticK(std::sin(0.5 * kAmplitude));
    CatalogueScene c;
    c.name = "hinge_pendulum";
    c.description = "1 m pendulum (1 kg ball, r 0.1 m) on a hinge about Z, released at 1 rad: period "
                    "4 sqrt(L'/g) K(sin(theta0/2)) = 2.143 s for the physical pendulum";
    c.duration = 10.0 * period;
    BodyDef bob = sphereBody("bob", kRadius, 1.0);
    bob.position = Vec3(kLength * std::sin(kAmplitude), -kLength * std::cos(kAmplitude), 0.0);
    bob.allowSleep = false;
    c.scene.bodies.push_back(bob);
    SceneJoint pivot;
    pivot.def.name = "pivot";
    pivot.def.type = JointType::Hinge;
    pivot.def.axis = Vec3::UnitZ();
    pivot.bodyB = "bob";
    c.scene.joints.push_back(pivot);
    c.conservesEnergy = true;
    SceneCheck check{"period", "s", period, 0.01 * period,
                     "1 %: a 60 Hz step resolves the swing in 128 steps; a stretching or slipping joint would not stay inside",
                     {}, "joints.pendulum_period"};
    check.makeProbe = [] { return std::make_unique<PeriodProbe>(0, 0, 0.0); };
    c.check = check;
    return c;
}

CatalogueScene hangingChain() {
    constexpr int kLinks = 40;
    constexpr double kSpacing = 0.1, kLinkMass = 0.1, kEndMass = 1.0;  // end mass 10x a link
    CatalogueScene c;
    c.name = "chain_40";
    c.description = "40 ball-jointed links (0.1 kg, 10 cm apart) with a 1 kg end mass (10x a link), released "
                    "horizontal: largest joint gap over the run";
    c.duration = 5.0;
    std::vector<std::size_t> links;
    for (int i = 0; i < kLinks; ++i) {
        const bool end = i + 1 == kLinks;
        BodyDef link = sphereBody("link_" + std::to_string(i), 0.03, end ? kEndMass : kLinkMass);
        link.position = Vec3(kSpacing * (i + 1), 0.0, 0.0);
        link.allowSleep = false;
        link.mask = 0;  // links pass through each other: the joints are measured, not the contacts
        c.scene.bodies.push_back(link);
        links.push_back(static_cast<std::size_t>(i));
        SceneJoint joint;
        joint.def.type = JointType::Ball;
        joint.def.anchor = Vec3(kSpacing * i, 0.0, 0.0);
        joint.bodyA = i == 0 ? "" : "link_" + std::to_string(i - 1);
        joint.bodyB = link.name;
        c.scene.joints.push_back(joint);
    }
    SceneCheck check{"max joint gap", "m", 0.0, 0.02,
                     "2 cm, a fifth of a link: stretched but holding; iterative solvers stretch on heavy ends",
                     {}, "hard.chain40.gap"};
    check.makeProbe = [links, spacing = kSpacing] { return std::make_unique<ChainGapProbe>(links, Vec3::Zero(), spacing); };
    c.check = check;
    return c;
}

CatalogueScene motorSpinUp() {
    constexpr double kMass = 2.0, kRadius = 0.5, kTorque = 1.0, kTarget = 5.0;
    const double inertia = 0.4 * kMass * kRadius * kRadius;  // 0.2 kg m^2: t* = I w / tau = 1 s
    CatalogueScene c;
    c.name = "motor_spinup";
    c.description = "a flywheel (2 kg ball, r 0.5 m) on a hinge motor (5 rad/s, 1 N m), no gravity: w = tau t / I "
                    "until t* = 1 s, then 5 rad/s";
    c.duration = 2.0;
    c.scene.settings.gravity = Vec3::Zero();
    BodyDef wheel = sphereBody("wheel", kRadius, kMass);
    wheel.allowSleep = false;
    c.scene.bodies.push_back(wheel);
    SceneJoint motor;
    motor.def.name = "motor";
    motor.def.type = JointType::Hinge;
    motor.def.axis = Vec3::UnitZ();
    motor.def.motor = JointMotor{kTarget, kTorque};
    motor.bodyB = "wheel";
    c.scene.joints.push_back(motor);
    c.reference = [inertia, torque = kTorque, target = kTarget](const std::string& body, double t) -> std::optional<BodyState> {
        if (body != "wheel") return std::nullopt;
        BodyState s;  // the centre stays put; the spin is what the check measures
        s.angularVelocity = Vec3(0, 0, std::min(torque * t / inertia, target));
        return s;
    };
    c.check = endpointCheck({"final spin", "rad/s", kTarget, 0.01 * kTarget,
                             "1 %: the motor holds its target speed once reached", {}, "joints.motor_speed"},
                            [](const std::vector<BodyState>&, const std::vector<BodyState>& last, double) {
                                return last[0].angularVelocity.z();
                            });
    return c;
}

CatalogueScene sliderSpring() {
    constexpr double kStiffness = 40.0, kMass = 2.0, kSpeed = 0.5;
    const double omega = std::sqrt(kStiffness / kMass);
    CatalogueScene c;
    c.name = "slider_spring";
    c.description = "2 kg on a slider along X with a 40 N/m spring, started at 0.5 m/s, no gravity: "
                    "x = (v0 / w) sin(w t), period 2 pi sqrt(m / k) = 1.405 s";
    c.duration = 10.0;
    c.scene.settings.gravity = Vec3::Zero();
    BodyDef mass;
    mass.name = "mass";
    mass.shape = ShapeDef::box(Vec3(0.1, 0.1, 0.1));
    mass.mass = kMass;
    mass.linearVelocity = Vec3(kSpeed, 0, 0);
    mass.allowSleep = false;
    c.scene.bodies.push_back(mass);
    SceneJoint slider;
    slider.def.name = "rail";
    slider.def.type = JointType::Slider;
    slider.def.axis = Vec3::UnitX();
    slider.def.spring = JointSpring{kStiffness, 0.0};
    slider.bodyB = "mass";
    c.scene.joints.push_back(slider);
    c.reference = [omega](const std::string& body, double t) -> std::optional<BodyState> {
        if (body != "mass") return std::nullopt;
        BodyState s;
        s.position = Vec3(kSpeed / omega * std::sin(omega * t), 0, 0);
        s.linearVelocity = Vec3(kSpeed * std::cos(omega * t), 0, 0);
        return s;
    };
    c.conservesEnergy = false;  // the spring's energy is not in the bodies' mechanical energy
    const double period = 2.0 * std::numbers::pi / omega;
    SceneCheck check{"period", "s", period, 0.01 * period,
                     "1 %: (w dt)^2 = 3e-3 at 60 Hz bounds an explicit or implicit spring's period error", {},
                     "joints.spring_period"};
    check.makeProbe = [] { return std::make_unique<PeriodProbe>(0, 0, 0.0); };
    c.check = check;
    return c;
}

std::vector<CatalogueScene> buildCatalogue() {
    std::vector<CatalogueScene> all;
    all.push_back(projectile());
    all.push_back(torqueFreeSpin());
    all.push_back(torqueFreeSpinExplicit());
    all.push_back(intermediateAxisFlip());
    all.push_back(dampedMotion());
    all.push_back(freeFallDrop());
    all.push_back(freeBodies());
    all.push_back(bouncingBall());
    all.push_back(slopeSlide());
    all.push_back(boxStack10());
    all.push_back(pyramid20());
    all.push_back(boxGrid1000());
    all.push_back(planar(bouncingBall()));
    all.push_back(planar(slopeSlide()));
    all.push_back(planar(boxStack10()));
    all.push_back(planar(pyramid20()));
    all.push_back(boxGrid1000Planar());
    all.push_back(hingePendulum());
    all.push_back(hangingChain());
    all.push_back(motorSpinUp());
    all.push_back(sliderSpring());
    // The joint scenes move in the XY plane with hinges about Z: the same on 2D engines.
    all.push_back(planar(hingePendulum()));
    all.push_back(planar(hangingChain()));
    all.push_back(planar(motorSpinUp()));
    all.push_back(planar(sliderSpring()));
    // Hard cases: the catalogue's own stress scenes, and those built for the purpose.
    for (CatalogueScene& c : all)
        if (c.name == "pyramid_20" || c.name == "pyramid_20_planar" || c.name == "chain_40" || c.name == "chain_40_planar")
            c.hardCase = true;
    for (CatalogueScene& c : hardCaseScenes()) all.push_back(std::move(c));
    return all;
}

}  // namespace

Scene freeBodiesScene(int count) {
    if (count < 0) throw Error::invalid("freeBodiesScene.count", count, "must be >= 0");
    Scene scene;
    constexpr int kRow = 10;  // bodies per grid row and column; spacing 1 m keeps them apart
    for (int i = 0; i < count; ++i) {
        BodyDef def;
        char name[32];
        std::snprintf(name, sizeof name, "box_%04d", i);
        def.name = name;
        def.shape = ShapeDef::box(Vec3(0.1, 0.1, 0.1));
        def.mass = 1.0;
        def.position = Vec3(i % kRow, (i / kRow) % kRow, i / (kRow * kRow));
        // Smooth deterministic spread of velocities (no RNG, so every platform builds the same scene).
        const double a = 0.7 * i;
        def.linearVelocity = Vec3(std::sin(a), 5.0 + std::cos(a), std::sin(1.3 * a));
        def.angularVelocity = Vec3(std::cos(0.5 * a), std::sin(0.9 * a), 2.0);
        def.mask = 0;  // collides with nothing, so the load stays free bodies where contacts exist
        scene.bodies.push_back(def);
    }
    return scene;
}

Scene boxGridScene(int nx, int ny, int nz, double spacing, double dropHeight) {
    if (nx < 0 || ny < 0 || nz < 0)
        throw Error::invalid("boxGridScene.counts", std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz),
                             "must be >= 0");
    Scene scene;
    scene.settings.timeStep = 1.0 / 60.0;
    scene.bodies.push_back(groundPlane());
    for (int y = 0; y < ny; ++y)
        for (int z = 0; z < nz; ++z)
            for (int x = 0; x < nx; ++x) {
                const std::string name = "box_" + std::to_string(x) + "_" + std::to_string(y) + "_" + std::to_string(z);
                // Centred on the y axis; the lowest layer's bottoms at dropHeight.
                const Vec3 at((x - 0.5 * (nx - 1)) * spacing, dropHeight + 0.5 + y * spacing, (z - 0.5 * (nz - 1)) * spacing);
                scene.bodies.push_back(unitBox(name, at));
            }
    return scene;
}

const std::vector<CatalogueScene>& sceneCatalogue() {
    static const std::vector<CatalogueScene> catalogue = buildCatalogue();
    return catalogue;
}

const CatalogueScene& catalogueScene(const std::string& name) {
    std::string known;
    for (const CatalogueScene& c : sceneCatalogue()) {
        if (c.name == name) return c;
        known += (known.empty() ? "" : ", ") + c.name;
    }
    throw Error::invalid("scene", "\"" + name + "\"", "unknown catalogue scene; known: " + known);
}

}  // namespace anyphys
