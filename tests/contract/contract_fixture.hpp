#pragma once
// The contract suite runs every test once per built backend. A backend that lacks a capability
// a test needs is skipped by capability, with the reason printed (never by backend name).
#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::test {

inline std::vector<std::string> builtBackendNames() {
    std::vector<std::string> names;
    for (const auto& info : availableBackends()) names.push_back(info.name);
    return names;
}

class ContractTest : public ::testing::TestWithParam<std::string> {
protected:
    /// Contract tests build 3D worlds unless their fixture says planar: a planar-only (2D)
    /// backend skips them, visibly, by its dimensions capability.
    virtual bool planarTest() const { return false; }

    void SetUp() override {
        if (!planarTest() && caps().dimensions < 3)
            GTEST_SKIP() << "backend " << backend() << " lacks 3D worlds (dimensions " << caps().dimensions << ")";
        if (planarTest() && !caps().planar) GTEST_SKIP() << "backend " << backend() << " lacks planar worlds";
    }

    const std::string& backend() const { return GetParam(); }
    Capabilities caps() const { return backendInfo(backend()).capabilities; }

    /// Checks a named contract criterion. If the backend declares it as a known deviation, a
    /// miss is printed (measured value and the backend's reason) instead of failing, and a pass
    /// fails, because the declaration has become untrue.
    void expectCriterion(const std::string& id, bool met, const std::string& measured) const {
        const auto& known = caps().knownDeviations;
        const auto it = known.find(id);
        if (it == known.end()) {
            EXPECT_TRUE(met) << "criterion " << id << " missed: " << measured;
        } else if (met) {
            ADD_FAILURE() << "backend " << backend() << " declares criterion " << id
                          << " a known deviation, but it now passes (" << measured << "): update its capabilities";
        } else {
            std::cout << "[ KNOWN    ] backend " << backend() << " misses " << id << ": " << measured << " ("
                      << it->second << ")\n";
            ::testing::Test::RecordProperty("known_deviation_" + id, measured);
        }
    }

    WorldSettings settings() const {
        WorldSettings s;
        s.backend = backend();
        s.planar = planarTest();
        return s;
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
