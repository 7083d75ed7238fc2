#pragma once
// Settings a backend reads already resolved. The layer fills every unset WorldSettings optional
// that a backend runs with (solver, substeps, iterations) from the backend's declared defaults
// (Capabilities::defaultSolver / defaultSubsteps / defaultIterations, by withBackendDefaults)
// before it creates the peer, so a default lives in one place and World::settings() shows it. A
// backend reads them through these accessors and never supplies a fallback of its own.
#include <optional>
#include <stdexcept>
#include <string>

#include "anyphys/world_settings.hpp"

namespace anyphys {

namespace detail {
template <class T>
T resolvedSetting(const std::optional<T>& value, const char* field) {
    if (!value)
        throw std::logic_error(std::string("WorldSettings.") + field +
                               " reached the backend unset: the layer resolves it first (withBackendDefaults)");
    return *value;
}
}  // namespace detail

inline Solver resolvedSolver(const WorldSettings& s) { return detail::resolvedSetting(s.solver, "solver"); }
inline int resolvedSubsteps(const WorldSettings& s) { return detail::resolvedSetting(s.substeps, "substeps"); }
inline int resolvedIterations(const WorldSettings& s) { return detail::resolvedSetting(s.iterations, "iterations"); }

/// A backend option's value, or `fallback` (its default) when the settings do not give it. The
/// layer has checked it against the range the backend lists (checkBackendOptions), so a count
/// casts to int safely.
inline double backendOption(const WorldSettings& s, const char* name, double fallback) {
    const auto it = s.backendOptions.find(name);
    return it == s.backendOptions.end() ? fallback : it->second;
}

}  // namespace anyphys
