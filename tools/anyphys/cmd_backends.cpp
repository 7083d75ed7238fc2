// `anyphys backends [--json]`: every built backend and what it honours.
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli.hpp"

namespace anyphys::cli {
namespace {

std::string_view forceEvaluationName(ForceEvaluation f) {
    return f == ForceEvaluation::PerStage ? "per_stage" : "per_step";
}

std::vector<std::string> missingPairNames(const Capabilities& caps) {
    std::vector<std::string> out;
    for (const auto& [a, b] : caps.missingShapePairs) out.push_back(std::string(toString(a)) + "-" + std::string(toString(b)));
    return out;
}

/// Capabilities with scene-file names, so the output can be matched against scene files.
nlohmann::json capabilitiesJson(const Capabilities& caps) {
    nlohmann::json options = nlohmann::json::object(), optionsAllowed = nlohmann::json::object();
    for (const BackendOption& option : caps.options) {
        options[option.name] = option.meaning;
        optionsAllowed[option.name] = option.allowed();
    }
    return {
        {"dimensions", caps.dimensions},
        {"unitRoundoff", caps.unitRoundoff},
        {"planar", caps.planar},
        {"shapes", enumNames(caps.shapes)},
        {"bodyTypes", enumNames(caps.bodyTypes)},
        {"jointTypes", std::vector<std::string>(caps.jointTypes.begin(), caps.jointTypes.end())},
        {"effects", caps.effects.names()},
        {"integrators", enumNames(caps.integrators)},
        {"solvers", enumNames(caps.solvers)},
        {"defaultSolver", toString(caps.defaultSolver)},
        {"defaultSubsteps", caps.defaultSubsteps},
        {"defaultIterations", caps.defaultIterations},
        {"gyroscopicModes", enumNames(caps.gyroscopicModes)},
        {"forceEvaluation", forceEvaluationName(caps.forceEvaluation)},
        {"parameters", std::vector<std::string>(caps.parameters.begin(), caps.parameters.end())},
        {"options", options},
        {"optionsAllowed", optionsAllowed},
        {"knownDeviations", caps.knownDeviations},
        {"deviationCeilings", caps.deviationCeilings},
        {"missingShapePairs", missingPairNames(caps)},
        {"lightestBody", caps.lightestBody},
        {"heaviestBody", caps.heaviestBody},
    };
}

std::string orNone(const std::vector<std::string>& items) { return items.empty() ? "-" : join(items); }

/// The joint fields honoured per type, "hinge: limits, motor; slider: ..." from the
/// "joint.<type>.<field>" parameters; the other parameters are returned in `rest`.
std::string jointFieldsByType(const Capabilities& c, std::vector<std::string>& rest) {
    std::map<std::string, std::vector<std::string>> byType;
    for (const std::string& p : c.parameters) {
        const auto dot = p.find('.', 6);
        if (p.starts_with("joint.") && dot != std::string::npos)
            byType[p.substr(6, dot - 6)].push_back(p.substr(dot + 1));
        else
            rest.push_back(p);
    }
    std::string out;
    for (const auto& [type, fields] : byType) out += (out.empty() ? "" : "; ") + type + ": " + join(fields);
    return out.empty() ? "-" : out;
}


void printText(const std::vector<BackendInfo>& backends) {
    for (const BackendInfo& b : backends) {
        const Capabilities& c = b.capabilities;
        std::cout << b.name << "  (" << c.dimensions << "D" << (c.planar ? ", planar" : "") << ")  "
                  << b.description << '\n';
        const auto row = [](std::string_view label, const std::string& value) {
            std::cout << "  " << label << std::string(18 - label.size(), ' ') << value << '\n';
        };
        row("shapes", orNone(enumNames(c.shapes)));
        row("body types", orNone(enumNames(c.bodyTypes)));
        row("joint types", orNone({c.jointTypes.begin(), c.jointTypes.end()}));
        row("effects", orNone(c.effects.names()));
        {
            std::ostringstream roundoff;
            roundoff << c.unitRoundoff << (c.unitRoundoff > 0x1p-30 ? " (steps in float)" : " (steps in double)");
            row("unit roundoff", roundoff.str());
        }
        row("integrators", orNone(enumNames(c.integrators)));
        row("solvers", orNone(enumNames(c.solvers)) + " (default " + std::string(toString(c.defaultSolver)) + ", " +
                           std::to_string(c.defaultSubsteps) + " substeps x " + std::to_string(c.defaultIterations) +
                           " iterations)");
        row("gyroscopic modes", orNone(enumNames(c.gyroscopicModes)));
        row("force evaluation", std::string(forceEvaluationName(c.forceEvaluation)));
        std::vector<std::string> parameters;
        const std::string jointFields = jointFieldsByType(c, parameters);
        row("joint fields", jointFields);
        row("parameters", orNone(parameters));
        std::vector<std::string> options;
        for (const BackendOption& option : c.options)
            options.push_back(option.name + " (" + option.meaning + "; " + option.allowed() + ")");
        row("options", orNone(options));
        row("missing pairs", orNone(missingPairNames(c)));
        {
            std::ostringstream range;
            range.precision(3);
            if (c.lightestBody > 0.0 || c.heaviestBody > 0.0)
                range << (c.lightestBody > 0.0 ? c.lightestBody : kMinMass) << " to "
                      << (c.heaviestBody > 0.0 ? c.heaviestBody : kMaxMass) << " kg";
            else
                range << "any (the layer's " << kMinMass << " to " << kMaxMass << " kg)";
            row("body masses", range.str());
        }
        for (const auto& [criterion, reason] : c.knownDeviations) {
            const auto ceiling = c.deviationCeilings.find(criterion);
            const std::string limit = ceiling == c.deviationCeilings.end() ? "" : " [ceiling " + std::to_string(ceiling->second) + "]";
            row("known deviation", criterion + ": " + reason + limit);
        }
    }
}

}  // namespace

Command addBackendsCommand(CLI::App& parent) {
    auto json = std::make_shared<bool>(false);
    CLI::App* app = parent.add_subcommand("backends", "List the built backends and their capabilities");
    app->add_flag("--json", *json, "Print JSON with every capability field (scene-file names)");
    return {app, [json] {
                const std::vector<BackendInfo> backends = availableBackends();
                if (*json) {
                    nlohmann::json list = nlohmann::json::array();
                    for (const BackendInfo& b : backends)
                        list.push_back({{"name", b.name},
                                        {"description", b.description},
                                        {"capabilities", capabilitiesJson(b.capabilities)}});
                    std::cout << nlohmann::json{{"backends", list}}.dump(2) << '\n';
                } else {
                    printText(backends);
                }
                return 0;
            }};
}

}  // namespace anyphys::cli
