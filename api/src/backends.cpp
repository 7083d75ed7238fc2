#include "anyphys/backends.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "anyphys/error.hpp"
#include "anyphys/joint_capabilities.hpp"
#include "anyphys/peers/backend.hpp"
#include "anyphys/world_settings.hpp"

namespace anyphys {

std::vector<BackendInfo> availableBackends() {
    std::vector<BackendInfo> out;
    for (const Backend& b : registeredBackends()) out.push_back({b.name, b.description, b.capabilities});
    return out;
}

BackendInfo backendInfo(const std::string& name) {
    const Backend& b = findBackend(name);
    return {b.name, b.description, b.capabilities};
}

WorldSettings withBackendDefaults(WorldSettings s, const Capabilities& caps) {
    if (!s.solver) s.solver = caps.defaultSolver;
    if (!s.substeps) s.substeps = caps.defaultSubsteps;
    if (!s.iterations) {
        const int work = caps.defaultIterations * caps.defaultSubsteps;
        s.iterations = std::max(caps.defaultIterations, (work + *s.substeps - 1) / *s.substeps);
    }
    return s;
}

std::vector<std::string> missingCapabilities(const Capabilities& caps, const WorldSettings& settings, Effects effects) {
    std::vector<std::string> missing;
    if (settings.planar && !caps.planar) missing.push_back("planar worlds");
    if (!settings.planar && caps.dimensions < 3) missing.push_back("3D worlds (planar only)");
    if (!caps.integrators.count(settings.integrator))
        missing.push_back("integrator " + std::string(toString(settings.integrator)));
    for (const auto& name : (effects & ~caps.effects).names()) missing.push_back("effect " + name);
    const bool constrained = effects.has(Effect::Contacts) || effects.has(Effect::Joints);
    if (constrained && settings.solver && !caps.solvers.count(*settings.solver))
        missing.push_back("solver " + std::string(toString(*settings.solver)));
    if (settings.substeps && !caps.parameters.count("settings.substeps")) missing.push_back("settings.substeps");
    if (constrained && settings.iterations && !caps.parameters.count("settings.iterations"))
        missing.push_back("settings.iterations");
    for (const auto& [name, value] : settings.backendOptions)
        if (!findOption(caps, name)) missing.push_back("backend option " + name);
    return missing;
}

std::string BackendOption::allowed() const {
    std::ostringstream os;
    os << (integer ? "an integer" : "a number");
    if (std::isinf(max) && std::isinf(min))
        os << " (finite)";
    else if (std::isinf(max))
        os << " >= " << min;
    else
        os << " in [" << min << ", " << max << "]";
    return os.str();
}

const BackendOption* findOption(const Capabilities& caps, std::string_view name) {
    const auto it = std::find_if(caps.options.begin(), caps.options.end(), [name](const BackendOption& o) { return o.name == name; });
    return it == caps.options.end() ? nullptr : &*it;
}

void checkBackendOptions(const Capabilities& caps, const WorldSettings& settings) {
    for (const auto& [name, value] : settings.backendOptions) {
        const BackendOption* option = findOption(caps, name);
        if (!option) continue;  // not listed: missingCapabilities reports it
        const bool inRange = value >= option->min && value <= option->max;  // false for NaN
        if (!inRange || (option->integer && value != std::floor(value)))
            throw Error::invalid("WorldSettings.backendOptions." + name, value, "must be " + option->allowed());
    }
}

std::vector<std::string> missingJointCapabilities(const Capabilities& caps, const JointDef& def, bool planar) {
    std::vector<std::string> missing;
    if (!caps.effects.has(Effect::Joints)) missing.push_back("effect joints");
    const std::string type(toString(peerJointType(def.type, planar)));
    if (!caps.jointTypes.contains(type)) {
        missing.push_back("joint type " + type);
        return missing;  // its parameters are missing with it
    }
    for (const auto& [field, parameter] : usedJointParameters(def, planar))
        if (!caps.parameters.contains(parameter)) missing.push_back(parameter);
    return missing;
}

}  // namespace anyphys
