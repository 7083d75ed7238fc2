#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "anyphys/containers/material_library.hpp"
#include "anyphys/error.hpp"

using namespace anyphys;

namespace {

// Expects `f` to throw anyphys::Error whose message contains every fragment.
template <class F>
void expectError(F&& f, std::initializer_list<std::string> fragments) {
    try {
        f();
        ADD_FAILURE() << "expected anyphys::Error";
    } catch (const Error& e) {
        for (const auto& part : fragments) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

MaterialLibrary rubberAndIce() {
    MaterialLibrary lib;
    lib.add("rubber", Material{0.9, 0.8, 1100});
    lib.add("ice", Material{0.04, 0.1, 917});
    return lib;
}

}  // namespace

TEST(CombineRule, EachRuleHasItsArithmetic) {
    EXPECT_DOUBLE_EQ(combine(CombineRule::Average, 0.2, 0.8), 0.5);
    EXPECT_DOUBLE_EQ(combine(CombineRule::Min, 0.2, 0.8), 0.2);
    EXPECT_DOUBLE_EQ(combine(CombineRule::Max, 0.2, 0.8), 0.8);
    EXPECT_DOUBLE_EQ(combine(CombineRule::Multiply, 0.2, 0.8), 0.16);
    EXPECT_DOUBLE_EQ(combine(CombineRule::GeometricMean, 0.2, 0.8), 0.4);
    // Geometric mean with a frictionless material is frictionless (why Box2D uses it).
    EXPECT_EQ(combine(CombineRule::GeometricMean, 0.0, 0.9), 0.0);
}

TEST(CombineRule, NamesRoundTrip) {
    for (auto rule : {CombineRule::Average, CombineRule::Min, CombineRule::Max, CombineRule::Multiply,
                      CombineRule::GeometricMean})
        EXPECT_EQ(combineRuleFromString(toString(rule)), rule);
    EXPECT_EQ(toString(CombineRule::GeometricMean), "geometric_mean");
    EXPECT_FALSE(combineRuleFromString("harmonic").has_value());
    EXPECT_EQ(combineRuleNames(), "average, min, max, multiply, geometric_mean");
}

TEST(MaterialLibrary, DefaultMaterialAlwaysExists) {
    MaterialLibrary lib;
    EXPECT_TRUE(lib.contains(""));
    EXPECT_EQ(lib.get("").friction, Material{}.friction);
    EXPECT_EQ(lib.get("").restitution, Material{}.restitution);
    EXPECT_EQ(lib.get("").density, Material{}.density);
    EXPECT_TRUE(lib.names().empty());
    EXPECT_EQ(lib.frictionRule(), CombineRule::GeometricMean);
    EXPECT_EQ(lib.restitutionRule(), CombineRule::Max);
}

TEST(MaterialLibrary, AddGetAndSortedNames) {
    MaterialLibrary lib = rubberAndIce();
    EXPECT_EQ(lib.get("rubber").friction, 0.9);
    EXPECT_EQ(lib.get("ice").density, 917);
    EXPECT_EQ(lib.names(), (std::vector<std::string>{"ice", "rubber"}));
    lib.add("rubber", Material{0.7, 0.5, 1200});  // replaces
    EXPECT_EQ(lib.get("rubber").friction, 0.7);
    EXPECT_EQ(lib.names().size(), 2u);
}

TEST(MaterialLibrary, UnknownNameListsKnownNames) {
    const MaterialLibrary lib = rubberAndIce();
    expectError([&] { (void)lib.get("steel"); }, {"\"steel\"", "ice", "rubber", "the default"});
    expectError([&] { (void)lib.resolve("rubber", "steel"); }, {"\"steel\"", "ice, rubber"});
}

TEST(MaterialLibrary, RejectsOutOfRangeValuesAndChangesNothing) {
    MaterialLibrary lib = rubberAndIce();
    expectError([&] { lib.add("rubber", Material{-0.1, 0.5, 1000}); }, {"materials.rubber.friction", "must be >= 0", "-0.1"});
    expectError([&] { lib.add("rubber", Material{0.5, 1.5, 1000}); },
                {"materials.rubber.restitution", "must be in [0, 1]", "1.5"});
    expectError([&] { lib.add("rubber", Material{0.5, -0.5, 1000}); }, {"materials.rubber.restitution"});
    expectError([&] { lib.add("rubber", Material{0.5, 0.5, 0}); }, {"materials.rubber.density", "must be > 0", "got 0"});
    expectError([&] { lib.add("steel", Material{NAN, 0.5, 7800}); }, {"materials.steel.friction", "nan"});
    expectError([&] { lib.add("steel", Material{0.5, 0.5, INFINITY}); }, {"materials.steel.density", "inf"});
    // Rejected calls left the library as it was.
    EXPECT_EQ(lib.get("rubber").friction, 0.9);
    EXPECT_EQ(lib.get("rubber").restitution, 0.8);
    EXPECT_FALSE(lib.contains("steel"));
}

TEST(MaterialLibrary, ResolveUsesDefaultRules) {
    const MaterialLibrary lib = rubberAndIce();
    const MixedMaterial m = lib.resolve("rubber", "ice");
    EXPECT_DOUBLE_EQ(m.friction, std::sqrt(0.9 * 0.04));  // geometric mean
    EXPECT_DOUBLE_EQ(m.restitution, 0.8);                  // max
    const MixedMaterial d = lib.resolve("", "");
    EXPECT_DOUBLE_EQ(d.friction, 0.6);
    EXPECT_DOUBLE_EQ(d.restitution, 0.0);
}

TEST(MaterialLibrary, ResolveFollowsSelectedRules) {
    MaterialLibrary lib = rubberAndIce();
    struct Case { CombineRule rule; double friction; double restitution; };
    const Case cases[] = {
        {CombineRule::Average, (0.9 + 0.04) / 2, (0.8 + 0.1) / 2},
        {CombineRule::Min, 0.04, 0.1},
        {CombineRule::Max, 0.9, 0.8},
        {CombineRule::Multiply, 0.9 * 0.04, 0.8 * 0.1},
        {CombineRule::GeometricMean, std::sqrt(0.9 * 0.04), std::sqrt(0.8 * 0.1)},
    };
    for (const auto& c : cases) {
        lib.setFrictionRule(c.rule);
        lib.setRestitutionRule(c.rule);
        const MixedMaterial m = lib.resolve("rubber", "ice");
        EXPECT_DOUBLE_EQ(m.friction, c.friction) << toString(c.rule);
        EXPECT_DOUBLE_EQ(m.restitution, c.restitution) << toString(c.rule);
        // Every rule is symmetric, bit for bit.
        EXPECT_EQ(lib.resolve("ice", "rubber").friction, m.friction) << toString(c.rule);
        EXPECT_EQ(lib.resolve("ice", "rubber").restitution, m.restitution) << toString(c.rule);
    }
}

TEST(MaterialLibrary, PairOverrideWinsAndIsSymmetric) {
    MaterialLibrary lib = rubberAndIce();
    lib.setPairOverride("rubber", "ice", PairOverride{0.1, std::nullopt});
    // Friction from the override, restitution still from the rule (max).
    for (const auto& m : {lib.resolve("rubber", "ice"), lib.resolve("ice", "rubber")}) {
        EXPECT_EQ(m.friction, 0.1);
        EXPECT_DOUBLE_EQ(m.restitution, 0.8);
    }
    ASSERT_TRUE(lib.pairOverride("ice", "rubber").has_value());
    EXPECT_EQ(lib.pairOverride("ice", "rubber")->friction, 0.1);
    EXPECT_EQ(lib.pairOverrides().size(), 1u);
    EXPECT_EQ(lib.pairOverrides().begin()->first, (std::pair<std::string, std::string>{"ice", "rubber"}));

    // Setting the pair again in the other order replaces the same entry.
    lib.setPairOverride("ice", "rubber", PairOverride{0.2, 0.3});
    EXPECT_EQ(lib.pairOverrides().size(), 1u);
    EXPECT_EQ(lib.resolve("rubber", "ice").friction, 0.2);
    EXPECT_EQ(lib.resolve("rubber", "ice").restitution, 0.3);
    // Other pairs are untouched.
    EXPECT_FALSE(lib.pairOverride("rubber", "rubber").has_value());
    EXPECT_DOUBLE_EQ(lib.resolve("rubber", "rubber").friction, 0.9);
}

TEST(MaterialLibrary, PairOverrideRejectsUnknownNamesAndBadValues) {
    MaterialLibrary lib = rubberAndIce();
    expectError([&] { lib.setPairOverride("rubber", "steel", PairOverride{0.1, 0.1}); },
                {"\"steel\"", "known materials", "ice, rubber"});
    expectError([&] { lib.setPairOverride("rubber", "ice", PairOverride{-1.0, std::nullopt}); },
                {"pair(ice, rubber).friction", "must be >= 0", "-1"});
    expectError([&] { lib.setPairOverride("rubber", "ice", PairOverride{std::nullopt, 2.0}); },
                {"pair(ice, rubber).restitution", "must be in [0, 1]", "got 2"});
    EXPECT_TRUE(lib.pairOverrides().empty());
}
