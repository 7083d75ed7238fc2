// Bullet-only checks: the escape hatch, per-pair materials from the layer's table (not Bullet's
// product), isolation of worlds, both solvers, lifetimes and damping.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"

namespace anyphys::test {
namespace {

BodyDef ground(const std::string& material = "") { return groundDef(material); }

BodyDef box(const Vec3& at, const std::string& material = "") {
    return boxDef("", Vec3(0.25, 0.25, 0.25), at, material);
}

/// Friction of every contact point in the Bullet world (what the solver will use).
std::vector<double> pointFrictions(World& world) {
    std::vector<double> out;
    btDispatcher* dispatcher = world.native<btDiscreteDynamicsWorld>()->getDispatcher();
    for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
        btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
        for (int i = 0; i < manifold->getNumContacts(); ++i) out.push_back(manifold->getContactPoint(i).m_combinedFriction);
    }
    return out;
}

TEST(BulletBackend, EscapeHatchReturnsBulletObjects) {
    World world(backendSettings("bullet"));
    Body floor = world.createBody(ground());
    Body b = world.createBody(box(Vec3(0, 2, 0)));
    auto* dynamics = world.native<btDiscreteDynamicsWorld>();
    ASSERT_NE(dynamics, nullptr);
    EXPECT_EQ(static_cast<btDynamicsWorld*>(dynamics), world.native<btDynamicsWorld>());
    EXPECT_EQ(dynamics->getNumCollisionObjects(), 2);
    btRigidBody* rigid = b.native<btRigidBody>();
    ASSERT_NE(rigid, nullptr);
    // The same object the world holds, with the layer's mass (125 kg: 0.5 m cube of 1000 kg/m^3).
    EXPECT_TRUE(dynamics->getCollisionObjectArray().findLinearSearch(rigid) < dynamics->getNumCollisionObjects());
    EXPECT_NEAR(1.0 / rigid->getInvMass(), 125.0, 1e-3);  // float mass
    EXPECT_TRUE(floor.native<btRigidBody>()->isStaticObject());
    // Any other type: nothing.
    EXPECT_EQ(world.native<int>(), nullptr);
    EXPECT_EQ(world.native<btRigidBody>(), nullptr);
    EXPECT_EQ(b.native<btDiscreteDynamicsWorld>(), nullptr);
    EXPECT_EQ(b.native<double>(), nullptr);
}

// Friction 0.2 on the box and 0.8 on the floor: the layer's geometric mean is 0.4, Bullet's
// product would be 0.16. On a 35 deg slope the box slides at g (sin - 0.4 cos) = 2.41 m/s^2
// (0.16 would give 4.34).
TEST(BulletBackend, PairFrictionIsTheLayersValueNotBulletsProduct) {
    MaterialLibrary materials;
    materials.add("box", Material{0.2, 0.0, 1000.0});
    materials.add("floor", Material{0.8, 0.0, 1000.0});
    World world(backendSettings("bullet"), materials);
    const double angle = 35 * std::numbers::pi / 180;
    const Quat tilt(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
    const Vec3 normal = tilt * Vec3::UnitY();
    BodyDef slope = ground("floor");
    slope.shape = ShapeDef::plane(normal, 0.0);
    world.createBody(slope);
    BodyDef def = box(normal * 0.25, "box");
    def.orientation = tilt;
    Body b = world.createBody(def);
    const Vec3 downhill = -(tilt * Vec3::UnitX());
    for (int i = 0; i < 30; ++i) world.step();
    // Every point carries 0.4 exactly (as float): the value the solver uses.
    const std::vector<double> mu = pointFrictions(world);
    ASSERT_FALSE(mu.empty());
    for (double m : mu) EXPECT_EQ(m, static_cast<double>(static_cast<btScalar>(std::sqrt(0.2 * 0.8))));
    const double v0 = b.linearVelocity().dot(downhill);
    for (int i = 0; i < 60; ++i) world.step();
    const double a = b.linearVelocity().dot(downhill) - v0;  // over 1 s
    const double exact = kG * (std::sin(angle) - 0.4 * std::cos(angle));
    // 5 %, the contract's bound for kinetic friction; the product (0.16) would be 80 % off.
    EXPECT_NEAR(a, exact, 0.05 * exact);
}

// Two Bullet worlds in one process with different tables for the same material names: each
// applies its own (nothing process-global leaks between them), stepping interleaved.
TEST(BulletBackend, TwoWorldsWithDifferentTablesDoNotInterfere) {
    const auto library = [](double mu) {
        MaterialLibrary m;
        m.add("box", Material{mu, 0.0, 1000.0});
        m.add("floor", Material{mu, 0.0, 1000.0});
        return m;
    };
    World slippery(backendSettings("bullet"), library(0.1)), grippy(backendSettings("bullet"), library(0.5));
    std::vector<Body> boxes;
    for (World* w : {&slippery, &grippy}) {
        w->createBody(ground("floor"));
        BodyDef def = box(Vec3(0, 0.25, 0), "box");
        def.linearVelocity = Vec3(6, 0, 0);
        boxes.push_back(w->createBody(def));
    }
    for (int i = 0; i < 420; ++i) {  // 7 s: past the slowest stop, 6 / (0.1 g) = 6.1 s
        slippery.step();
        grippy.step();
        if (i == 10) {
            for (double m : pointFrictions(slippery)) EXPECT_FLOAT_EQ(m, 0.1);
            for (double m : pointFrictions(grippy)) EXPECT_FLOAT_EQ(m, 0.5);
        }
    }
    // Slide distance v0^2 / (2 mu g): 18.3 m and 3.67 m. 5 %, as the contract's slide test:
    // stepping shifts the stop by about mu g dt / v0 of the distance (1.4 % at mu 0.5).
    for (int k = 0; k < 2; ++k) {
        const double exact = 36.0 / (2 * (k == 0 ? 0.1 : 0.5) * kG);
        EXPECT_NEAR(boxes[k].position().x(), exact, 0.05 * exact);
    }
}

// Restitution is the layer's too (max rule: 0.7 with a dead floor) and only above the threshold.
TEST(BulletBackend, PairRestitutionIsTheLayersValue) {
    MaterialLibrary materials;
    materials.add("ball", Material{0.5, 0.7, 1000.0});
    World world(backendSettings("bullet"), materials);
    world.createBody(ground());
    BodyDef def;
    def.shape = ShapeDef::sphere(0.25);
    def.position = Vec3(0, 0.25 + 1.0, 0);
    def.material = "ball";
    Body ball = world.createBody(def);
    double fastestUp = 0;
    for (int i = 0; i < 40; ++i) {
        world.step();
        fastestUp = std::max(fastestUp, ball.linearVelocity().y());
    }
    // Impact at sqrt(2 g 1) = 4.43 m/s, rebound 0.7 of it = 3.10 m/s. 5 %: the impact falls inside
    // a step, so the solver sees the speed up to g dt (0.16 m/s, 3.7 %) off.
    EXPECT_NEAR(fastestUp, 0.7 * std::sqrt(2 * kG), 0.05 * 0.7 * std::sqrt(2 * kG));
}

// Both solvers keep a box resting on the ground: sequential impulses (pgs) and Bullet's MLCP
// with the Dantzig solver (direct).
TEST(BulletBackend, BothSolversHoldABoxAtRest) {
    for (Solver solver : {Solver::ProjectedGaussSeidel, Solver::Direct}) {
        SCOPED_TRACE(std::string(toString(solver)));
        WorldSettings s = backendSettings("bullet");
        s.solver = solver;
        World world(s);
        world.createBody(ground());
        BodyDef def = box(Vec3(0.3, 0.25, -0.2));
        def.allowSleep = false;  // keep it simulated all along
        Body b = world.createBody(def);
        for (int i = 0; i < 180; ++i) world.step();
        // 5 mm (the default linearSlop) of sinking or sideways drift over 3 s; resting contact
        // converges to the box's half height within Bullet's split-impulse depth (5 mm).
        EXPECT_NEAR(b.position().y(), 0.25, 0.005);
        EXPECT_LT((b.position() - Vec3(0.3, b.position().y(), -0.2)).norm(), 0.005);
        EXPECT_LT(b.linearVelocity().norm(), 0.01);  // at rest: far under the sleep threshold x 4
    }
}

// Damping: Bullet's v *= (1 - d)^dt with d = 1 - exp(-c) is exactly v0 exp(-c t).
TEST(BulletBackend, DampingMatchesExponentialDecay) {
    WorldSettings s = backendSettings("bullet");
    s.gravity = Vec3::Zero();
    World world(s);
    BodyDef def;
    def.shape = ShapeDef::sphere(0.5);
    def.linearVelocity = Vec3(5, 0, 0);
    def.angularVelocity = Vec3(0, 0, 3);
    def.linearDamping = 0.8;
    def.angularDamping = 1.5;
    Body b = world.createBody(def);
    for (int i = 0; i < 120; ++i) world.step();
    // 1e-5 relative: float rounding of 120 multiplications by a factor near 1 (each ~6e-8) and
    // of Bullet's powf; the method itself is exact.
    EXPECT_NEAR(b.linearVelocity().x(), 5.0 * std::exp(-0.8 * 2.0), 1e-5 * 5.0);
    EXPECT_NEAR(b.angularVelocity().z(), 3.0 * std::exp(-1.5 * 2.0), 1e-5 * 3.0);
}

// Worlds and bodies created and destroyed in mixed orders, a Bullet world next to a native one,
// events on: nothing leaks or dangles (run under LeakSanitizer in the sanitizer build).
TEST(BulletBackend, MixedLifetimesNextToANativeWorld) {
    auto a = std::make_unique<World>(backendSettings("bullet"));
    WorldSettings nativeSettings;
    nativeSettings.backend = "native";
    auto n = std::make_unique<World>(nativeSettings);
    auto b = std::make_unique<World>(backendSettings("bullet"));
    std::vector<Body> inA, inB;
    for (World* w : {a.get(), n.get(), b.get()}) w->createBody(ground());
    for (int i = 0; i < 6; ++i) {
        inA.push_back(a->createBody(box(Vec3(i, 1 + 0.1 * i, 0))));
        inB.push_back(b->createBody(box(Vec3(0, 1 + 0.6 * i, 0))));  // a falling stack
        n->createBody(box(Vec3(i, 1, 0)));
    }
    BodyDef compound;
    compound.shape = ShapeDef::compound({ShapeDef::sphere(0.2).placed(Vec3(0.3, 0, 0)), ShapeDef::box(Vec3(0.1, 0.2, 0.1))});
    compound.position = Vec3(3, 3, 3);
    inA.push_back(a->createBody(compound));
    BodyDef hull;
    hull.shape = ShapeDef::convex({Vec3(0, 0, 0), Vec3(0.4, 0, 0), Vec3(0, 0.4, 0), Vec3(0, 0, 0.4)});
    hull.position = Vec3(-3, 1, 0);
    inB.push_back(b->createBody(hull));
    BodyDef mesh;
    mesh.type = BodyType::Static;
    mesh.shape = ShapeDef::mesh({Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, 0, 1)}, {0, 2, 1});
    mesh.position = Vec3(10, 0.5, 0);
    b->createBody(mesh);
    for (int i = 0; i < 30; ++i) {
        a->step();
        n->step();
        b->step();
    }
    // Destroy bodies in the middle of contact, then a world with bodies still in it.
    b->destroyBody(inB[0]);
    a->destroyBody(inA[3]);
    for (int i = 0; i < 10; ++i) b->step();
    a.reset();  // first-created world first, with its bodies
    for (int i = 0; i < 10; ++i) {
        n->step();
        b->step();
    }
    for (std::size_t i = 1; i < inB.size(); ++i) EXPECT_TRUE(inB[i].position().allFinite());
    n.reset();
    auto c = std::make_unique<World>(backendSettings("bullet"));
    c->createBody(ground());
    b.reset();
    c->step();
}

// Sleeping uses each world's own timeToSleep (Bullet's gDeactivationTime is process-wide): two
// worlds side by side put the same resting box to sleep at their own times.
TEST(BulletBackend, EachWorldSleepsAfterItsOwnTimeToSleep) {
    std::vector<std::unique_ptr<World>> worlds;
    std::vector<Body> boxes;
    for (double t : {0.3, 1.5}) {
        WorldSettings s = backendSettings("bullet");
        s.timeToSleep = t;
        worlds.push_back(std::make_unique<World>(s));
        worlds.back()->createBody(ground());
        boxes.push_back(worlds.back()->createBody(box(Vec3(0, 0.25, 0))));
    }
    double asleepAt[2] = {-1, -1};
    for (int i = 0; i < 180; ++i)
        for (int k = 0; k < 2; ++k) {
            worlds[k]->step();
            if (asleepAt[k] < 0 && !boxes[k].isAwake()) asleepAt[k] = worlds[k]->time();
        }
    // A box built resting is still from the start: it sleeps after timeToSleep, plus one step for
    // its island to follow, plus up to 0.1 s while the contact settles.
    EXPECT_GE(asleepAt[0], 0.3 - 1e-6);
    EXPECT_LE(asleepAt[0], 0.3 + 0.1);
    EXPECT_GE(asleepAt[1], 1.5 - 1e-6);
    EXPECT_LE(asleepAt[1], 1.5 + 0.1);
}

// Kinematic bodies follow their velocity exactly and push dynamic ones.
TEST(BulletBackend, KinematicBodyPushesADynamicOne) {
    WorldSettings s = backendSettings("bullet");
    World world(s);
    world.createBody(ground());
    BodyDef pusher = box(Vec3(-1, 0.25, 0));
    pusher.type = BodyType::Kinematic;
    pusher.linearVelocity = Vec3(1, 0, 0);
    Body k = world.createBody(pusher);
    Body d = world.createBody(box(Vec3(0, 0.25, 0)));
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_NEAR(k.position().x(), 1.0, 1e-9);  // double-precision path, exact up to rounding
    // The pushed box stays ahead of the pusher: its centre at least a box width (0.5 m) in front,
    // less 1 cm of contact overlap.
    EXPECT_GT(d.position().x(), k.position().x() + 0.49);
}

}  // namespace
}  // namespace anyphys::test
