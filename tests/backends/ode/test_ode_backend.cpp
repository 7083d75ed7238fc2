// ODE-specific behaviour of the ODE backend: the escape hatch, solver choice, backend options,
// object lifetimes, damping, per-pair materials and contact impulses.
#include <gtest/gtest.h>
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"
#include "anyphys/scene_objects.hpp"
#include "contact_helpers.hpp"
#include "ode_test_helpers.hpp"
#include "ode_world.hpp"

namespace anyphys {
namespace {

using ode::test::peerOf;

using test::kG;

BodyDef ground(const std::string& material = "") { return test::groundDef(material); }

BodyDef box(const Vec3& at, const std::string& material = "") {
    return test::boxDef("", Vec3(0.5, 0.5, 0.5), at, material);
}

// ODE's convex-convex test returns NaN normals for hull faces that touch exactly; one such
// contact made the step's quaternions NaN and ODE aborted the whole process
// ("!bSafeNormalize4Fault"). The hard-case arch is built of flush wedge blocks.
TEST(OdeBackend, FlushHullFacesNeitherAbortNorPoisonTheState) {
    const CatalogueScene& arch = catalogueScene("hard_arch");
    WorldSettings s = arch.scene.settings;
    s.backend = "ode";
    World world(s, arch.scene.materials);
    const SceneObjects objects = createSceneObjects(world, arch.scene);
    for (int i = 0; i < 60; ++i) world.step();
    for (const Body& b : objects.bodies) {
        const bool finiteState = b.position().allFinite() && b.orientation().coeffs().allFinite() &&
                                 b.linearVelocity().allFinite() && b.angularVelocity().allFinite();
        EXPECT_TRUE(finiteState) << b.name();
    }
}

TEST(OdeBackend, EscapeHatchReturnsEngineObjects) {
    World world(test::backendSettings("ode"));
    Body floor = world.createBody(ground());
    Body cube = world.createBody(box(Vec3(1, 2, 3)));
    dxWorld* w = world.native<dxWorld>();
    ASSERT_NE(w, nullptr);
    EXPECT_NE(world.native<dxSpace>(), nullptr);
    EXPECT_EQ(world.native<int>(), nullptr);  // not an ODE type
    EXPECT_EQ(&peerOf(world), dWorldGetData(w));

    dxBody* b = cube.native<dxBody>();
    ASSERT_NE(b, nullptr);
    EXPECT_EQ(dBodyGetWorld(b), w);
    const dReal* p = dBodyGetPosition(b);
    EXPECT_EQ(Vec3(p[0], p[1], p[2]), Vec3(1, 2, 3));  // the peer frame: a box's centre of mass is its origin
    EXPECT_NE(cube.native<dxGeom>(), nullptr);
    EXPECT_EQ(dGeomGetBody(cube.native<dxGeom>()), b);
    EXPECT_EQ(cube.native<int>(), nullptr);
    EXPECT_EQ(floor.native<dxBody>(), nullptr);  // static bodies are bare geoms in ODE
    EXPECT_NE(floor.native<dxGeom>(), nullptr);
}

// The pgs solver runs dWorldQuickStep and direct runs dWorldStep (counted by the peer); both keep
// a box resting on the ground.
TEST(OdeBackend, QuickStepAndDirectSolverBothHoldABoxAtRest) {
    for (Solver solver : {Solver::ProjectedGaussSeidel, Solver::Direct}) {
        SCOPED_TRACE(std::string(toString(solver)));
        WorldSettings s = test::backendSettings("ode");
        s.solver = solver;
        World world(s);
        world.createBody(ground());
        Body cube = world.createBody(box(Vec3(0, 0.5, 0)));
        for (int i = 0; i < 120; ++i) world.step();
        // 1 cm: the box may settle into the contact surface layer (1 mm) and ODE's correction
        // tolerance; falling through or bouncing off would be decimetres.
        EXPECT_NEAR(cube.position().y(), 0.5, 0.01);
        // 1 mm: nothing pushes it sideways; settling into the contacts shifts it by ~1e-5 m.
        EXPECT_NEAR(cube.position().x(), 0.0, 1e-3);
        const ode::OdeWorld& peer = peerOf(world);
        if (solver == Solver::Direct) {
            EXPECT_EQ(peer.directSteps(), 120u);
            EXPECT_EQ(peer.quickSteps(), 0u);
        } else {
            EXPECT_EQ(peer.directSteps(), 0u);
            EXPECT_EQ(peer.quickSteps(), 120u);
        }
    }
}

// ODE's Dantzig LCP gives up on the stack's resting contacts now and then ("s <= 0"), and left
// alone it leaves the rows it had not reached without force: the stack fell 12.8 m in 10 s. Such
// a step is taken again by quickstep (DirectStepper): it happens (the LCP does fail here), on a
// few steps only (the rest stay direct), and the stack stands. One failed step was enough to
// start the fall: with the fallback, 1 step of the 600 is quickstep's.
TEST(OdeBackend, DirectStepsWhoseLcpGivesUpAreTakenByQuickstep) {
    WorldSettings s = test::backendSettings("ode");
    s.solver = Solver::Direct;
    s.substeps = 1;
    World world(s);
    world.createBody(ground());
    std::vector<Body> boxes;
    for (int i = 0; i < 10; ++i) {
        BodyDef def = box(Vec3(0, 0.5 + i, 0));
        def.allowSleep = false;
        boxes.push_back(world.createBody(def));
    }
    double drift = 0.0;
    for (int i = 0; i < 600; ++i) {
        world.step();
        for (const Body& b : boxes) drift = std::max(drift, std::hypot(b.position().x(), b.position().z()));
    }
    const ode::OdeWorld& peer = peerOf(world);
    std::cout << "[ MEASURED ] ode direct, ten-box stack over 10 s: " << peer.directFallbacks() << " of "
              << peer.directSteps() << " steps fell back to quickstep; largest sideways move " << drift * 1e3 << " mm\n";
    EXPECT_GT(peer.directFallbacks(), 0u);  // the case this covers still arises
    EXPECT_LT(peer.directFallbacks(), peer.directSteps() / 10);  // measured 1 of 600
    EXPECT_EQ(peer.quickSteps(), 0u);  // fallbacks are counted apart
    // The contract suite's stack bound (test_stability.cpp): 1 cm; a toppled stack moves metres.
    EXPECT_LT(drift, 0.01);
}

TEST(OdeBackend, ErpAndCfmOptionsReachTheWorld) {
    WorldSettings s = test::backendSettings("ode");
    s.backendOptions["erp"] = 0.4;
    s.backendOptions["cfm"] = 1e-7;
    World world(s);
    EXPECT_EQ(dWorldGetERP(world.native<dxWorld>()), 0.4);
    EXPECT_EQ(dWorldGetCFM(world.native<dxWorld>()), 1e-7);

    // Without options: erp follows settings.baumgarte.
    WorldSettings plain = test::backendSettings("ode");
    plain.baumgarte = 0.3;
    World defaults(plain);
    EXPECT_EQ(dWorldGetERP(defaults.native<dxWorld>()), 0.3);

    // Out of range: refused by the layer (the range ODE lists for erp), naming the option.
    s.backendOptions["erp"] = 1.5;
    try {
        World bad(s);
        ADD_FAILURE() << "erp 1.5 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("backendOptions.erp"), std::string::npos) << e.what();
    }
    // An option the backend does not list: refused by the layer.
    WorldSettings unknown = test::backendSettings("ode");
    unknown.backendOptions["soft_erp"] = 0.5;
    try {
        World bad(unknown);
        ADD_FAILURE() << "unknown option accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("backend option soft_erp"), std::string::npos) << e.what();
    }
}

// Worlds and bodies created and destroyed in mixed orders, an ODE world next to a native one,
// bodies destroyed while in contact. Under LeakSanitizer this also checks that every geom, body,
// space and joint group is released.
TEST(OdeBackend, MixedLifetimesAndWorldsOfTwoBackends) {
    auto a = std::make_unique<World>(test::backendSettings("ode"));
    WorldSettings nativeSettings;
    nativeSettings.backend = "native";
    auto native = std::make_unique<World>(nativeSettings);
    // Lenient: this world holds a hull and a mesh (the pair ODE cannot collide, refused under the
    // strict policy) so that every kind of geom and its arrays is created and released.
    WorldSettings lenient = test::backendSettings("ode");
    lenient.capabilityPolicy = CapabilityPolicy::Lenient;
    auto b = std::make_unique<World>(lenient);
    b->setWarningHandler([](const std::string&) {});
    std::vector<Body> bodies;
    for (World* w : {a.get(), native.get(), b.get()}) {
        w->createBody(ground());
        for (int i = 0; i < 4; ++i) bodies.push_back(w->createBody(box(Vec3(0, 0.5 + i, 0))));
    }
    for (int i = 0; i < 30; ++i)
        for (World* w : {a.get(), native.get(), b.get()}) w->step();
    // Destroy out of creation order, while stacked boxes touch.
    a->destroyBody(bodies[1]);
    b->destroyBody(bodies[10]);
    b->destroyBody(bodies[8]);
    a = nullptr;  // the first ODE world goes with bodies alive
    for (int i = 0; i < 30; ++i) {
        b->step();
        native->step();
    }
    BodyDef convex;
    convex.shape = ShapeDef::convex({Vec3(-0.5, 0, -0.5), Vec3(0.5, 0, -0.5), Vec3(0, 0, 0.5), Vec3(0, 0.8, 0)});
    convex.position = Vec3(3, 1, 0);
    Body hull = b->createBody(convex);
    BodyDef mesh = ground();
    mesh.shape = ShapeDef::mesh({Vec3(-5, 0, -5), Vec3(5, 0, -5), Vec3(0, 0, 5)}, {0, 2, 1});
    mesh.position = Vec3(0, 0.01, 0);
    b->createBody(mesh);
    for (int i = 0; i < 30; ++i) b->step();
    EXPECT_TRUE(std::isfinite(hull.position().y()));
    EXPECT_EQ(b->bodyCount(), 5u);  // ground, 2 boxes, hull, mesh
    native = nullptr;
    b = nullptr;
    World again(test::backendSettings("ode"));  // ODE stays initialised for later worlds
    again.createBody(box(Vec3(0, 1, 0)));
    again.step();
}

// Quickstep reorders rows with ODE's one global random generator; each world keeps its own
// stream, so identical worlds give identical results even when stepped interleaved.
TEST(OdeBackend, IdenticalWorldsStayIdenticalWhenInterleaved) {
    World first(test::backendSettings("ode")), second(test::backendSettings("ode"));
    std::vector<Body> a, b;
    for (World* w : {&first, &second}) {
        w->createBody(ground());
        for (int i = 0; i < 5; ++i) (w == &first ? a : b).push_back(w->createBody(box(Vec3(0.1 * i, 0.5 + i, 0))));
    }
    for (int i = 0; i < 120; ++i) {
        first.step();
        second.step();
        second.step();  // a different interleaving of the global generator's users...
        first.step();   // ...still the same sequence per world
    }
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].position(), b[i].position()) << "box " << i;
}

