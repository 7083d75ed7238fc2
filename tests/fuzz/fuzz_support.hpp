#pragma once
// Shared by the fuzzers (tests/fuzz, docs/reliability.md): the rule that anything but an
// anyphys::Error escaping a call is a crash, and the backends this build has.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::fuzz {

/// Runs `f`; an anyphys::Error is the documented refusal and is swallowed (after checking it
/// carries a message); any other exception aborts, so libFuzzer records the input as a crash.
template <class F>
bool refusedOrDone(F&& f) {
    try {
        f();
        return true;
    } catch (const Error& e) {
        if (std::getenv("ANYPHYS_FUZZ_TRACE")) std::fprintf(stderr, "  refused: %s\n", e.what());
        if (std::string(e.what()).empty()) {
            std::fprintf(stderr, "fuzz: anyphys::Error with an empty message\n");
            std::abort();
        }
        return false;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz: a %s escaped (not an anyphys::Error): %s\n", typeid(e).name(), e.what());
        std::abort();
    } catch (...) {
        std::fprintf(stderr, "fuzz: a non-std exception escaped\n");
        std::abort();
    }
}

/// Every built backend's name, looked up once.
inline const std::vector<BackendInfo>& backends() {
    static const std::vector<BackendInfo> all = availableBackends();
    return all;
}

}  // namespace anyphys::fuzz
