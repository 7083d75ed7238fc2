// `anyphys hardcases`: the hard-case catalogue (tall stacks, wide pyramids, mass ratios, deep
// overlap, far from the origin, fast bodies, ragdoll piles...) on every backend, sleeping off,
// as a matrix of case x backend: the measured figure against the case's bound, and whether it
// passes, misses (FAIL), or misses as the backend declares (known, within its ceiling).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "compare.hpp"

namespace anyphys::cli {
namespace {

struct HardCaseOptions {
    std::vector<std::string> cases;
    std::vector<std::string> backends;
    bool fast = false;
    bool json = false;
};

/// Cases of at most this many bodies make the fast subset (--fast, run in CI).
constexpr std::size_t kFastCaseBodies = 100;

enum class Verdict {
    Pass,
    Fail,           ///< missed, undeclared
    Known,          ///< missed as the backend declares, within its ceiling
    OverCeiling,    ///< missed as declared, but worse than the declared ceiling
    StaleDeclared,  ///< passes, yet the backend declares it missed
    NotApplicable,  ///< the backend lacks what the scene needs
    Error,          ///< the backend threw while stepping
};

const char* word(Verdict v) {
    switch (v) {
        case Verdict::Pass: return "pass";
        case Verdict::Fail: return "FAIL";
        case Verdict::Known: return "known";
        case Verdict::OverCeiling: return "FAIL: over ceiling";
        case Verdict::StaleDeclared: return "FAIL: passes but declared";
        case Verdict::NotApplicable: return "n/a";
        case Verdict::Error: return "ERROR";
    }
    return "?";
}

bool gates(Verdict v) {
    return v == Verdict::Fail || v == Verdict::OverCeiling || v == Verdict::StaleDeclared || v == Verdict::Error;
}

struct Cell {
    ComboResult result;
    Verdict verdict = Verdict::NotApplicable;
    std::optional<double> ceiling;  ///< the backend's declared ceiling for this criterion
};

Cell judge(const CatalogueScene& scene, const BackendInfo& backend) {
    Cell cell;
    cell.result = runCombo(scene, backend, scene.scene.settings.integrator);
    const ComboResult& r = cell.result;
    if (r.status == ComboResult::Status::Unsupported) return cell;
    if (r.status == ComboResult::Status::Failed || !r.checkValue) {
        cell.verdict = Verdict::Error;
        return cell;
    }
    const std::string& criterion = scene.check->criterion;
    const Capabilities& caps = backend.capabilities;
    const bool declared = caps.knownDeviations.contains(criterion);
    if (const auto it = caps.deviationCeilings.find(criterion); it != caps.deviationCeilings.end()) cell.ceiling = it->second;
    if (r.checkPassed) cell.verdict = declared ? Verdict::StaleDeclared : Verdict::Pass;
    else if (!declared) cell.verdict = Verdict::Fail;
    else if (cell.ceiling && !(*r.checkValue <= *cell.ceiling)) cell.verdict = Verdict::OverCeiling;
    else cell.verdict = Verdict::Known;
    return cell;
}

std::string cellText(const Cell& c) {
    if (c.verdict == Verdict::NotApplicable) return "n/a";
    if (c.verdict == Verdict::Error) return "ERROR";
    return printfNumber("%.3g", *c.result.checkValue) + " " + word(c.verdict);
}

void printMatrix(const std::vector<const CatalogueScene*>& cases, const std::vector<BackendInfo>& backends,
                 const std::vector<std::vector<Cell>>& cells) {
    std::size_t nameWidth = 9;
    for (const CatalogueScene* c : cases) nameWidth = std::max(nameWidth, c->name.size());
    std::size_t cellWidth = 8;
    for (const auto& row : cells)
        for (const Cell& cell : row) cellWidth = std::max(cellWidth, cellText(cell).size());
    std::printf("%-*s  %-22s", int(nameWidth), "hard case", "measure (bound)");
    for (const BackendInfo& b : backends) std::printf("  %-*s", int(cellWidth), b.name.c_str());
    std::printf("\n");
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const SceneCheck& check = *cases[i]->check;
        const std::string measure = check.label + " (" + printfNumber("%g", check.tolerance) + (check.unit.empty() ? "" : " ") + check.unit + ")";
        std::printf("%-*s  %-22s", int(nameWidth), cases[i]->name.c_str(), measure.c_str());
        for (const Cell& cell : cells[i]) std::printf("  %-*s", int(cellWidth), cellText(cell).c_str());
        std::printf("\n");
    }
    std::printf("\nEach cell: the case's measure over the whole run (sleeping off) and its verdict against the bound: "
                "pass; FAIL; known (the backend declares the miss, within its ceiling); n/a (the backend lacks a shape, "
                "joint or planar worlds the case needs).\n");
    // What the gating and n/a cells mean in words, so the matrix needs no other document.
    for (std::size_t i = 0; i < cases.size(); ++i)
        for (std::size_t j = 0; j < backends.size(); ++j) {
            const Cell& cell = cells[i][j];
            if (cell.verdict == Verdict::NotApplicable || cell.verdict == Verdict::Error)
                std::printf("  %s on %s: %s: %s\n", cases[i]->name.c_str(), backends[j].name.c_str(), word(cell.verdict),
                            cell.result.reason.c_str());
            else if (cell.verdict == Verdict::Known || cell.verdict == Verdict::OverCeiling)
                std::printf("  %s on %s: %s%s: %s\n", cases[i]->name.c_str(), backends[j].name.c_str(), word(cell.verdict),
                            cell.ceiling ? (" (ceiling " + printfNumber("%g", *cell.ceiling) + ")").c_str() : "",
                            backends[j].capabilities.knownDeviations.at(cases[i]->check->criterion).c_str());
        }
}

nlohmann::json toJson(const std::vector<const CatalogueScene*>& cases, const std::vector<BackendInfo>& backends,
                      const std::vector<std::vector<Cell>>& cells) {
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const SceneCheck& check = *cases[i]->check;
        nlohmann::json results = nlohmann::json::object();
        for (std::size_t j = 0; j < backends.size(); ++j) {
            const Cell& cell = cells[i][j];
            nlohmann::json r = {{"verdict", word(cell.verdict)}};
            if (cell.result.checkValue) r["value"] = *cell.result.checkValue;
            if (cell.ceiling) r["ceiling"] = *cell.ceiling;
            if (!cell.result.reason.empty()) r["reason"] = cell.result.reason;
            if (cell.result.steps > 0 && cell.result.status == ComboResult::Status::Ok)
                r["msPerStep"] = cell.result.wallMs / static_cast<double>(cell.result.steps);
            results[backends[j].name] = r;
        }
        list.push_back({{"name", cases[i]->name},
                        {"description", cases[i]->description},
                        {"bodies", cases[i]->scene.bodies.size()},
                        {"duration", cases[i]->duration},
                        {"measure", check.label},
                        {"unit", check.unit},
                        {"bound", check.tolerance},
                        {"why", check.why},
                        {"criterion", check.criterion},
                        {"results", results}});
    }
    return {{"hardcases", list}};
}