// Damping dv/dt = -c v is applied as ODE's per-step scale 1 - exp(-c dt), so free motion decays
// as exp(-c t) to rounding.
TEST(OdeBackend, DampingMatchesExponentialDecay) {
    WorldSettings s = test::backendSettings("ode");
    s.gravity = Vec3::Zero();
    World world(s);
    BodyDef def;
    def.shape = ShapeDef::sphere(0.5);
    def.linearVelocity = Vec3(5, 0, 0);
    def.angularVelocity = Vec3(0, 3, 0);
    def.linearDamping = 0.8;
    def.angularDamping = 1.5;
    Body b = world.createBody(def);
    for (int i = 0; i < 120; ++i) world.step();
    const double t = world.time();
    // 1e-12 relative: the scale is exact, so only 120 roundings of the product remain.
    EXPECT_NEAR(b.linearVelocity().x(), 5.0 * std::exp(-0.8 * t), 1e-12 * 5.0);
    EXPECT_NEAR(b.angularVelocity().y(), 3.0 * std::exp(-1.5 * t), 1e-12 * 3.0);
    // A second dt per step (World::step(dt)) re-derives the scale.
    const double v = b.linearVelocity().x();
    for (int i = 0; i < 10; ++i) world.step(0.01);
    EXPECT_NEAR(b.linearVelocity().x(), v * std::exp(-0.8 * 0.1), 1e-12 * v);
}

