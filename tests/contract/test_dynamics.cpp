// Free-body dynamics every backend must get right: forces, impulses, damping, gravity scale,
// kinematic bodies, the fixed-step accumulator and effect selection.
#include <cmath>

#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class DynamicsTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
    WorldSettings weightless() const {
        WorldSettings s = settings();
        s.gravity = Vec3::Zero();
        return s;
    }
};

// Newton's second law over one step: dv = F dt / m, and the force lasts one step only.
TEST_P(DynamicsTest, ForceActsForOneStep) {
    World world(weightless());
    BodyDef def = sphereDef(0.5);
    def.mass = 2.0;
    Body b = world.createBody(def);
    b.applyForce(Vec3(4, 0, 0));
    world.step();
    const double dt = world.settings().timeStep;
    // Exact up to rounding: a few roundings of v (1e-12 covers a double engine's arithmetic).
    const double dv = 4.0 / 2.0 * dt, tolerance = 1e-12 + rounding(dv, 4);
    EXPECT_NEAR(b.linearVelocity().x(), dv, tolerance);
    world.step();
    EXPECT_NEAR(b.linearVelocity().x(), dv, tolerance);  // no force any more
}

// Impulses change velocity at once: dv = J / m, dw = I^-1 J (principal axes aligned with world).
// In a planar world only the spin about Z exists: the angular impulse is about Z alone.
TEST_P(DynamicsTest, ImpulsesChangeVelocityImmediately) {
    World world(weightless());
    BodyDef def;
    def.shape = ShapeDef::box(Vec3(0.5, 0.25, 0.125));
    def.mass = 3.0;
    def.inertia = Vec3(1, 2, 4);
    Body b = world.createBody(def);
    b.applyLinearImpulse(Vec3(0, 6, 0));
    const Vec3 angularImpulse = planarWorld() ? Vec3(0, 0, 2) : Vec3(2, 2, 2);
    const Vec3 spin = planarWorld() ? Vec3(0, 0, 0.5) : Vec3(2, 1, 0.5);
    b.applyAngularImpulse(angularImpulse);
    EXPECT_NEAR((b.linearVelocity() - Vec3(0, 2, 0)).norm(), 0, 1e-14 + rounding(2, 2));
    EXPECT_NEAR((b.angularVelocity() - spin).norm(), 0, 1e-14 + rounding(2, 2));
}

// A torque about a principal axis spins the body at w = tau t / I.
TEST_P(DynamicsTest, TorqueAboutPrincipalAxis) {
    World world(weightless());
    BodyDef def = sphereDef(0.5);
    def.mass = 1.0;
    def.inertia = Vec3(0.5, 0.5, 0.25);
    Body b = world.createBody(def);
    for (int i = 0; i < 60; ++i) {
        b.applyTorque(Vec3(0, 0, 1));
        world.step();
    }
    // 1 s of torque; 1e-9 for a double engine, and a float one rounds w (4) at each of 60 steps.
    EXPECT_NEAR(b.angularVelocity().z(), 1.0 / 0.25 * 1.0, 1e-9 + rounding(4, 60));
}

// Mass from shape and density when not given: a 1 m box of density 500 weighs 500 kg and has
// I = m (1 + 1) / 12 about each axis.
TEST_P(DynamicsTest, MassPropertiesFromShapeAndDensity) {
    World world(settings());
    BodyDef def;
    def.shape = ShapeDef::box(Vec3(0.5, 0.5, 0.5));
    def.density = 500.0;
    const MassProperties m = world.createBody(def).massProperties();
    EXPECT_NEAR(m.mass, 500.0, 1e-9);
    EXPECT_NEAR(m.inertia.x(), 500.0 * 2.0 / 12.0, 1e-9);
    // Sphere of radius 0.5 with the default density 1000: m = 4/3 pi r^3 rho, I = 2/5 m r^2.
    const MassProperties s = world.createBody(sphereDef(0.5)).massProperties();
    EXPECT_NEAR(s.mass, 4.0 / 3.0 * M_PI * 0.125 * 1000.0, 1e-9);
    EXPECT_NEAR(s.inertia.y(), 0.4 * s.mass * 0.25, 1e-9);
    // What the backend simulates, not what the layer computed: impulses on the 500 kg box give
    // dv = J / m and dw = J / I (about Z, which a planar world keeps) to rounding.
    World weightless(this->weightless());
    Body box = weightless.createBody(def);
    box.applyLinearImpulse(Vec3(250, 0, 0));
    box.applyAngularImpulse(Vec3(0, 0, 500.0 * 2.0 / 12.0 * 3.0));
    EXPECT_NEAR(box.linearVelocity().x(), 0.5, 1e-12 + rounding(0.5, 4));
    EXPECT_NEAR(box.angularVelocity().z(), 3.0, 1e-12 + rounding(3, 4));
    weightless.step();  // and the engine moves it with them
    const double moved = 0.5 * weightless.settings().timeStep;
    EXPECT_NEAR(box.position().x(), moved, 1e-12 + rounding(moved, 4));
}

