// Projectile under constant gravity: each integrator's closed-form error is known exactly.
// Exact: y(t) = v0y t - g t^2 / 2 -> at t = 2 s with v0y = 10, g = 10: y = 0.
// Explicit Euler uses the old velocity for every position update and ends g T dt / 2 = 1/6 m
// above; semi-implicit Euler uses the new one and ends 1/6 m below; Verlet, midpoint and RK4
// integrate a quadratic exactly.
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

struct ProjectileCase {
    Integrator integrator;
    double expectedOffset;  // m, final height minus the exact height
};

class ProjectileTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
};

TEST_P(ProjectileTest, EachIntegratorEndsAtItsClosedFormHeight) {
    const ProjectileCase cases[] = {{Integrator::ExplicitEuler, 1.0 / 6.0},
                                    {Integrator::SemiImplicitEuler, -1.0 / 6.0},
                                    {Integrator::Verlet, 0.0},
                                    {Integrator::Midpoint, 0.0},
                                    {Integrator::RK4, 0.0}};
    int tested = 0;
    for (const auto& c : cases) {
        if (!caps().integrators.count(c.integrator)) {
            std::cout << "[ SKIPPED  ] " << backend() << " lacks integrator " << toString(c.integrator) << '\n';
            continue;
        }
        WorldSettings s = settings();
        s.gravity = Vec3(0, -10, 0);
        s.timeStep = 1.0 / 60.0;
        s.integrator = c.integrator;
        World world(s);
        BodyDef def;
        def.shape = ShapeDef::sphere(0.5);
        def.linearVelocity = Vec3(10, 10, 0);
        def.mass = 1.0;
        Body ball = world.createBody(def);
        for (int i = 0; i < 120; ++i) world.step();
        // 1e-9 m: 120 steps of rounding in quantities of order 10 stay near 1e-13 in double;
        // a float engine rounds them to 6e-8 relative at each of the 120 steps (within 1e-4 m,
        // still 1 600 times below the 1/6 m between the methods). Anything larger means a
        // different method.
        const double tolerance = 1e-9 + rounding(20, 120);
        EXPECT_NEAR(ball.position().y(), c.expectedOffset, tolerance) << toString(c.integrator);
        EXPECT_NEAR(ball.position().x(), 20.0, tolerance) << toString(c.integrator);
        EXPECT_NEAR(ball.linearVelocity().y(), -10.0, tolerance) << toString(c.integrator);
        EXPECT_NEAR(world.time(), 2.0, 1e-12);
        ++tested;
    }
    ANYPHYS_REQUIRE(tested > 0, "every integrator");
}

ANYPHYS_CONTRACT_SUITE(ProjectileTest);

}  // namespace
}  // namespace anyphys::test
