// The layer mixes materials (combine rules, pair overrides) and every backend applies the result:
// a box sliding on the ground at v0 stops after v0^2 / (2 mu g) for the mixed mu.
#include <algorithm>
#include <cmath>

#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class MaterialsTest : public ContractTest {
protected:
    bool runsPlanarWithout3D() const override { return true; }
};

constexpr double kV0 = 5.0;  // m/s

struct SlideCase {
    const char* what;
    CombineRule rule;
    std::optional<double> pairFriction;  ///< override of the (box, floor) pair
    double mixedMu;                      ///< what the layer must resolve
};

// Box friction 0.2, floor friction 0.8 under each rule, and an override beating the rule.
const SlideCase kCases[] = {
    {"geometric mean (default)", CombineRule::GeometricMean, std::nullopt, 0.4},  // sqrt(0.2 * 0.8)
    {"average", CombineRule::Average, std::nullopt, 0.5},
    {"min", CombineRule::Min, std::nullopt, 0.2},
    {"max", CombineRule::Max, std::nullopt, 0.8},
    {"multiply", CombineRule::Multiply, std::nullopt, 0.16},
    {"pair override 0.3", CombineRule::GeometricMean, 0.3, 0.3},
};

/// Distance a box launched at v0 along x slides before it stops (4.5 s is past the slowest
/// stop, v0 / (0.16 g) = 3.2 s).
double slideDistance(const WorldSettings& settings, const SlideCase& c) {
    MaterialLibrary materials;
    materials.add("box", Material{0.2, 0.0, 1000.0});
    materials.add("floor", Material{0.8, 0.0, 1000.0});
    materials.setFrictionRule(c.rule);
    if (c.pairFriction) materials.setPairOverride("box", "floor", PairOverride{c.pairFriction, std::nullopt});
    World world(settings, materials);
    world.createBody(groundDef("floor"));
    // A cube slides without tipping while mu < half width / half height = 1.
    BodyDef def = boxDef("box", Vec3(0.25, 0.25, 0.25), Vec3(0, 0.25, 0), "box");
    def.linearVelocity = Vec3(kV0, 0, 0);
    Body box = world.createBody(def);
    while (world.time() < 4.5) world.step();
    return box.position().x();
}

TEST_P(MaterialsTest, CombineRulesAndPairOverridesSetTheSlideDistance) {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    double worst = 0.0;
    std::string figures;
    for (const SlideCase& c : kCases) {
        const double exact = kV0 * kV0 / (2 * c.mixedMu * kG);
        const double measured = slideDistance(settings(), c);
        report(backend() + " slide distance, " + c.what + " (exact " + std::to_string(exact) + ")", measured, "m");
        worst = std::max(worst, std::abs(measured - exact) / exact);
        figures += std::string(" ") + c.what + ": " + std::to_string(measured) + " m (exact " + std::to_string(exact) + ");";
    }
    // 5 %: stepping shifts the stopping distance by about mu g dt / v0 of it (2.6 % at the
    // largest mu, 0.8), and the stop falls between two steps. The cases differ by >= 20 %, so
    // each rule is told apart.
    expectCriterion("materials.slide_distance", worst <= 0.05,
                    "worst " + std::to_string(100 * worst) + " % off (bound 5 %):" + figures, worst);
}

// A pair override of restitution makes two dead materials bounce: both restitution 0, the pair
// overridden to 0.8 -> rebound to 0.64 of the drop. Default settings, as in
// ContactsTest.BallReboundsToRestitutionSquaredOfDropHeight.
TEST_P(MaterialsTest, PairOverrideSetsRestitution) {
    const std::string missing =
        lacking(caps(), {ShapeType::Sphere, ShapeType::Plane}, Effect::Contacts | Effect::Restitution);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    constexpr double kRadius = 0.5, kDrop = 2.0;
    MaterialLibrary materials;
    materials.add("ball", Material{0.6, 0.0, 1000.0});
    materials.add("floor", Material{0.6, 0.0, 1000.0});
    materials.setPairOverride("ball", "floor", PairOverride{std::nullopt, 0.8});
    World world(settings(), materials);
    world.createBody(groundDef("floor"));
    Body ball = world.createBody(ballDef("ball", kRadius, Vec3(0, kRadius + kDrop, 0), "ball"));
    const double rebound = firstReboundApex(world, ball, 4.0) - kRadius;
    report(backend() + " rebound with pair restitution 0.8 (exact 1.28)", rebound, "m");
    // The bounce's own error (reboundTolerance, as in the restitution contract; impact 6.3 m/s,
    // far above the threshold).
    const double tolerance = reboundTolerance(world.settings());
    expectCriterion(std::string(planarWorld() ? "planar." : "") + "materials.pair_restitution",
                    std::abs(rebound - 0.64 * kDrop) <= tolerance,
                    "pair override e = 0.8: rebound " + std::to_string(rebound) + " m, exact 1.28 m +- " +
                        std::to_string(tolerance),
                    std::abs(rebound - 0.64 * kDrop));
}

ANYPHYS_CONTRACT_SUITE(MaterialsTest);

}  // namespace
}  // namespace anyphys::test
