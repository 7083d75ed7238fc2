// The force callback's evaluation rule, which the layer owns: a backend that evaluates forces per
// step (ForceEvaluation::PerStep) gets the callback run once by the World at the step's start,
// and its forces act over the whole step, every substep of it; a per-stage backend runs it at
// each stage of its integrator. And the solver settings a world runs with: unset ones resolved
// once, by the layer, to the backend's published defaults.
#include <map>
#include <tuple>
#include <vector>

#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class ForceCallbackContract : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }

    /// Free bodies only (no gravity, no contacts): the integrator alone decides the evaluations.
    WorldSettings freeFlight(std::optional<int> substeps, Integrator integrator = Integrator::SemiImplicitEuler) const {
        WorldSettings s = settings();
        s.gravity = Vec3::Zero();
        s.integrator = integrator;
        if (substeps && caps().parameters.contains("settings.substeps")) s.substeps = substeps;
        return s;
    }

    /// The substep counts a backend honours: 1 and 4, or just its default.
    std::vector<std::optional<int>> substepCounts() const {
        if (!caps().parameters.contains("settings.substeps")) return {std::nullopt};
        return {1, 4};
    }
};

// Force evaluations one step of the integrator makes: the method's stage count.
int stagesOf(Integrator integrator) {
    switch (integrator) {
        case Integrator::ExplicitEuler:
        case Integrator::SemiImplicitEuler: return 1;
        case Integrator::Verlet:
        case Integrator::Midpoint: return 2;
        case Integrator::RK4: return 4;
    }
    return 1;
}

TEST_P(ForceCallbackContract, RunsOncePerStepOrOncePerIntegratorStage) {
    const bool perStep = caps().forceEvaluation == ForceEvaluation::PerStep;
    const double dt = 1.0 / 60.0;
    for (Integrator integrator : caps().integrators)
        for (const std::optional<int>& substeps : substepCounts()) {
            SCOPED_TRACE(std::string(toString(integrator)) + ", substeps " +
                         (substeps ? std::to_string(*substeps) : std::string("default")));
            World world(freeFlight(substeps, integrator));
            Body body = world.createBody(sphereDef(0.5));
            std::vector<double> times;
            world.setForceCallback([&](ForceContext& c) {
                times.push_back(c.time());
                c.addForce(body, Vec3(1, 0, 0));
            });
            for (int step = 0; step < 3; ++step) {
                const double start = world.time();
                times.clear();
                world.step(dt);
                // Per step: once, with the step-start time (the states it read are the step's
                // start). Per stage: once per stage of the method, at times within the step
                // (free bodies are integrated once per step, whatever the substeps).
                ASSERT_EQ(static_cast<int>(times.size()), perStep ? 1 : stagesOf(integrator)) << "step " << step;
                EXPECT_EQ(times.front(), start);  // every method's first stage is the step's start
                for (double t : times) {
                    EXPECT_GE(t, start);
                    EXPECT_LE(t, start + dt);
                }
            }
        }
}

// A constant callback force F on a free body of mass m for one step of dt: dv = F dt / m, whatever
// the substep count. A force applied only at the first substep would give dv / N, one that
// lingered into the next step would show there.
TEST_P(ForceCallbackContract, ForceActsOverTheWholeStepAndOnlyThatStep) {
    const double dt = 1.0 / 60.0, mass = 2.0;
    const Vec3 force(3.0, -1.5, 0.0);  // in the plane, so planar worlds keep all of it
    const Vec3 expected = force * dt / mass;
    for (const std::optional<int>& substeps : substepCounts()) {
        SCOPED_TRACE(substeps ? "substeps " + std::to_string(*substeps) : std::string("default substeps"));
        World world(freeFlight(substeps));
        BodyDef def = sphereDef(0.5);
        def.mass = mass;
        Body body = world.createBody(def);
        bool push = true;
        world.setForceCallback([&](ForceContext& c) {
            if (push) c.addForce(body, force);
        });
        world.step(dt);
        const Vec3 dv = body.state().linearVelocity;
        // Exact up to rounding: each substep adds h F / m to the velocity (one rounding of the
        // force, the inverse mass, h and the product, one of the sum: 5 per substep), plus the
        // float conversion of every input on a float engine; 8 per substep covers both.
        const int n = *world.settings().substeps;
        const double tolerance = rounding(expected.norm(), 8.0 * n);
        EXPECT_NEAR(dv.x(), expected.x(), tolerance);
        EXPECT_NEAR(dv.y(), expected.y(), tolerance);
        EXPECT_NEAR(dv.z(), 0.0, tolerance);
        // The next step without a force: nothing of the last one is held over.
        push = false;
        world.step(dt);
        const Vec3 after = body.state().linearVelocity;
        EXPECT_NEAR(after.x(), dv.x(), rounding(dv.norm(), 2));
        EXPECT_NEAR(after.y(), dv.y(), rounding(dv.norm(), 2));
    }
}

