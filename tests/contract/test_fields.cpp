// Force fields (buoyancy, drag, wind, explosion) against closed forms, on every backend: the 3D
// suite where the backend has 3D worlds, the planar suite everywhere (a planar world still has 3D
// shapes, so volumes, masses and areas are those of the 3D bodies and the closed forms are the same).
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "anyphys/fields/field_forces.hpp"
#include "contract_fixture.hpp"
#include "contact_helpers.hpp"

namespace anyphys::test {
namespace {

// ---- shared cases, run in a 3D and in a planar world ------------------------------------------

// A flat box (2 x 0.5 x 2 m, wide enough to float upright: its metacentre is above its centre of
// mass) of density 600 in water settles with draft 600 / 1000 of its height, 0.3 m.
void boxSettlesAtItsDraft(WorldSettings s) {
    World world(s);
    world.addField(FieldDef::buoyancy(1000.0, Vec3(0, 1, 0), 0.0, 1.0, 0.5));
    BodyDef def;
    def.shape = ShapeDef::box(Vec3(1.0, 0.25, 1.0));
    def.density = 600.0;
    def.position = Vec3(0, 0.0, 0);  // half under: 0.05 m too high
    def.allowSleep = false;
    Body box = world.createBody(def);
    const double draft = 0.6 * 0.5;
    for (int i = 0; i < 60 * 30; ++i) world.step();
    const double centre = -draft + 0.25;
    // Tolerance: the heave is damped at f c / 2 = 0.3 / s (f = 0.6 wet, c = 1 / s), so after 30 s
    // e^-9 of the 5 cm start is left (6e-6 m); the discrete equilibrium is the exact one (the
    // forces balance at rest whatever the step). 1e-4 m leaves room for a float engine's rounding.
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": box centre " << box.position().y()
              << " m, closed form " << centre << " m, error " << box.position().y() - centre << " m\n";
    EXPECT_NEAR(box.position().y(), centre, 1e-4);
    EXPECT_NEAR(box.linearVelocity().norm(), 0.0, 1e-4);
}

// Small heave of that box with no drag: period 2 pi sqrt(d / g), d the draft (the stiffness
// rho_w g A over the mass rho_b A H; the water's added mass is not modelled).
void boxHeavesAtItsPeriod(WorldSettings s) {
    World world(s);
    world.addField(FieldDef::buoyancy(1000.0));
    BodyDef def;
    def.shape = ShapeDef::box(Vec3(1.0, 0.25, 1.0));
    def.density = 600.0;
    const double draft = 0.3, equilibrium = 0.25 - draft;
    def.position = Vec3(0, equilibrium + 0.02, 0);
    def.allowSleep = false;
    Body box = world.createBody(def);
    std::vector<double> crossings;  // upward crossings of the equilibrium, interpolated
    double previous = box.position().y() - equilibrium;
    while (world.time() < 8.0) {
        world.step();
        const double y = box.position().y() - equilibrium;
        if (previous < 0.0 && y >= 0.0) crossings.push_back(world.time() - s.timeStep * y / (y - previous));
        previous = y;
    }
    ASSERT_GE(crossings.size(), 4u);
    const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    const double expected = 2 * kPi * std::sqrt(draft / kG);
    // Tolerance: semi-implicit Euler shortens a harmonic period by (w h)^2 / 24 = 3.8e-4 at
    // w = 5.7 rad/s, h = 1/60 s (measured: -3.78e-4 on every backend); interpolating crossings linearly is off by less than (w h)^2 / 8
    // of a step per crossing. 2e-3 relative holds both with room for the engines' rounding.
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": heave period " << period << " s, closed form "
              << expected << " s, relative error " << (period - expected) / expected << "\n";
    EXPECT_NEAR(period, expected, 2e-3 * expected);
}

// A sphere of density 300 floats with 30 % of its volume under: the cap of height h with
// pi h^2 (3r - h) / 3 = 0.3 * 4/3 pi r^3.
void sphereFloatsAtArchimedesDepth(WorldSettings s) {
    World world(s);
    world.addField(FieldDef::buoyancy(1000.0, Vec3(0, 1, 0), 0.0, 2.0, 1.0));
    const double r = 0.5;
    BodyDef def;
    def.shape = ShapeDef::sphere(r);
    def.density = 300.0;
    def.position = Vec3(0, 0.3, 0);
    def.allowSleep = false;
    Body ball = world.createBody(def);
    for (int i = 0; i < 60 * 30; ++i) world.step();
    double lo = 0.0, hi = 2 * r;  // the cap height, by bisection
    for (int i = 0; i < 200; ++i) {
        const double h = 0.5 * (lo + hi);
        (kPi * h * h * (3 * r - h) / 3 < 0.3 * 4.0 / 3.0 * kPi * r * r * r ? lo : hi) = h;
    }
    const double centre = r - lo;
    // Tolerance as for the box: the motion is damped by c f / 2 = 0.3 / s, e^-9 left after 30 s.
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": sphere centre " << ball.position().y()
              << " m, closed form " << centre << " m, error " << ball.position().y() - centre << " m\n";
    EXPECT_NEAR(ball.position().y(), centre, 1e-4);
}

// Air drag: a sphere falling from rest reaches v_t = sqrt(2 m g / (rho Cd A)) (v = v_t tanh(g t / v_t)).
void sphereReachesTerminalSpeed(WorldSettings s) {
    World world(s);
    world.addField(FieldDef::drag(1.2));
    const double r = 0.1, density = 100.0;
    BodyDef def;
    def.shape = ShapeDef::sphere(r);
    def.density = density;
    Body ball = world.createBody(def);
    const double m = density * 4.0 / 3.0 * kPi * r * r * r;
    const double terminal = std::sqrt(2 * m * kG / (1.2 * 0.47 * kPi * r * r));
    for (int i = 0; i < 60 * 15; ++i) world.step();
    const double v = -ball.linearVelocity().y();
    // Tolerance: after 15 s = 6.8 v_t / g, 1 - tanh leaves 2e-6 relative; the discrete fixed point
    // v = v + h (g - k v^2) is the exact v_t. 1e-4 relative leaves room for a float engine.
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": terminal speed " << v << " m/s, closed form "
              << terminal << " m/s, relative error " << (v - terminal) / terminal << "\n";
    EXPECT_NEAR(v, terminal, 1e-4 * terminal);
}

// Wind of speed w on a free body at rest (no gravity): u = w - v obeys u' = -k u^2, so
// v(t) = w k w t / (1 + k w t), k = rho Cd A / (2 m): up to w and never past it.
void windPushesUpToItsSpeed(WorldSettings s) {
    s.gravity = Vec3::Zero();
    World world(s);
    const double w = 6.0;
    world.addField(FieldDef::wind(Vec3(w, 0, 0), 1.2));
    const double r = 0.5, density = 1.0;
    BodyDef def;
    def.shape = ShapeDef::sphere(r);
    def.density = density;
    def.allowSleep = false;
    Body ball = world.createBody(def);
    const double m = density * 4.0 / 3.0 * kPi * r * r * r;
    const double k = 1.2 * 0.47 * kPi * r * r / (2 * m);
    double fastest = 0.0;
    for (int i = 0; i < 60 * 10; ++i) {
        world.step();
        fastest = std::max(fastest, ball.linearVelocity().x());
    }
    const double kwt = k * w * world.time();
    const double expected = w * kwt / (1 + kwt);
    // Tolerance: explicit forces over a step (semi-implicit Euler) make 1/u grow by
    // h k^2 integral(u) more than exactly, so u is off by u h k ln(1 + k w t) relative: 1.2e-3 m/s
    // here. 5e-3 m/s holds it with room for the engines' rounding.
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": speed after 10 s " << ball.linearVelocity().x()
              << " m/s, closed form " << expected << " m/s, error " << ball.linearVelocity().x() - expected << " m/s\n";
    EXPECT_NEAR(ball.linearVelocity().x(), expected, 5e-3);
    EXPECT_LE(fastest, w);
    EXPECT_NEAR(ball.linearVelocity().y(), 0.0, 1e-12);
}

// An explosion gives each body within its radius impulse (1 - d / R) along the line from the
// centre through the body's nearest surface point, d that point's distance: the bodies' total
// momentum is the sum of those impulses; bodies beyond the radius get nothing.
void explosionGivesTheSumOfItsImpulses(WorldSettings s, double unitRoundoff) {
    s.gravity = Vec3::Zero();
    World world(s);
    const FieldDef blast = FieldDef::explosion(Vec3(0, 0, 0), 0.25, 500.0, 5.0);
    world.addField(blast);
    const double r = 0.25;
    const std::vector<Vec3> places{Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(-2, -2, 0), Vec3(2.5, 0.5, 0), Vec3(0, -6, 0)};
    std::vector<Body> balls;
    for (const Vec3& p : places) {
        BodyDef def;
        def.shape = ShapeDef::sphere(r);
        def.position = p;
        balls.push_back(world.createBody(def));
    }
    for (int i = 0; i < 30; ++i) world.step();
    Vec3 momentum = Vec3::Zero(), impulses = Vec3::Zero();
    double largest = 0.0;
    for (std::size_t i = 0; i < balls.size(); ++i) {
        const double d = places[i].norm() - r;
        const Vec3 expected = places[i].normalized() * explosionImpulse(blast, d);
        const Vec3 p = balls[i].massProperties().mass * balls[i].linearVelocity();
        // Tolerance: an impulse is one multiply-add on the velocity: rounding of the engine.
        EXPECT_NEAR((p - expected).norm(), 0.0, 1e-9 + 4 * unitRoundoff * 500.0) << "body " << i;
        EXPECT_NEAR(balls[i].angularVelocity().norm(), 0.0, 1e-9) << "body " << i;  // through the centre of mass
        momentum += p;
        impulses += expected;
        largest = std::max(largest, (p - expected).norm());
    }
    EXPECT_EQ(balls.back().linearVelocity().norm(), 0.0);  // beyond the radius
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": momentum " << formatVec3(momentum)
              << " N s, sum of impulses " << formatVec3(impulses) << " N s, largest body error " << largest << " N s\n";
    EXPECT_NEAR((momentum - impulses).norm(), 0.0, 1e-9 + 20 * unitRoundoff * 500.0);
}

// Two balls (radius 0.25 m) placed at `first` and `second`, after 10 steps of an explosion at the
// origin (500 N s, radius 5 m) beside a static slab of half extents (0.1, 1, 1) at `slabCentre`;
// the caller turns gravity off.
struct TwoBalls {
    Body first, second;
};
TwoBalls explodeBesideASlab(World& world, const Vec3& slabCentre, const Vec3& first, const Vec3& second) {
    world.addField(FieldDef::explosion(Vec3(0, 0, 0), 0.0, 500.0, 5.0));
    BodyDef slab;
    slab.type = BodyType::Static;
    slab.shape = ShapeDef::box(Vec3(0.1, 1.0, 1.0));
    slab.position = slabCentre;
    world.createBody(slab);
    BodyDef def;
    def.shape = ShapeDef::sphere(0.25);
    def.position = first;
    Body a = world.createBody(def);
    def.position = second;
    Body b = world.createBody(def);
    for (int i = 0; i < 10; ++i) world.step();
    return {a, b};
}

// Static geometry between the centre and a body shields it (a ray cast); a body in the open
// beside it is pushed.
void wallShieldsFromExplosion(WorldSettings s) {
    s.gravity = Vec3::Zero();
    World world(s);
    const auto [behind, open] = explodeBesideASlab(world, Vec3(1.5, 0, 0), Vec3(3, 0, 0), Vec3(-3, 0, 0));
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": behind the wall " << behind.linearVelocity().norm()
              << " m/s, in the open " << open.linearVelocity().norm() << " m/s\n";
    EXPECT_EQ(behind.linearVelocity().norm(), 0.0);
    EXPECT_EQ(behind.angularVelocity().norm(), 0.0);
    EXPECT_LT(open.linearVelocity().x(), -1.0);
}

// An explosion centred exactly on a static face (a blast on the ground) pushes what lies in front
// of the face and not what lies behind it, on every backend. The shielding rays start on the
// surface, where the engines disagree: cast from there as they were, ODE met the face heading out
// (the front ball stayed put) and Bullet and Box2D missed it heading in (the back ball flew).
void explosionOnAFacePushesOnlyItsSide(WorldSettings s) {
    s.gravity = Vec3::Zero();
    World world(s);
    // The slab's face x = 0 holds the centre.
    const auto [front, back] = explodeBesideASlab(world, Vec3(-0.1, 0, 0), Vec3(2, 0.5, 0), Vec3(-2, 0.5, 0));
    std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": in front of the face " << front.linearVelocity().norm()
              << " m/s, behind it " << back.linearVelocity().norm() << " m/s\n";
    EXPECT_GT(front.linearVelocity().x(), 1.0);
    EXPECT_EQ(back.linearVelocity().norm(), 0.0);
}

// A field absurd for the world (a wind at 1e308 m/s, air of density 1e300, an explosion of
// 1e308 N s) is refused, naming what, before an engine integrates an infinite push (ODE aborted
// inside its integrator on such a wind: found by the API fuzzer), and the world is left as it was.
void absurdFieldsAreRefused(WorldSettings s) {
    s.gravity = Vec3::Zero();
    World world(s);
    BodyDef def = sphereDef(0.5);
    def.linearVelocity = Vec3(3, 0, 0);
    def.allowSleep = false;
    Body ball = world.createBody(def);
    const auto refusal = [](const std::function<void()>& call) -> Error {
        try {
            call();
        } catch (const Error& e) {
            return e;
        }
        ADD_FAILURE() << "accepted";
        return Error("");
    };
    const Error wind = refusal([&] { world.addField(FieldDef::wind(Vec3(1e308, 0, 0))); });
    EXPECT_EQ(wind.field(), "FieldDef.velocity") << wind.what();
    EXPECT_TRUE(world.fields().empty());

    for (const FieldDef& field : {FieldDef::drag(1e300), FieldDef::explosion(Vec3(0.6, 0, 0), 0.0, 1e308, 2.0)}) {
        world.addField(field);
        const Error push = refusal([&] { world.step(); });
        std::cout << "  " << s.backend << (s.planar ? " planar" : "") << ": " << push.what() << "\n";
        EXPECT_EQ(push.kind(), ErrorKind::InvalidArgument);
        EXPECT_EQ(push.field(), "fields");
        EXPECT_NE(std::string(push.what()).find("maxSpeed"), std::string::npos) << push.what();
        // Nothing was handed to the engine: the step did not happen.
        EXPECT_EQ(world.time(), 0.0);
        EXPECT_EQ(ball.position(), def.position);
        EXPECT_EQ(ball.linearVelocity(), def.linearVelocity);
        world.clearFields();
    }
    world.step();  // still a working world: the ball coasts at 3 m/s
    EXPECT_NEAR(ball.position().x(), 3.0 * s.timeStep, 1e-6);
}

// ---- the 3D suite -------------------------------------------------------------------------------

class FieldsTest : public ContractTest {};

TEST_P(FieldsTest, FloatingBoxSettlesAtDraft) { boxSettlesAtItsDraft(settings()); }
TEST_P(FieldsTest, FloatingBoxHeavePeriod) { boxHeavesAtItsPeriod(settings()); }
TEST_P(FieldsTest, SphereFloatsAtArchimedesDepth) { sphereFloatsAtArchimedesDepth(settings()); }
TEST_P(FieldsTest, TerminalSpeedInAir) { sphereReachesTerminalSpeed(settings()); }
TEST_P(FieldsTest, WindPushesUpToItsSpeed) { windPushesUpToItsSpeed(settings()); }
TEST_P(FieldsTest, ExplosionMomentumIsTheSumOfImpulses) { explosionGivesTheSumOfItsImpulses(settings(), caps().unitRoundoff); }
TEST_P(FieldsTest, WallShieldsFromExplosion) { wallShieldsFromExplosion(settings()); }
TEST_P(FieldsTest, ExplosionOnAFacePushesOnlyItsSide) { explosionOnAFacePushesOnlyItsSide(settings()); }
TEST_P(FieldsTest, AbsurdFieldsAreRefusedBeforeTheEngine) { absurdFieldsAreRefused(settings()); }

// A tilted floating box: buoyancy acts at the centre of buoyancy, so the torque rights a stable
// hull (the flat box) and its final pose is level at the same draft.
// Draft of the 0.5 m tall box at 600 kg/m^3 in water: 0.6 x 0.5 = 0.3 m, its centre 0.05 m under
// the surface. Tilted by 0.2 rad about `axis`, released at that height, run 40 s.
void tiltedFlatBoxRightsItself(const WorldSettings& s, const Vec3& axis) {
    World world(s);
    world.addField(FieldDef::buoyancy(1000.0, Vec3(0, 1, 0), 0.0, 1.0, 1.0));
    BodyDef def;
    def.shape = ShapeDef::box(Vec3(1.0, 0.25, 1.0));
    def.density = 600.0;
    def.position = Vec3(0, -0.05, 0);
    def.orientation = Quat(Eigen::AngleAxisd(0.2, axis.normalized()));
    def.allowSleep = false;
    Body box = world.createBody(def);
    for (int i = 0; i < 60 * 40; ++i) world.step();
    const Vec3 up = box.orientation() * Vec3::UnitY();
    EXPECT_GT(up.y(), 1.0 - 1e-6);  // level to within 1.4 mrad
    EXPECT_NEAR(box.position().y(), 0.25 - 0.3, 1e-4);
}

TEST_P(FieldsTest, TiltedFlatBoxRightsItself) { tiltedFlatBoxRightsItself(settings(), Vec3(1, 0, 1)); }

// The effects: a field's effect is derived while the world holds one (and listed), and a world
// without fields derives none of them.
TEST_P(FieldsTest, EffectsFollowTheFields) {
    World world(settings());
    BodyDef def = sphereDef(0.5);
    world.createBody(def);
    const Effects fields = Effects(Effect::Buoyancy) | Effects(Effect::Drag) | Effects(Effect::Wind) | Effects(Effect::Explosion);
    EXPECT_TRUE((world.activeEffects() & fields).empty());
    world.addField(FieldDef::drag());
    world.addField(FieldDef::explosion(Vec3::Zero(), 1.0, 1.0, 1.0));
    EXPECT_TRUE(world.activeEffects().has(Effect::Drag));
    EXPECT_TRUE(world.activeEffects().has(Effect::Explosion));
    EXPECT_FALSE(world.activeEffects().has(Effect::Buoyancy));
    EXPECT_FALSE(world.activeEffects().has(Effect::UserForces));  // the layer's, not the user's
    EXPECT_EQ(world.fields().size(), 2u);
    world.clearFields();
    EXPECT_TRUE((world.activeEffects() & fields).empty());
    // Declared effects that exclude a field's refuse it, changing nothing.
    WorldSettings declared = settings();
    declared.effects = Effects(Effect::Gravity);
    World strict(declared);
    EXPECT_THROW(strict.addField(FieldDef::wind(Vec3(1, 0, 0))), Error);
    EXPECT_TRUE(strict.fields().empty());
    try {
        world.addField(FieldDef::explosion(Vec3::Zero(), 0.0, 1.0, -1.0));
        ADD_FAILURE() << "a negative radius was accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "FieldDef.radius: must be > 0, got -1");
    }
    EXPECT_TRUE(world.fields().empty());
}

// Declared effects: a field whose effect is declared runs; the same field with its effect
// dropped from the declaration is refused (above), and a field stage never runs for a world
// without fields (the force hook is not even installed: see the benchmark in bench/).
TEST_P(FieldsTest, DeclaredDragRuns) {
    WorldSettings s = settings();
    s.effects = Effects(Effect::Gravity) | Effects(Effect::Drag);
    World world(s);
    world.addField(FieldDef::drag(1.2));
    BodyDef def;
    def.shape = ShapeDef::sphere(0.1);
    def.density = 100.0;
    Body ball = world.createBody(def);
    for (int i = 0; i < 60 * 3; ++i) world.step();
    // Slower than free fall (29.4 m/s after 3 s) by the drag.
    EXPECT_LT(-ball.linearVelocity().y(), 20.0);
}

ANYPHYS_CONTRACT_SUITE(FieldsTest);

// ---- the planar suite ---------------------------------------------------------------------------

class PlanarFieldsTest : public ContractTest {
protected:
    bool planarTest() const override { return true; }
};

TEST_P(PlanarFieldsTest, FloatingBoxSettlesAtDraft) { boxSettlesAtItsDraft(settings()); }
TEST_P(PlanarFieldsTest, FloatingBoxHeavePeriod) { boxHeavesAtItsPeriod(settings()); }
TEST_P(PlanarFieldsTest, SphereFloatsAtArchimedesDepth) { sphereFloatsAtArchimedesDepth(settings()); }
TEST_P(PlanarFieldsTest, TerminalSpeedInAir) { sphereReachesTerminalSpeed(settings()); }
TEST_P(PlanarFieldsTest, WindPushesUpToItsSpeed) { windPushesUpToItsSpeed(settings()); }
TEST_P(PlanarFieldsTest, ExplosionMomentumIsTheSumOfImpulses) { explosionGivesTheSumOfItsImpulses(settings(), caps().unitRoundoff); }
TEST_P(PlanarFieldsTest, WallShieldsFromExplosion) { wallShieldsFromExplosion(settings()); }
TEST_P(PlanarFieldsTest, ExplosionOnAFacePushesOnlyItsSide) { explosionOnAFacePushesOnlyItsSide(settings()); }
TEST_P(PlanarFieldsTest, AbsurdFieldsAreRefusedBeforeTheEngine) { absurdFieldsAreRefused(settings()); }
TEST_P(PlanarFieldsTest, TiltedFlatBoxRightsItself) { tiltedFlatBoxRightsItself(settings(), Vec3(0, 0, 1)); }

TEST_P(PlanarFieldsTest, OutOfPlaneFieldsAreRefused) {
    World world(settings());
    EXPECT_THROW(world.addField(FieldDef::wind(Vec3(1, 0, 1))), Error);
    EXPECT_THROW(world.addField(FieldDef::explosion(Vec3(0, 0, 1), 0.0, 1.0, 1.0)), Error);
    EXPECT_TRUE(world.fields().empty());
}

ANYPHYS_CONTRACT_SUITE(PlanarFieldsTest);

}  // namespace
}  // namespace anyphys::test
