// Parsing and applying sweep axes. Setting names are those of the scene format
// (containers/src/scene_json.cpp), so a sweep reads like the scene file it varies.
#include "sweep_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "anyphys/validation.hpp"
#include "cli.hpp"

namespace anyphys::cli {
namespace {

/// The plain numeric settings a sweep may vary, by scene-format key.
struct NumberSetting {
    const char* name;
    double WorldSettings::*field;
};
constexpr NumberSetting kNumberSettings[] = {
    {"contactHertz", &WorldSettings::contactHertz},
    {"contactDampingRatio", &WorldSettings::contactDampingRatio},
    {"contactPushMaxVelocity", &WorldSettings::contactPushMaxVelocity},
    {"baumgarte", &WorldSettings::baumgarte},
    {"restitutionThreshold", &WorldSettings::restitutionThreshold},
    {"linearSlop", &WorldSettings::linearSlop},
    {"speculativeDistance", &WorldSettings::speculativeDistance},
    {"sleepLinearVelocity", &WorldSettings::sleepLinearVelocity},
    {"sleepAngularVelocity", &WorldSettings::sleepAngularVelocity},
    {"timeToSleep", &WorldSettings::timeToSleep},
};

const NumberSetting* numberSetting(const std::string& name) {
    for (const NumberSetting& s : kNumberSettings)
        if (name == s.name) return &s;
    return nullptr;
}

/// Backend option names offered by some built backend.
std::set<std::string> backendOptionNames() {
    std::set<std::string> names;
    for (const BackendInfo& b : availableBackends())
        for (const BackendOption& option : b.capabilities.options) names.insert(option.name);
    return names;
}

/// An axis named "backendOptions.NAME" is always the backend option, even where a setting has
/// the same name (Bullet's linearSlop option and settings.linearSlop).
constexpr std::string_view kOptionPrefix = "backendOptions.";

/// The backend option an axis name stands for, when it is not a setting.
std::string optionName(const std::string& axis) {
    return axis.starts_with(kOptionPrefix) ? axis.substr(kOptionPrefix.size()) : axis;
}

std::string effectOffNames() {
    std::string out = "none";
    for (const auto& e : kEffectNames) out += ", " + std::string(e.name);
    return out;
}

std::optional<double> parseNumber(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

/// A time step: a number or a fraction "a/b" (1/60 reads better than 0.016666666666666666).
std::optional<double> parseTimeStep(const std::string& text) {
    const auto slash = text.find('/');
    if (slash == std::string::npos) return parseNumber(text);
    const auto a = parseNumber(text.substr(0, slash)), b = parseNumber(text.substr(slash + 1));
    if (!a || !b || *b == 0.0) return std::nullopt;
    return *a / *b;
}

[[noreturn]] void badValue(const std::string& spec, const std::string& value, const std::string& allowed) {
    throw Error("--sweep " + spec + ": value \"" + value + "\" " + allowed);
}

/// The normalised value, or throws naming it.
std::string normalise(const std::string& spec, const std::string& name, const std::string& value) {
    if (name == "timeStep") {
        const auto v = parseTimeStep(value);
        if (!v || *v <= 0.0) badValue(spec, value, "is not allowed: timeStep must be a number > 0 or a fraction like 1/60");
        return exactNumber(*v);
    }
    if (name == "substeps" || name == "iterations") {
        const auto v = parseNumber(value);
        if (!v || *v < 1 || *v != std::floor(*v) || *v > 1e6)
            badValue(spec, value, "is not allowed: " + name + " must be a whole number >= 1");
        return exactNumber(*v);
    }
    if (name == "integrator") {
        if (!fromString<Integrator>(value)) badValue(spec, value, "is not allowed: integrator must be one of " + allowedNames<Integrator>());
        return value;
    }
    if (name == "solver") {
        if (!fromString<Solver>(value)) badValue(spec, value, "is not allowed: solver must be one of " + allowedNames<Solver>());
        return value;
    }
    if (name == "effectOff") {
        if (value != "none" && !effectFromString(value))
            badValue(spec, value, "is not allowed: effectOff must be one of " + effectOffNames());
        return value;
    }
    const auto v = parseNumber(value);
    if (!v) badValue(spec, value, "is not allowed: " + name + " must be a number");
    if (const NumberSetting* s = numberSetting(name)) {
        WorldSettings probe;  // the World's own range rule, checked now rather than per run
        probe.*(s->field) = *v;
        try {
            validate(probe, "settings");
        } catch (const Error& e) {
            badValue(spec, value, std::string("is not allowed: ") + e.what());
        }
    }
    return exactNumber(*v);
}

}  // namespace

std::string allowedAxisNames() {
    std::string out = "timeStep, substeps, iterations, integrator, solver";
    for (const NumberSetting& s : kNumberSettings) out += ", " + std::string(s.name);
    const std::set<std::string> options = backendOptionNames();
    out += ", effectOff, or a backend option (" + join({options.begin(), options.end()}) +
           "; backendOptions.NAME for one named like a setting)";
    return out;
}

SweepAxis parseSweepAxis(const std::string& spec) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0)
        throw Error("--sweep \"" + spec + "\": expected NAME=V1,V2,... (e.g. timeStep=1/30,1/60)");
    SweepAxis axis;
    axis.name = spec.substr(0, eq);
    const bool known = axis.name == "timeStep" || axis.name == "substeps" || axis.name == "iterations" ||
                       axis.name == "integrator" || axis.name == "solver" || axis.name == "effectOff" ||
                       numberSetting(axis.name) || backendOptionNames().contains(optionName(axis.name));
    if (!known) throw Error("--sweep " + spec + ": unknown setting \"" + axis.name + "\"; allowed: " + allowedAxisNames());
    std::string rest = spec.substr(eq + 1);
    std::size_t start = 0;
    while (true) {
        const auto comma = rest.find(',', start);
        std::string value = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (value.empty()) badValue(spec, value, "is empty: give values separated by single commas");
        if (value.find_first_of(" \t\n") != std::string::npos)
            badValue(spec, value, "is not allowed: give values separated by commas without spaces");
        axis.values.push_back(normalise(spec, axis.name, value));
        axis.given.push_back(value);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return axis;
}

double axisNumber(const std::string& value) { return std::strtod(value.c_str(), nullptr); }

std::optional<std::string> applyAxisValue(const std::string& name, const std::string& value, const Capabilities& caps,
                                          WorldSettings& settings, const std::function<Effects()>& derivedEffects) {
    const auto honours = [&caps](const std::string& parameter) { return caps.parameters.contains(parameter); };
    if (name == "integrator") {
        settings.integrator = *fromString<Integrator>(value);
        if (!caps.integrators.contains(settings.integrator)) return "integrator " + value + " not offered by this backend";
        return std::nullopt;
    }
    if (name == "solver") {
        settings.solver = *fromString<Solver>(value);
        if (!caps.solvers.contains(*settings.solver)) return "solver " + value + " not offered by this backend";
        return std::nullopt;
    }
    if (name == "effectOff") {
        Effects effects = derivedEffects();
        if (value != "none") {
            const Effect off = *effectFromString(value);
            if (!caps.effects.has(off)) return "effect " + value + " not offered by this backend";
            effects.remove(off);
        }
        settings.effects = effects;
        if (!honours("settings.effects")) return "settings.effects not honoured by this backend";
        return std::nullopt;
    }
    const double v = axisNumber(value);
    if (name == "timeStep") settings.timeStep = v;
    else if (name == "substeps") settings.substeps = static_cast<int>(v);
    else if (name == "iterations") settings.iterations = static_cast<int>(v);
    else if (const NumberSetting* s = numberSetting(name)) settings.*(s->field) = v;
    else {
        const std::string option = optionName(name);
        settings.backendOptions[option] = v;
        if (!findOption(caps, option)) return "backend option " + option + " not offered by this backend";
        return std::nullopt;
    }
    if (!honours("settings." + name)) return "settings." + name + " not honoured by this backend";
    return std::nullopt;
}

}  // namespace anyphys::cli