// A torque from the callback acts over the whole step too: dw = T dt / I about a principal axis.
TEST_P(ForceCallbackContract, TorqueActsOverTheWholeStep) {
    const double dt = 1.0 / 60.0;
    const Vec3 torque(0.0, 0.0, 0.4);  // about Z, so planar worlds keep it
    for (const std::optional<int>& substeps : substepCounts()) {
        SCOPED_TRACE(substeps ? "substeps " + std::to_string(*substeps) : std::string("default substeps"));
        World world(freeFlight(substeps));
        Body body = world.createBody(sphereDef(0.5));
        const double inertia = body.massProperties().inertia.z();
        world.setForceCallback([&](ForceContext& c) { c.addTorque(body, torque); });
        world.step(dt);
        const double expected = torque.z() * dt / inertia;
        const int n = *world.settings().substeps;
        // As for the force above, with the inverse inertia in place of the inverse mass.
        EXPECT_NEAR(body.state().angularVelocity.z(), expected, rounding(expected, 8.0 * n));
    }
}

// A callback's force and Body::applyForce's add up over the step, on every backend.
TEST_P(ForceCallbackContract, CallbackAndAppliedForcesAddUp) {
    const double dt = 1.0 / 60.0, mass = 1.5;
    World world(freeFlight(std::nullopt));
    BodyDef def = sphereDef(0.5);
    def.mass = mass;
    Body body = world.createBody(def);
    world.setForceCallback([&](ForceContext& c) { c.addForce(body, Vec3(1.0, 0, 0)); });
    body.applyForce(Vec3(2.0, 0, 0));
    world.step(dt);
    const double expected = 3.0 * dt / mass;
    // Two force sums and the substeps' updates; 8 roundings per substep as above.
    EXPECT_NEAR(body.state().linearVelocity.x(), expected, rounding(expected, 8.0 * *world.settings().substeps + 2));
}

// ---- solver settings resolved by the layer -------------------------------------------------

class ResolvedSettingsContract : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
};

// World::settings() reports what runs: every unset solver setting filled in with the backend's
// published default, by the same rule the tool reports configurations with.
TEST_P(ResolvedSettingsContract, UnsetSolverSettingsReportTheBackendDefaults) {
    const Capabilities c = caps();
    World world(settings());
    const WorldSettings& s = world.settings();
    ASSERT_TRUE(s.solver && s.substeps && s.iterations);
    EXPECT_EQ(*s.solver, c.defaultSolver);
    EXPECT_EQ(*s.substeps, c.defaultSubsteps);
    EXPECT_EQ(*s.iterations, c.defaultIterations);
    const WorldSettings tool = withBackendDefaults(settings(), c);
    EXPECT_EQ(tool.solver, s.solver);
    EXPECT_EQ(tool.substeps, s.substeps);
    EXPECT_EQ(tool.iterations, s.iterations);
}

// The defaults each backend publishes are the tuned values docs/scene-format.md and
// docs/architecture.md list; a backend not listed here must be added with its documented values.
TEST_P(ResolvedSettingsContract, PublishedDefaultsAreTheDocumentedOnes) {
    const std::map<std::string, std::tuple<Solver, int, int>> documented{
        {"native", {Solver::SoftStep, 8, 1}},
        {"ode", {Solver::ProjectedGaussSeidel, 1, 50}},
        {"bullet", {Solver::ProjectedGaussSeidel, 1, 30}},
        {"box2d", {Solver::ProjectedGaussSeidel, 1, 8}},
    };
    const auto it = documented.find(backend());
    ASSERT_NE(it, documented.end()) << "backend " << backend() << " has no documented solver defaults";
    const auto [solver, substeps, iterations] = it->second;
    EXPECT_EQ(caps().defaultSolver, solver);
    EXPECT_EQ(caps().defaultSubsteps, substeps);
    EXPECT_EQ(caps().defaultIterations, iterations);
}

// Set values are kept; unset iterations follow the substeps so a step keeps the default work.
TEST_P(ResolvedSettingsContract, SetValuesAreKeptAndIterationsKeepTheDefaultWork) {
    const Capabilities c = caps();
    if (c.parameters.contains("settings.substeps")) {
        WorldSettings one = settings();
        one.substeps = 1;
        World world(one);
        EXPECT_EQ(*world.settings().substeps, 1);
        // ceil(default work / 1): at least the default sweeps per step in one substep.
        EXPECT_EQ(*world.settings().iterations, std::max(c.defaultIterations, c.defaultIterations * c.defaultSubsteps));
    }
    if (c.parameters.contains("settings.iterations")) {
        WorldSettings set = settings();
        set.iterations = 3;
        World world(set);
        EXPECT_EQ(*world.settings().iterations, 3);
        EXPECT_EQ(*world.settings().substeps, c.defaultSubsteps);
    }
}

ANYPHYS_CONTRACT_SUITE(ForceCallbackContract);
ANYPHYS_CONTRACT_SUITE(ResolvedSettingsContract);

}  // namespace
}  // namespace anyphys::test