int hardcases(const HardCaseOptions& o) {
    std::vector<const CatalogueScene*> cases;
    if (o.cases.empty()) {
        for (const CatalogueScene& c : sceneCatalogue())
            if (c.hardCase && (!o.fast || c.scene.bodies.size() <= kFastCaseBodies)) cases.push_back(&c);
    }
    for (const std::string& name : o.cases) {
        const CatalogueScene& c = catalogueScene(name);
        if (!c.hardCase || !c.check)
            throw Error::invalid("--cases", "\"" + name + "\"", "not a hard case (`anyphys scenes` marks them [hard case])");
        cases.push_back(&c);
    }
    std::vector<BackendInfo> backends;
    if (o.backends.empty()) backends = availableBackends();
    for (const std::string& name : o.backends) backends.push_back(parseBackend("--backends", name));

    std::vector<std::vector<Cell>> cells;
    for (const CatalogueScene* c : cases) {
        cells.emplace_back();
        for (const BackendInfo& b : backends) cells.back().push_back(judge(*c, b));
    }
    if (o.json) std::cout << toJson(cases, backends, cells).dump(2) << '\n';
    else printMatrix(cases, backends, cells);

    std::string failures;
    for (std::size_t i = 0; i < cases.size(); ++i)
        for (std::size_t j = 0; j < backends.size(); ++j)
            if (gates(cells[i][j].verdict))
                failures += (failures.empty() ? "" : ", ") + cases[i]->name + " on " + backends[j].name + " (" +
                            word(cells[i][j].verdict) + ")";
    std::fflush(stdout);  // the matrix before the error line
    if (!failures.empty()) throw Error("hard cases failed: " + failures);
    return 0;
}

}  // namespace

Command addHardCasesCommand(CLI::App& parent) {
    auto o = std::make_shared<HardCaseOptions>();
    CLI::App* app = parent.add_subcommand(
        "hardcases", "Run the hard cases on every backend, sleeping off: a matrix of measured figures and verdicts");
    app->add_option("--cases", o->cases, "Comma-separated hard cases (default: all; see `anyphys scenes`)")->delimiter(',');
    app->add_option("--backends", o->backends, "Comma-separated backends (default: every built one)")->delimiter(',');
    app->add_flag("--fast", o->fast, "Only the cases of at most 100 bodies (the subset CI runs)");
    app->add_flag("--json", o->json, "Print JSON instead of the matrix");
    return {app, [o] { return hardcases(*o); }};
}

}  // namespace anyphys::cli