// Linear damping dv/dt = -c v: v(t) = v0 e^{-ct}. RK4 at 60 Hz is accurate to ~1e-9.
TEST_P(DynamicsTest, DampingDecaysExponentially) {
    ANYPHYS_REQUIRE(caps().parameters.count("body.linearDamping"), "parameter body.linearDamping");
    ANYPHYS_REQUIRE(caps().integrators.count(Integrator::RK4), "integrator rk4");
    WorldSettings s = weightless();
    s.integrator = Integrator::RK4;
    World world(s);
    BodyDef def = sphereDef(0.5);
    def.linearVelocity = Vec3(5, 0, 0);
    def.linearDamping = 0.8;
    Body b = world.createBody(def);
    EXPECT_TRUE(world.activeEffects().has(Effect::Damping));
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_NEAR(b.linearVelocity().x(), 5.0 * std::exp(-0.8 * 2.0), 1e-8);
}

// Damping at c h = 0.05 on the default integrator (semi-implicit Euler), the rate a game uses:
// every engine scales the velocity by the exact decay, so after 2 s it is v0 exp(-c t). Native
// once damped free bodies as a force, (1 - c h) per step: 14 % short after these 120 steps.
TEST_P(DynamicsTest, DampingOnTheDefaultIntegratorDecaysByTheExactFactor) {
    ANYPHYS_REQUIRE(caps().parameters.count("body.linearDamping") && caps().parameters.count("body.angularDamping"),
                    "parameters body.linearDamping and body.angularDamping");
    const double c = 3.0;
    World world(weightless());
    BodyDef def = sphereDef(0.5);  // isotropic: the spin keeps its axis
    def.linearVelocity = Vec3(4, 0, 0);
    def.angularVelocity = Vec3(0, 0, 2);
    def.linearDamping = c;
    def.angularDamping = c;
    Body b = world.createBody(def);
    const int steps = 120;
    for (int i = 0; i < steps; ++i) world.step();
    const double decay = std::exp(-c * steps * world.settings().timeStep);
    // 1e-5 relative: the factor is exact; a float engine rounds it by about 1e-7 a step.
    EXPECT_NEAR(b.linearVelocity().x(), 4 * decay, 1e-5 * 4 * decay);
    EXPECT_NEAR(b.angularVelocity().z(), 2 * decay, 1e-5 * 2 * decay);
}

// A free body spinning at 20 rad/s (1/3 rad a step at 60 Hz) about a fixed axis turns by w t:
// the rotation over a step at constant spin is exact in every engine's update (exponential
// map), where the first-order quaternion update q + h dq/dt turns by 2 atan(w h / 2) a step,
// 0.18 rad short after this second (native did, before it took the exact rotation).
TEST_P(DynamicsTest, AFreeSpinTurnsByTheSpinTimesTheTime) {
    const double w = 20.0;
    World world(weightless());
    BodyDef def = sphereDef(0.5);
    def.angularVelocity = Vec3(0, 0, w);
    Body b = world.createBody(def);
    const int steps = 60;
    for (int i = 0; i < steps; ++i) world.step();
    const double t = steps * world.settings().timeStep;
    const Quat exact(Eigen::AngleAxisd(w * t, Vec3::UnitZ()));
    // 1e-4 rad: exact up to rounding; a float engine's angle (about 20 rad) carries a few 1e-6 rad
    // a step.
    EXPECT_LT(b.orientation().angularDistance(exact), 1e-4) << "angular speed " << b.angularVelocity().z();
}