// The layer's resolved value for a material pair is what ODE's contact uses: a box sliding at v0
// stops after v0^2 / (2 mu g), with the pair override's mu, not the mixed one.
TEST(OdeBackend, PairOverrideSetsTheContactFriction) {
    constexpr double kV0 = 4.0;
    const auto slide = [&](std::optional<double> pairFriction) {
        MaterialLibrary materials;
        materials.add("box", Material{0.2, 0.0, 1000.0});
        materials.add("floor", Material{0.8, 0.0, 1000.0});
        if (pairFriction) materials.setPairOverride("box", "floor", PairOverride{pairFriction, std::nullopt});
        World world(test::backendSettings("ode"), materials);
        world.createBody(ground("floor"));
        BodyDef def = box(Vec3(0, 0.5, 0), "box");
        def.linearVelocity = Vec3(kV0, 0, 0);
        Body b = world.createBody(def);
        while (world.time() < 4.0) world.step();
        return b.position().x();
    };
    for (auto [pair, mu] : {std::pair<std::optional<double>, double>{std::nullopt, 0.4}, {0.25, 0.25}, {0.7, 0.7}}) {
        const double exact = kV0 * kV0 / (2 * mu * kG);
        // 3 %: semi-implicit stepping stops the box about mu g dt / v0 of the way early (1.1 % at
        // mu 0.7) plus the stop falling between steps; the cases differ by >= 40 %.
        EXPECT_NEAR(slide(pair), exact, 0.03 * exact) << "mu " << mu;
    }
}

