#pragma once
// The contract suite runs every test once per built backend. A backend that lacks a capability
// a test needs is skipped by capability, with the reason printed (never by backend name).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::test {

/// A dynamic body at the origin with a sphere of `radius` (a def has no default shape).
inline BodyDef sphereDef(double radius) {
    BodyDef d;
    d.shape = ShapeDef::sphere(radius);
    return d;
}

/// The bound of a mass-scaling case: how far a run with every mass scaled may exceed the same run
/// at the scene's masses (`light`, in any measure where more is worse). Scaling every mass changes
/// no motion under gravity, contacts and joints, so the runs differ only by rounding, which a
/// structure that already sways turns into another sway: twice the light run's figure, and at
/// least 1 mm more. A softness fixed in absolute terms exceeds it by the mass factor.
inline double massScalingBound(double light) { return std::max(2.0 * light, light + 1e-3); }

/// The names of the built backends. Computed once per process: every suite's instantiation asks,
/// and each test runs in a process of its own under ctest, where copying every backend's
/// capabilities per suite was an eighth of a sanitizer build's start-up.
inline const std::vector<std::string>& builtBackendNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const auto& info : availableBackends()) out.push_back(info.name);
        return out;
    }();
    return names;
}

class ContractTest : public ::testing::TestWithParam<std::string> {
protected:
    /// Contract tests build 3D worlds unless their fixture says planar: a planar-only (2D)
    /// backend skips them, visibly, by its dimensions capability.
    virtual bool planarTest() const { return false; }
    /// A suite whose cases need no third dimension (bad input, queries, sleeping, materials)
    /// says so: on a backend without 3D worlds it then runs in a planar world, not skipped.
    virtual bool runsPlanarWithout3D() const { return false; }
    /// Whether this test's worlds are planar: a planar suite, or a suite that needs no third
    /// dimension on a backend that has none.
    bool planarWorld() const { return planarTest() || (runsPlanarWithout3D() && caps().dimensions < 3); }

    void SetUp() override {
        if (!planarWorld() && caps().dimensions < 3)
            GTEST_SKIP() << "backend " << backend() << " lacks 3D worlds (dimensions " << caps().dimensions << ")";
        if (planarWorld() && !caps().planar) GTEST_SKIP() << "backend " << backend() << " lacks planar worlds";
        if (planarWorld() && !planarTest())
            std::cout << "[ PLANAR   ] backend " << backend() << " has no 3D worlds: this suite runs in a planar world\n";
    }

    const std::string& backend() const { return GetParam(); }
    Capabilities caps() const { return backendInfo(backend()).capabilities; }

    /// Checks a named contract criterion. If the backend declares it as a known deviation, a
    /// miss is printed (measured value and the backend's reason) instead of failing, and a pass
    /// fails, because the declaration has become untrue.
    /// With `value` (the criterion's measure), a declared miss must also stay within the
    /// backend's ceiling for it, if it declares one.
    void expectCriterion(const std::string& id, bool met, const std::string& measured,
                         std::optional<double> value = std::nullopt) const {
        const Capabilities c = caps();  // caps() returns a copy: iterators need it alive
        const auto it = c.knownDeviations.find(id);
        const auto ceiling = c.deviationCeilings.find(id);
        if (it == c.knownDeviations.end()) {
            EXPECT_TRUE(met) << "criterion " << id << " missed: " << measured;
        } else if (!met && value && ceiling != c.deviationCeilings.end() && !(*value <= ceiling->second)) {
            ADD_FAILURE() << "backend " << backend() << " misses " << id << " worse than its declared ceiling "
                          << ceiling->second << ": " << measured;
        } else if (met) {
            ADD_FAILURE() << "backend " << backend() << " declares criterion " << id
                          << " a known deviation, but it now passes (" << measured << "): update its capabilities";
        } else {
            std::cout << "[ KNOWN    ] backend " << backend() << " misses " << id << ": " << measured << " ("
                      << it->second << ")" << (value ? " [measure " + std::to_string(*value) + "]" : "")
                      << (ceiling != c.deviationCeilings.end() ? " [ceiling " + std::to_string(ceiling->second) + "]" : "")
                      << "\n";
            ::testing::Test::RecordProperty("known_deviation_" + id, measured);
        }
    }

    /// Rounding in the engine's arithmetic: `roundings` roundings of a quantity of size
    /// `magnitude`. A result "exact up to rounding" is within this of the exact value; it is
    /// about 1e-16 relative per rounding for double engines and 6e-8 for float ones.
    double rounding(double magnitude, double roundings = 1) const {
        return caps().unitRoundoff * std::abs(magnitude) * roundings;
    }

    WorldSettings settings() const {
        WorldSettings s;
        s.backend = backend();
        s.planar = planarWorld();
        return s;
    }

    /// `base` once per solver the backend offers, at 1 and (where the backend honours substeps)
    /// 4 substeps: the settings a contract criterion is checked under when it must hold for every
    /// solver and substep count. `variantName` gives each one's criterion suffix.
    std::vector<WorldSettings> everySolverAndSubstepCount(const WorldSettings& base) const {
        const bool substeps = caps().parameters.contains("settings.substeps");
        std::vector<WorldSettings> out;
        for (Solver solver : caps().solvers)
            for (int n : substeps ? std::vector<int>{1, 4} : std::vector<int>{1}) {
                WorldSettings s = base;
                s.solver = solver;
                s.substeps = n;
                out.push_back(s);
            }
        return out;
    }

    /// "<solver>.s<substeps>", e.g. "pgs.s4", for settings from `everySolverAndSubstepCount`.
    static std::string variantName(const WorldSettings& s) {
        return std::string(toString(s.solver.value())) + ".s" + std::to_string(s.substeps.value());
    }
};

inline std::string backendTestName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

/// Skips the current test, visibly, when the backend lacks what it needs.
#define ANYPHYS_REQUIRE(condition, what)                                                   \
    do {                                                                                   \
        if (!(condition)) GTEST_SKIP() << "backend " << backend() << " lacks " << (what); \
    } while (0)

#define ANYPHYS_CONTRACT_SUITE(Suite) \
    INSTANTIATE_TEST_SUITE_P(AllBackends, Suite, ::testing::ValuesIn(::anyphys::test::builtBackendNames()), \
                             ::anyphys::test::backendTestName)

}  // namespace anyphys::test
