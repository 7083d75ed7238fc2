#pragma once
// A backend descriptor and the registry of built backends.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "anyphys/capabilities.hpp"
#include "anyphys/peers/world_peer.hpp"
#include "anyphys/world_settings.hpp"

namespace anyphys {

struct Backend {
    std::string name;          ///< e.g. "native"
    std::string description;   ///< one line: engine and version
    Capabilities capabilities;
    /// Creates a world; settings are validated and checked against the capabilities.
    std::function<std::unique_ptr<WorldPeer>(const WorldSettings&)> createWorld;
};

/// The backends this build contains, in registration order.
const std::vector<Backend>& registeredBackends();
/// The backend of that name; throws anyphys::Error listing the known names otherwise.
const Backend& findBackend(const std::string& name);

}  // namespace anyphys