// Damping far stiffer than the step, dv/dt = -c v with c h = 0.67 and 2.5 at 60 Hz: an explicit
// update (v *= 1 - c h) flips the velocity's sign and grows it 1.5x per step at c = 150, and
// Bullet's own damping (1 - d)^h freezes the body once d = 1 - exp(-c) rounds to 1 (c > 37).
// The exact decay exp(-c h) per step is stable for any c: v after n steps is v0 exp(-c n h).
TEST_P(DynamicsTest, StiffDampingDecaysByTheExactFactor) {
    ANYPHYS_REQUIRE(caps().parameters.count("body.linearDamping") && caps().parameters.count("body.angularDamping"),
                    "parameters body.linearDamping and body.angularDamping");
    for (double c : {40.0, 150.0}) {
        SCOPED_TRACE("damping " + std::to_string(c) + " 1/s");
        World world(weightless());
        const double h = world.settings().timeStep;
        BodyDef def;
        def.shape = ShapeDef::sphere(0.5);  // isotropic: the spin keeps its axis
        def.linearVelocity = Vec3(5, 0, 0);
        def.angularVelocity = Vec3(0, 0, 3);
        def.linearDamping = c;
        def.angularDamping = c;
        Body b = world.createBody(def);
        for (int n = 1; n <= 3; ++n) {
            world.step();
            const double decay = std::exp(-c * n * h);
            // 1e-5 relative: the factor is exact; float engines round it to about 1e-7 per step.
            EXPECT_NEAR(b.linearVelocity().x(), 5 * decay, 1e-5 * 5 * decay) << "after " << n << " steps";
            EXPECT_NEAR(b.angularVelocity().norm(), 3 * decay, 1e-5 * 3 * decay) << "after " << n << " steps";
        }
        // Over the three steps it moves between the right and left Riemann sums of the exact
        // velocity (each step at its end or its start velocity): an engine may damp before or
        // after moving, but not move further or backwards. 1e-6 relative for float engines.
        const double f = std::exp(-c * h);
        const double least = 5 * h * (f + f * f + f * f * f), most = 5 * h * (1 + f + f * f);
        EXPECT_GE(b.position().x(), least * (1 - 1e-6));
        EXPECT_LE(b.position().x(), most * (1 + 1e-6));
    }
}

// Gravity scale 0.5 halves the fall: after n steps of h, semi-implicit Euler's closed form is
// y = y0 - g' h^2 n (n + 1) / 2 with g' = g / 2 (Verlet's, where semi-implicit Euler is not
// offered: y0 - g' t^2 / 2, exact for a constant acceleration).
TEST_P(DynamicsTest, GravityScale) {
    ANYPHYS_REQUIRE(caps().parameters.count("body.gravityScale"), "parameter body.gravityScale");
    const bool semiImplicit = caps().integrators.count(Integrator::SemiImplicitEuler) > 0;
    ANYPHYS_REQUIRE(semiImplicit || caps().integrators.count(Integrator::Verlet), "integrator semi_implicit_euler or verlet");
    WorldSettings s = settings();
    s.integrator = semiImplicit ? Integrator::SemiImplicitEuler : Integrator::Verlet;
    World world(s);
    BodyDef def = sphereDef(0.5);
    def.position = Vec3(0, 10, 0);
    def.gravityScale = 0.5;
    Body b = world.createBody(def);
    constexpr int kSteps = 60;
    for (int i = 0; i < kSteps; ++i) world.step();
    const double g = 0.5 * 9.81, h = world.settings().timeStep;
    const double fallen = semiImplicit ? g * h * h * kSteps * (kSteps + 1) / 2 : g * (kSteps * h) * (kSteps * h) / 2;
    // 1e-9 for a double engine; a float one rounds y (about 10) at each step.
    EXPECT_NEAR(b.position().y(), 10.0 - fallen, 1e-9 + rounding(10, kSteps));
    EXPECT_NEAR(b.linearVelocity().y(), -g * kSteps * h, 1e-9 + rounding(g, kSteps));
}

