// Mass and inertia regularisation of assemblies: bounded mass ratios across joints with the
// total mass kept, parents at least as hard to turn as their children, refusals that change
// nothing, and the "regularize" key of scene-file instances.
#include <gtest/gtest.h>

#include <numeric>

#include "anyphys/containers/assembly.hpp"
#include "anyphys/containers/mass_regularization.hpp"
#include "anyphys/error.hpp"
#include "anyphys/mass_properties.hpp"

namespace anyphys {
namespace {

BodyDef ball(const std::string& name, double mass) {
    BodyDef b;
    b.name = name;
    b.shape = ShapeDef::sphere(0.1);
    b.mass = mass;
    return b;
}

SceneJoint link(const std::string& a, const std::string& b) {
    SceneJoint j;
    j.def.type = JointType::Ball;
    j.bodyA = a;
    j.bodyB = b;
    return j;
}

// A chain a - b - c - d of masses 1, 50, 2, 100 kg, plus a loose 500 kg body joined to nothing.
Scene chain() {
    Scene s;
    for (auto [name, mass] : {std::pair{"a", 1.0}, {"b", 50.0}, {"c", 2.0}, {"d", 100.0}, {"loose", 500.0}})
        s.bodies.push_back(ball(name, mass));
    s.joints = {link("a", "b"), link("b", "c"), link("c", "d")};
    return s;
}

double totalJointedMass(const Scene& s) {
    double total = 0.0;
    for (int i = 0; i < 4; ++i) total += *s.bodies[i].mass;
    return total;
}

TEST(MassRegularization, BoundsEveryJointsMassRatioAndKeepsTheTotal) {
    Scene s = chain();
    const double total = totalJointedMass(s);
    regularizeMasses(s, MassRegularization{3.0, false});
    for (const SceneJoint& j : s.joints) {
        const auto massOf = [&s](const std::string& n) {
            for (const BodyDef& b : s.bodies)
                if (b.name == n) return *b.mass;
            return 0.0;
        };
        const double hi = std::max(massOf(j.bodyA), massOf(j.bodyB)), lo = std::min(massOf(j.bodyA), massOf(j.bodyB));
        EXPECT_LE(hi / lo, 3.0 * (1 + 1e-9)) << j.bodyA << " - " << j.bodyB;
    }
    EXPECT_NEAR(totalJointedMass(s), total, 1e-9 * total);  // the assembly weighs what it did
    EXPECT_EQ(*s.bodies[4].mass, 500.0);                     // a body in no joint is left alone
    // Ratios that already hold are kept: the heaviest stays the heaviest.
    EXPECT_GT(*s.bodies[3].mass, *s.bodies[1].mass);
}

TEST(MassRegularization, ScalesAnExplicitInertiaWithItsMass) {
    Scene s = chain();
    s.bodies[0].inertia = Vec3(1, 2, 3);
    regularizeMasses(s, MassRegularization{3.0, false});
    const double factor = *s.bodies[0].mass / 1.0;
    EXPECT_GT(factor, 1.0);
    EXPECT_TRUE(s.bodies[0].inertia->isApprox(Vec3(1, 2, 3) * factor, 1e-12));
    EXPECT_FALSE(s.bodies[1].inertia.has_value());  // derived from shape and mass by the world, as before
}

TEST(MassRegularization, RaisesParentInertiaUpTheTree) {
    // root -> mid -> tip: a long heavy capsule at the tip, small balls above it.
    Scene s;
    s.bodies = {ball("root", 1.0), ball("mid", 1.0)};
    BodyDef tip;
    tip.name = "tip";
    tip.shape = ShapeDef::capsule(0.05, 0.5);
    tip.mass = 3.0;
    s.bodies.push_back(tip);
    s.joints = {link("root", "mid"), link("mid", "tip")};
    const double tipMax = (3.0 * unitInertia(tip.shape)).maxCoeff();
    regularizeMasses(s, MassRegularization{0.0, true});
    ASSERT_TRUE(s.bodies[1].inertia && s.bodies[0].inertia);
    EXPECT_NEAR(s.bodies[1].inertia->minCoeff(), tipMax, 1e-12);
    EXPECT_NEAR(s.bodies[0].inertia->minCoeff(), tipMax, 1e-12);  // through mid, to the root
    EXPECT_FALSE(s.bodies[2].inertia.has_value());                // the child is not touched
    EXPECT_EQ(*s.bodies[0].mass, 1.0);                            // masses alone without a ratio
}

TEST(MassRegularization, RefusesABodyWhoseMassItCannotKnowAndChangesNothing) {
    Scene s = chain();
    s.bodies[2].mass.reset();
    s.bodies[2].shape = ShapeDef::convex({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    const Scene before = s;
    try {
        regularizeMasses(s, MassRegularization{3.0, false});
        FAIL() << "expected a refusal";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("\"c\""), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("explicit mass"), std::string::npos) << e.what();
    }
    for (std::size_t i = 0; i < s.bodies.size(); ++i) EXPECT_EQ(s.bodies[i].mass, before.bodies[i].mass);
}

TEST(MassRegularization, ResolvesMassFromDensityAsTheWorldDoes) {
    Scene s = chain();
    s.bodies[0].mass.reset();
    s.bodies[0].density = 10.0;  // 10 kg/m^3 x (4/3 pi 0.1^3) = 0.042 kg against 50 kg
    regularizeMasses(s, MassRegularization{2.0, false});
    ASSERT_TRUE(s.bodies[0].mass.has_value());
    EXPECT_GE(*s.bodies[0].mass * 2.0 * (1 + 1e-9), *s.bodies[1].mass);
}

TEST(MassRegularization, SceneFileInstancesTakeARegularizeObject) {
    const std::string text = R"({ "instances": [
        { "scene": "ragdoll", "prefix": "a/" },
        { "scene": "ragdoll", "prefix": "b/", "position": [3, 0, 0],
          "regularize": { "maxMassRatio": 2, "raiseParentInertia": true } } ] })";
    const Scene s = parseScene(text);
    const auto massOf = [&s](const std::string& n) {
        for (const BodyDef& b : s.bodies)
            if (b.name == n) return *b.mass;
        return 0.0;
    };
    // The ragdoll's chest (20.65 kg) and upper arm (1.96 kg) differ by 10.5: bounded to 2 in b/ only.
    EXPECT_GT(massOf("a/chest") / massOf("a/upper_arm_l"), 10.0);
    EXPECT_LE(massOf("b/chest") / massOf("b/upper_arm_l"), 2.0 * (1 + 1e-9));
    double a = 0.0, b = 0.0;
    for (const BodyDef& body : s.bodies) (body.name[0] == 'a' ? a : b) += *body.mass;
    EXPECT_NEAR(a, b, 1e-9 * a);

    const auto errorOf = [](const std::string& json) {
        try {
            parseScene(json);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string bad = errorOf(R"({ "instances": [ { "scene": "ragdoll", "regularize": { "maxMassRatio": 0.5 } } ] })");
    EXPECT_NE(bad.find("instances[0].regularize.maxMassRatio"), std::string::npos) << bad;
    const std::string unknown = errorOf(R"({ "instances": [ { "scene": "ragdoll", "regularize": { "ratio": 2 } } ] })");
    EXPECT_NE(unknown.find("ratio"), std::string::npos) << unknown;
}

}  // namespace
}  // namespace anyphys
