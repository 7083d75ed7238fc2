#pragma once
// Which backends this build contains and what each honours.
#include <string>
#include <string_view>
#include <vector>

#include "anyphys/capabilities.hpp"
#include "anyphys/effects.hpp"

namespace anyphys {

struct BackendInfo {
    std::string name;
    std::string description;
    Capabilities capabilities;
};

/// Every built backend, in registration order (native first).
std::vector<BackendInfo> availableBackends();
/// The named backend's info; throws anyphys::Error listing the known names if unknown.
BackendInfo backendInfo(const std::string& name);
/// `settings` as a world of this backend runs them: an unset solver, substep count or iteration
/// count takes the backend's declared default (Capabilities::defaultSolver, defaultSubsteps,
/// defaultIterations); unset iterations with fewer substeps than the default are raised to keep
/// the default work per step (native's 8 substeps x 1 iteration becomes 1 x 8: one sweep per
/// step cannot hold a stack). The one place these defaults are filled in: World resolves its
/// settings with it before the backend sees them (so World::settings() shows what runs), and the
/// tool reports configurations with it.
struct WorldSettings withBackendDefaults(struct WorldSettings settings, const Capabilities& caps);
/// Names of what `settings` (plus content needing `effects`) asks for that the backend lacks,
/// e.g. {"integrator rk4", "effect contacts"}. Empty when everything is honoured.
std::vector<std::string> missingCapabilities(const Capabilities& caps, const struct WorldSettings& settings, Effects effects);
/// The option `name` among those the backend lists, or nullptr.
const BackendOption* findOption(const Capabilities& caps, std::string_view name);
/// Throws anyphys::Error of kind InvalidArgument naming "WorldSettings.backendOptions.<name>",
/// the value and the option's range (BackendOption::allowed) for the first option the backend
/// lists whose value it does not take. Options it does not list are missingCapabilities' concern.
void checkBackendOptions(const Capabilities& caps, const struct WorldSettings& settings);
/// What a joint asks for that the backend lacks: "joint type cone", "effect joints", or the
/// parameters it uses by name ("joint.hinge.motor"; see joint_capabilities.hpp). `planar`: the
/// world is planar (a ball joint then runs as a hinge). Empty when everything is honoured.
std::vector<std::string> missingJointCapabilities(const Capabilities& caps, const struct JointDef& def, bool planar);

}  // namespace anyphys