// Kinematic bodies move at their set velocity, untouched by gravity and forces (spinning about Y,
// or about Z in a planar world).
TEST_P(DynamicsTest, KinematicBodyIgnoresGravityAndForces) {
    ANYPHYS_REQUIRE(caps().bodyTypes.count(BodyType::Kinematic), "kinematic bodies");
    World world(settings());
    BodyDef def = sphereDef(0.5);
    def.type = BodyType::Kinematic;
    def.linearVelocity = Vec3(1, 0, 0);
    const Vec3 axis = planarWorld() ? Vec3::UnitZ() : Vec3::UnitY();
    def.angularVelocity = 0.5 * axis;
    Body k = world.createBody(def);
    k.applyForce(Vec3(0, 100, 0));
    for (int i = 0; i < 60; ++i) world.step();
    // 1e-9 for a double engine; a float one rounds position and angle at each of 60 steps.
    EXPECT_NEAR((k.position() - Vec3(1, 0, 0)).norm(), 0, 1e-9 + rounding(1, 60));
    EXPECT_NEAR((k.linearVelocity() - Vec3(1, 0, 0)).norm(), 0, 1e-12 + rounding(1, 2));
    EXPECT_NEAR(k.orientation().angularDistance(Quat(Eigen::AngleAxisd(0.5, axis))), 0, 1e-9 + rounding(0.5, 60));
}

// Static bodies never move, even struck by a heavy body: a 1 000 kg ball at 10 m/s hits a static
// box and is stopped by it (a backend that gave the box a mass would let it be pushed away).
TEST_P(DynamicsTest, StaticBodyStaysPutWhenStruck) {
    World world(weightless());
    BodyDef wall;
    wall.type = BodyType::Static;
    wall.shape = ShapeDef::box(Vec3(0.5, 1, 1));
    wall.position = Vec3(3, 0, 0);
    wall.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
    Body box = world.createBody(wall);
    BodyDef ball;
    ball.shape = ShapeDef::sphere(0.25);
    ball.mass = 1000.0;
    ball.linearVelocity = Vec3(10, 0, 0);
    Body b = world.createBody(ball);
    for (int i = 0; i < 60; ++i) world.step();
    EXPECT_EQ(box.position(), Vec3(3, 0, 0));
    // Not turned: only the engine's rounding of the stored orientation (an angle, in float).
    EXPECT_NEAR(box.orientation().angularDistance(wall.orientation), 0.0, 1e-15 + rounding(0.3, 2));
    EXPECT_EQ(box.linearVelocity(), Vec3::Zero());
    // The ball never got past the box's near face (x = 2.5 at the middle, tilted 0.3 rad).
    EXPECT_LT(b.position().x(), 3.0);
    EXPECT_LT(b.linearVelocity().x(), 1.0);  // stopped or thrown back, not carried on
}

// The accumulator takes as many fixed steps as fit and keeps the remainder.
TEST_P(DynamicsTest, FixedStepAccumulator) {
    WorldSettings s = settings();
    s.timeStep = 0.01;
    s.maxStepsPerUpdate = 5;
    World world(s);
    EXPECT_EQ(world.update(0.035), 3);
    EXPECT_NEAR(world.interpolationAlpha(), 0.5, 1e-9);
    EXPECT_EQ(world.update(0.005), 1);
    EXPECT_EQ(world.update(1.0), 5);  // capped: a slow frame cannot snowball
    EXPECT_LT(world.interpolationAlpha(), 1.0);
    EXPECT_EQ(world.stepCount(), 9u);
}

// Effects are derived from content unless declared; a declared set is obeyed exactly.
TEST_P(DynamicsTest, EffectsDerivedOrDeclared) {
    World derived(settings());
    EXPECT_FALSE(derived.activeEffects().has(Effect::Gravity));  // no bodies yet
    derived.createBody(sphereDef(0.5));
    EXPECT_TRUE(derived.activeEffects().has(Effect::Gravity));
    EXPECT_FALSE(derived.activeEffects().has(Effect::Damping));

    WorldSettings s = settings();
    s.effects = Effects::none();  // gravity declared off
    World declared(s);
    Body b = declared.createBody(sphereDef(0.5));
    for (int i = 0; i < 10; ++i) declared.step();
    EXPECT_EQ(b.position(), Vec3::Zero());
    EXPECT_THROW(b.applyForce(Vec3(1, 0, 0)), Error);  // userForces not declared
}

ANYPHYS_CONTRACT_SUITE(DynamicsTest);

}  // namespace
}  // namespace anyphys::test