// Contact impulses come from ODE's joint feedback: a box at rest on the ground receives m g dt of
// normal impulse per step, summed over its contact points.
TEST(OdeBackend, RestingContactImpulsesCarryTheWeight) {
    World world(test::backendSettings("ode"));
    world.createBody(ground());
    BodyDef def = box(Vec3(0, 0.5, 0));
    def.allowSleep = false;  // sleeping pairs send no events
    Body cube = world.createBody(def);
    (void)world.lastEvents();  // read from the start: ODE measures impulses once someone reads events
    for (int i = 0; i < 60; ++i) world.step();
    const double dt = world.settings().timeStep;
    double total = 0.0;
    int stays = 0;
    for (const ContactEvent& e : world.lastEvents()) {
        if (e.phase != ContactPhase::Stay) continue;
        ++stays;
        EXPECT_TRUE(e.hasImpulses);
        for (const ContactPoint& p : e.points) total += p.normalImpulse;
    }
    ASSERT_EQ(stays, 1);
    const double weight = cube.massProperties().mass * kG * dt;
    // 1 %: at rest the solver's converged normal impulse balances gravity; what remains is the
    // Baumgarte push-out of the surface layer's residual overlap.
    EXPECT_NEAR(total, weight, 0.01 * weight);
}

// The contact joints' feedback (the events' impulses) costs quickstep a copy of every joint's
// Jacobian: a world with events on that nobody reads wires none, and moves exactly as one that
// reads them; from the step after the first read it measures them.
TEST(OdeBackend, ImpulsesAreMeasuredOnlyOnceEventsAreRead) {
    World unread(test::backendSettings("ode")), read(test::backendSettings("ode"));
    std::vector<Body> cubes;
    for (World* w : {&unread, &read}) {
        w->createBody(ground());
        BodyDef def = box(Vec3(0, 0.45, 0));  // 5 cm into the ground: pushed out over some steps
        def.allowSleep = false;
        cubes.push_back(w->createBody(def));
    }
    (void)read.lastEvents();
    for (int i = 0; i < 30; ++i) {
        unread.step();
        read.step();
        ASSERT_EQ(cubes[0].position(), cubes[1].position()) << "step " << i + 1;
        ASSERT_EQ(cubes[0].orientation().coeffs(), cubes[1].orientation().coeffs()) << "step " << i + 1;
    }
    EXPECT_FALSE(peerOf(unread).measuredImpulses());
    EXPECT_TRUE(peerOf(read).measuredImpulses());
    (void)unread.lastEvents();
    unread.step();
    EXPECT_TRUE(peerOf(unread).measuredImpulses());
}

}  // namespace
}  // namespace anyphys
