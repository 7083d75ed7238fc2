// Every integrator a backend offers must be the method it names: on smooth problems the error
// at a fixed end time must fall with the time step at the method's order (slope of log error
// against log dt): explicit Euler 1, semi-implicit Euler 1, Verlet 2, midpoint 2, RK4 4.
#include <cmath>
#include <iostream>
#include <numbers>

#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

struct Method {
    Integrator integrator;
    double order;
};
constexpr Method kMethods[] = {{Integrator::ExplicitEuler, 1}, {Integrator::SemiImplicitEuler, 1},
                               {Integrator::Verlet, 2},        {Integrator::Midpoint, 2},
                               {Integrator::RK4, 4}};

// Least-squares slope of log(error) over log(dt).
double fittedSlope(const std::vector<double>& dts, const std::vector<double>& errors) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = static_cast<double>(dts.size());
    for (std::size_t i = 0; i < dts.size(); ++i) {
        const double x = std::log(dts[i]), y = std::log(errors[i]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// dt = 1/20 .. 1/160: small enough to be in the asymptotic regime for these problems, large
// enough that RK4's error (~1e-10 at the finest) stays far above rounding.
const std::vector<double> kSteps = {1.0 / 20, 1.0 / 40, 1.0 / 80, 1.0 / 160};

// Tolerance on the fitted slope: the leading error term dominates to within a few percent at
// these steps; 0.15 separates every order from its neighbour with margin.
constexpr double kSlopeTolerance = 0.15;

class ConvergenceTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
};

// Harmonic oscillator x'' = -w^2 x through the force callback (needs per-stage force
// evaluation: a force held constant over the step would cap every method at first order).
TEST_P(ConvergenceTest, SpringThroughForceCallback) {
    ANYPHYS_REQUIRE(caps().forceEvaluation == ForceEvaluation::PerStage, "per-stage force evaluation");
    // w = pi and T = 1.3 s: the end point is off any symmetry point of the orbit (where some
    // first-order errors cancel), and w h <= 0.08 keeps explicit Euler's amplitude growth,
    // exp(T w^2 h / 2) - 1, in its linear regime.
    const double w = std::numbers::pi, T = 1.3;
    const std::vector<double> steps = {1.0 / 40, 1.0 / 80, 1.0 / 160, 1.0 / 320};
    for (const Method& m : kMethods) {
        if (!caps().integrators.count(m.integrator)) continue;
        std::vector<double> errors;
        for (double dt : steps) {
            WorldSettings s = settings();
            s.gravity = Vec3::Zero();
            s.integrator = m.integrator;
            s.timeStep = dt;
            World world(s);
            BodyDef def = sphereDef(0.5);
            def.position = Vec3(1, 0, 0);
            def.mass = 1.0;
            Body mass = world.createBody(def);
            world.setForceCallback([&](ForceContext& ctx) { ctx.addForce(mass, -w * w * ctx.state(mass).position); });
            const int n = static_cast<int>(std::lround(T / dt));
            for (int i = 0; i < n; ++i) world.step();
            // Phase-space distance: at a turning point the position alone hides the phase error
            // to first order, so velocity is included (scaled by 1/w to the same units).
            const double dx = mass.position().x() - std::cos(w * T);
            const double dv = mass.linearVelocity().x() + w * std::sin(w * T);
            errors.push_back(std::hypot(dx, dv / w));
        }
        const double slope = fittedSlope(steps, errors);
        std::cout << "  " << toString(m.integrator) << ": measured order " << slope << '\n';
        EXPECT_NEAR(slope, m.order, kSlopeTolerance) << toString(m.integrator);
    }
}

// Linear damping v' = -c v with an initial spin: exercises velocity-dependent accelerations
// and the orientation update together. Exact: x = v0 (1 - e^{-ct}) / c, rotation angle
// w0 (1 - e^{-ct}) / c about a fixed axis.
TEST_P(ConvergenceTest, DampedTranslationAndRotation) {
    ANYPHYS_REQUIRE(caps().effects.has(Effect::Damping), "effect damping");
    ANYPHYS_REQUIRE(caps().parameters.count("body.linearDamping") && caps().parameters.count("body.angularDamping"),
                    "parameters body.linearDamping and body.angularDamping");
    const double c = 1.5, v0 = 2.0, w0 = 3.0, T = 1.0;
    for (const Method& m : kMethods) {
        if (!caps().integrators.count(m.integrator)) continue;
        std::vector<double> errors;
        for (double dt : kSteps) {
            WorldSettings s = settings();
            s.gravity = Vec3::Zero();
            s.integrator = m.integrator;
            s.timeStep = dt;
            World world(s);
            BodyDef def;
            def.shape = ShapeDef::sphere(0.5);  // isotropic: no gyroscopic coupling
            def.linearVelocity = Vec3(v0, 0, 0);
            def.angularVelocity = Vec3(0, 0, w0);
            def.linearDamping = c;
            def.angularDamping = c;
            Body body = world.createBody(def);
            const int n = static_cast<int>(std::lround(T / dt));
            for (int i = 0; i < n; ++i) world.step();
            const double decay = (1.0 - std::exp(-c * T)) / c;
            const Quat exactQ(Eigen::AngleAxisd(w0 * decay, Vec3::UnitZ()));
            const double positionError = std::abs(body.position().x() - v0 * decay);
            const double angleError = body.orientation().angularDistance(exactQ);
            errors.push_back(positionError + angleError);
        }
        const double slope = fittedSlope(kSteps, errors);
        std::cout << "  " << toString(m.integrator) << ": measured order " << slope << '\n';
        // The method's order is a floor here, not a value: a backend may take damping as its
        // exact factor (native's semi-implicit Euler splits it around the step, which makes this
        // motion second order); the error must still fall at least as fast as the method's.
        EXPECT_GE(slope, m.order - kSlopeTolerance) << toString(m.integrator);
    }
}

ANYPHYS_CONTRACT_SUITE(ConvergenceTest);

}  // namespace
}  // namespace anyphys::test
