// `anyphys compare`: every catalogue scene on every built backend with every integrator, side
// by side: wall time, error against the analytic answer, drift of conserved quantities.
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "compare.hpp"
#include "sweep.hpp"

namespace anyphys::cli {
namespace {

struct CompareOptions {
    std::vector<std::string> scenes;
    std::vector<std::string> backends;
    std::vector<std::string> integrators;
    bool json = false;
    // Sweep mode (docs/sweeps.md): any of these turns it on.
    std::vector<std::string> sweeps;  ///< NAME=V1,V2,... each
    std::optional<int> repeat;
    std::string out;
    std::string shard;                ///< k/N
    std::optional<int> shards;        ///< N for a Kubernetes indexed job
    bool sweepMode() const { return !sweeps.empty() || repeat || !out.empty() || !shard.empty() || shards; }
};

/// The combinations to run, with names checked up front (an unknown name is a usage error).
struct Selection {
    std::vector<const CatalogueScene*> scenes;
    std::vector<BackendInfo> backends;
    std::vector<Integrator> integrators;
    bool integratorsNamed = false;  // --integrators given
};

Selection select(const CompareOptions& o) {
    Selection s;
    if (o.scenes.empty())
        for (const CatalogueScene& c : sceneCatalogue())
            if (c.compareByDefault) s.scenes.push_back(&c);  // heavy loads run only when named
    for (const std::string& name : o.scenes) s.scenes.push_back(&catalogueScene(name));

    if (o.backends.empty()) s.backends = availableBackends();
    for (const std::string& name : o.backends) s.backends.push_back(parseBackend("--backends", name));

    // Default: each backend runs the integrators it offers (the union is listed; combinations a
    // backend lacks are left out). Named with --integrators: a backend lacking one shows an
    // "unsupported" row, so what was asked for is visibly answered.
    s.integratorsNamed = !o.integrators.empty();
    std::set<Integrator> chosen;
    for (const std::string& name : o.integrators) chosen.insert(parseIntegrator("--integrators", name));
    if (o.integrators.empty())
        for (const BackendInfo& b : s.backends) chosen.insert(b.capabilities.integrators.begin(), b.capabilities.integrators.end());
    s.integrators.assign(chosen.begin(), chosen.end());
    return s;
}

std::string orDash(const std::optional<double>& value, const char* pattern) {
    return value ? printfNumber(pattern, *value) : "-";
}

std::string verdictText(const ComboResult& r) {
    if (r.checkPassed) return "ok";
    if (r.knownDeviation) return "FAIL (declared known deviation)";
    if (r.overCeiling) return "FAIL (declared, over its ceiling " + printfNumber("%.3g", *r.ceiling) + ")";
    return "FAIL";
}

/// "top drift 3.1e-04 m (want 0 +- 0.01) ok": the scene's own measure against its bound.
std::string checkText(const ComboResult& r) {
    if (!r.checkValue) return "-";
    const SceneCheck& check = *catalogueScene(r.scene).check;
    const std::string unit = check.unit.empty() ? "" : " " + check.unit;
    return check.label + " " + printfNumber("%.4g", *r.checkValue) + unit + " (want " + printfNumber("%g", check.expected) +
           " +- " + printfNumber("%.3g", check.tolerance) + ") " + verdictText(r);
}

std::string statusWord(ComboResult::Status status) {
    return status == ComboResult::Status::Unsupported ? "unsupported" : "failed";
}

void printTable(const std::vector<ComboResult>& results) {
    using Row = std::vector<std::string>;
    std::vector<Row> rows{
        {"scene", "backend", "integrator", "steps", "wall ms", "pos error m", "|L| drift", "energy drift", "check"}};
    for (const ComboResult& r : results) {
        if (r.status != ComboResult::Status::Ok) {
            rows.push_back({r.scene, r.backend, r.integrator, statusWord(r.status) + ": " + r.reason});
            continue;
        }
        rows.push_back({r.scene, r.backend, r.integrator, std::to_string(r.steps), printfNumber("%.2f", r.wallMs),
                        orDash(r.positionError, "%.3e"), orDash(r.angularMomentumDrift, "%+.3e"),
                        orDash(r.energyDrift, "%+.3e"), checkText(r)});
    }
    std::vector<std::size_t> widths(rows.front().size(), 0);
    for (const Row& row : rows)
        if (row.size() == widths.size())  // refusal rows span the measured columns; they don't set widths
            for (std::size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
    for (const Row& row : rows) {
        std::string line;
        for (std::size_t i = 0; i < row.size(); ++i) {
            const bool last = i + 1 == row.size();
            const std::size_t pad = widths[i] > row[i].size() ? widths[i] - row[i].size() : 0;
            if (i < 3 || last) line += row[i] + (last ? "" : std::string(pad, ' '));  // text: left-aligned
            else line += std::string(pad, ' ') + row[i];                             // numbers: right-aligned
            if (!last) line += "  ";
        }
        std::cout << line << '\n';
    }
    std::cout << "pos error: max over bodies of |p - p_exact| at the end (\"-\": no analytic answer); "
                 "drifts: (end - start) / |start| (\"-\": not conserved by the scene); "
                 "check: the scene's own measure against exact physics (`anyphys scenes` says what each measures)\n";
}

nlohmann::json toJson(const std::vector<ComboResult>& results) {
    const auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
    nlohmann::json list = nlohmann::json::array();
    for (const ComboResult& r : results) {
        nlohmann::json row = {{"scene", r.scene}, {"backend", r.backend}, {"integrator", r.integrator}};
        if (r.status != ComboResult::Status::Ok) {
            row["status"] = statusWord(r.status);
            row["reason"] = r.reason;
        } else {
            row["status"] = "ok";
            row["steps"] = r.steps;
            row["wallMs"] = r.wallMs;
            row["positionError"] = optional(r.positionError);
            row["angularMomentumDrift"] = optional(r.angularMomentumDrift);
            row["energyDrift"] = optional(r.energyDrift);
            row["check"] = nlohmann::json();
            if (r.checkValue) {
                const SceneCheck& check = *catalogueScene(r.scene).check;
                row["check"] = {{"label", check.label},       {"unit", check.unit},
                                {"value", *r.checkValue},     {"expected", check.expected},
                                {"tolerance", check.tolerance}, {"passed", r.checkPassed},
                                {"criterion", check.criterion}, {"knownDeviation", r.knownDeviation},
                                {"ceiling", optional(r.ceiling)}, {"overCeiling", r.overCeiling}};
            }
        }
        list.push_back(row);
    }
    return {{"results", list}};
}

/// The sweep's grid: the --sweep axes; --integrators, if given, is one more axis.
int sweep(const CompareOptions& o) {
    const Selection s = select(o);
    SweepOptions options;
    options.scenes = s.scenes;
    options.backends = s.backends;
    for (const std::string& spec : o.sweeps) {
        options.axes.push_back(parseSweepAxis(spec));
        for (std::size_t i = 0; i + 1 < options.axes.size(); ++i)
            if (options.axes[i].name == options.axes.back().name)
                throw Error("--sweep " + spec + ": the setting \"" + options.axes.back().name + "\" is swept twice");
    }
    if (!o.integrators.empty()) {
        for (const SweepAxis& axis : options.axes)
            if (axis.name == "integrator") throw Error("--integrators and --sweep integrator=...: give the integrators once");
        options.axes.push_back(parseSweepAxis("integrator=" + join(o.integrators, ",")));
    }
    options.repeat = o.repeat.value_or(3);
    if (options.repeat < 1) throw Error::invalid("--repeat", options.repeat, "must be >= 1");
    options.out = o.out;
    options.shard = o.shard.empty() ? shardFromEnvironment(o.shards) : parseShard("--shard", o.shard);
    options.json = o.json;
    return runSweep(options);
}

int compare(const CompareOptions& o) {
    if (o.sweepMode()) return sweep(o);
    const Selection s = select(o);
    std::vector<ComboResult> results;
    for (const CatalogueScene* scene : s.scenes)
        for (const BackendInfo& backend : s.backends)
            for (Integrator integrator : s.integrators) {
                if (!backend.capabilities.integrators.contains(integrator)) {
                    if (!s.integratorsNamed) continue;
                    // Reported, not dropped: the table shows what each backend cannot do.
                    ComboResult r;
                    r.scene = scene->name;
                    r.backend = backend.name;
                    r.integrator = std::string(toString(integrator));
                    r.status = ComboResult::Status::Unsupported;
                    r.reason = "integrator " + r.integrator + " not offered by this backend";
                    results.push_back(r);
                    continue;
                }
                results.push_back(runCombo(*scene, backend, integrator));
            }

    if (o.json) std::cout << toJson(results).dump(2) << '\n';
    else printTable(results);

    const auto failed = std::count_if(results.begin(), results.end(),
                                      [](const ComboResult& r) { return r.status == ComboResult::Status::Failed; });
    if (failed > 0) throw Error(std::to_string(failed) + " combination(s) failed while stepping (see the table)");
    // A check that misses without the backend declaring it is a defect, not a table entry.
    std::string undeclared;
    for (const ComboResult& r : results)
        if (r.checkValue && !r.checkPassed && !r.knownDeviation)
            undeclared += (undeclared.empty() ? "" : ", ") + r.scene + " on " + r.backend + " (" + r.integrator + ")";
    if (!undeclared.empty())
        throw Error("checks failed without a declared known deviation, or over its ceiling: " + undeclared);
    return 0;
}

}  // namespace

Command addCompareCommand(CLI::App& parent) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* app = parent.add_subcommand(
        "compare", "Run catalogue scenes on every backend and integrator and compare accuracy, conservation and speed");
    app->add_option("--scenes", o->scenes,
                    "Comma-separated catalogue scenes (default: all but the heavy benchmark loads; see `anyphys scenes`)")
        ->delimiter(',');
    app->add_option("--backends", o->backends, "Comma-separated backends (default: every built one)")->delimiter(',');
    app->add_option("--integrators", o->integrators,
                    "Comma-separated integrators (default: each backend's own): " + allowedNames<Integrator>())
        ->delimiter(',');
    app->add_flag("--json", o->json, "Print JSON instead of a table");
    // Each --sweep is one axis; its values are split by parseSweepAxis, not CLI11 (no delimiter).
    app->add_option("--sweep", o->sweeps,
                    "Sweep a setting over values, NAME=V1,V2,... (repeatable; a full grid over every axis): " +
                        allowedAxisNames() + "; timeStep also takes fractions like 1/60; effectOff takes effect names or none")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check([](const std::string& spec) {
            try {
                parseSweepAxis(spec);
                return std::string();
            } catch (const Error& e) {
                const std::string message = e.what();  // CLI11 names the option itself
                return message.starts_with("--sweep ") ? message.substr(8) : message;
            }
        });
    app->add_option("--repeat", o->repeat, "Timed runs per configuration after one untimed warm-up (default 3 in sweep mode)");
    app->add_option("--out", o->out, "Write one row per configuration to this CSV, and a .jsonl beside it");
    app->add_option("--shard", o->shard,
                    "Run only the k-th of N cost-balanced parts, k/N (default: from SLURM_ARRAY_TASK_ID / "
                    "SLURM_ARRAY_TASK_COUNT or JOB_COMPLETION_INDEX)");
    app->add_option("--shards", o->shards, "N for a Kubernetes indexed job (JOB_COMPLETION_INDEX); else ANYPHYS_SHARD_COUNT");
    return {app, [o] { return compare(*o); }};
}

}  // namespace anyphys::cli
