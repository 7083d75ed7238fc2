// The report's pages, section by section (docs/report.md explains how to read them).
#include "report_pages.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "cli.hpp"
#include "report_document.hpp"

namespace anyphys::cli {
namespace {

std::string plural(std::size_t n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

void provenance(Document& doc, const ReportData& data) {
    std::set<std::string> versions, commits;
    std::size_t ok = 0;
    double loadMin = INFINITY, loadMax = -INFINITY;
    for (const ReportRow& row : data.rows) {
        if (!row.version.empty()) versions.insert(row.version);
        if (!row.commit.empty()) commits.insert(row.commit);
        ok += row.ok();
        if (row.machineLoad && std::isfinite(*row.machineLoad))
            loadMin = std::min(loadMin, *row.machineLoad), loadMax = std::max(loadMax, *row.machineLoad);
    }
    const auto listed = [](const std::set<std::string>& s) {
        return s.empty() ? std::string("-") : join(std::vector<std::string>(s.begin(), s.end()));
    };
    doc.list({"results files: " + join(data.files),
              "rows: " + std::to_string(data.rows.size()) + " (" + std::to_string(ok) + " ok, " +
                  std::to_string(data.rows.size() - ok) + " unsupported or failed, not plotted)",
              "anyphys_version: " + listed(versions), "commit: " + listed(commits),
              "machine_load: " + (loadMin <= loadMax ? formatNumber(loadMin) + " to " + formatNumber(loadMax) : "-")});
}

/// Why a backend has no headline configuration: it never ran the scene, or nothing it ran got there.
std::string noneWithinTarget(const SceneReport& s, const std::string& backend) {
    const auto it = s.notRun.find(backend);
    if (it == s.notRun.end()) return "none within target";
    return "not run (" + (it->second.empty() ? std::string("unsupported: see the scene's section") : it->second) + ")";
}

/// The row's varying settings without the backend (the line names it already).
std::string describeSettingsOrScene(const ReportRow& row, const SceneReport& s) {
    const std::string settings = describeSettings(row, s.varying);
    return settings.empty() ? "(scene settings)" : settings;
}

/// Configuration, cost, error; `withBackend` false where the table has a backend column.
std::vector<std::string> configCells(const ReportRow* row, const SceneReport& s, bool withBackend) {
    if (!row) return {"none", "-", "-"};
    return {withBackend ? describeConfig(*row, s.varying) : describeSettingsOrScene(*row, s),
            formatNumber(row->msPerSimSecond), formatNumber(row->posError)};
}

void headlineTable(Document& doc, const std::vector<SceneReport>& scenes) {
    doc.section("Headline: fastest configuration within the error target");
    doc.paragraph("Per scene and backend, the configuration with the least ms per simulated second whose pos_error is "
                  "at most error_target (1 % of scene_scale; rows without pos_error qualify on their check) and whose "
                  "check did not fail.");
    std::vector<std::vector<std::string>> rows;
    for (const SceneReport& s : scenes)
        for (const auto& [backend, row] : s.headline) {
            std::vector<std::string> cells{s.scene, backend};
            for (std::string& cell : configCells(row, s, false)) cells.push_back(std::move(cell));
            if (!row) cells[2] = noneWithinTarget(s, backend);
            cells.push_back(formatNumber(row ? row->target() : s.scale ? Number(1e-2 * *s.scale) : std::nullopt));
            rows.push_back(std::move(cells));
        }
    doc.table({"scene", "backend", "configuration", "ms/sim s", "pos_error (m)", "error_target (m)"}, std::move(rows));
}

void statusSection(Document& doc, const SceneReport& s) {
    std::string text = "scene_scale " + formatNumber(s.scale) + " m. " + plural(s.rows.size(), "row") + ", " +
                       std::to_string(s.okRows) + " ok.";
    if (!s.varying.empty()) text += " Varying settings: " + join(s.varying) + ".";
    doc.paragraph(text);
    if (s.notOk.empty()) return;
    std::vector<std::string> items;
    for (const auto& [what, count] : s.notOk) items.push_back(std::to_string(count) + " x " + what);
    doc.paragraph("Not plotted (" + plural(s.rows.size() - s.okRows, "row") + "):");
    doc.list(std::move(items));
}

void costSection(Document& doc, const SceneReport& s, const ScenePlots& plots) {
    doc.subsection("Error against cost");
    if (plots.cost.empty()) {
        doc.paragraph("No ok row has both a positive pos_error and a cost: nothing to plot.");
        return;
    }
    doc.image(plots.cost, s.scene + ": error against cost");
    if (s.unplottedCost)
        doc.paragraph(plural(s.unplottedCost, "ok row") + " without a positive finite pos_error or cost not drawn "
                      "(log axes).");
    doc.paragraph("Pareto front: configurations no other configuration beats in both cost and error.");
    std::vector<std::vector<std::string>> rows;
    for (const ReportRow* row : s.pareto) rows.push_back(configCells(row, s, true));
    doc.table({"configuration", "ms/sim s", "pos_error (m)"}, std::move(rows));
}

void convergenceSection(Document& doc, const SceneReport& s, const ScenePlots& plots) {
    doc.subsection("Convergence");
    if (s.convergence.empty()) {
        doc.paragraph("No group of configurations differing only in timeStep has two or more steps with a finite "
                      "pos_error: no convergence plot.");
        return;
    }
    if (!plots.convergence.empty()) doc.image(plots.convergence, s.scene + ": convergence");
    doc.paragraph("Fitted order: least-squares slope of log(pos_error) on log(timeStep), over three or more distinct "
                  "steps. An error below 2.2e-16 x scene_scale x steps (one double rounding per step, added up) "
                  "is rounding, not truncation, and is left out of the fit.");
    std::vector<std::vector<std::string>> rows;
    for (const ConvergenceLine& line : s.convergence)
        rows.push_back({line.label, std::to_string(line.fitPoints), std::to_string(line.belowFloor),
                        line.order ? formatFixed(*line.order) : "- (fewer than 3 steps)",
                        line.theoretical ? std::to_string(*line.theoretical) : "-"});
    doc.table({"group", "points fitted", "below rounding floor", "fitted order", "theoretical order"}, std::move(rows));
}

void stabilitySection(Document& doc, const SceneReport& s, const ScenePlots& plots) {
    doc.subsection("Stability map");
    if (s.stability.empty()) {
        doc.paragraph("One timeStep and one iterations value only: no stability map.");
        return;
    }
    doc.paragraph("exploded: failed, a non-finite metric or pos_error > scene_scale; drifted: check failed, or without a "
                  "check pos_error > error_target; stable otherwise. A cell holding several configurations shows the "
                  "worst.");
    for (std::size_t i = 0; i < s.stability.size(); ++i) {
        const StabilityMap& map = s.stability[i];
        doc.image(plots.stability[i], s.scene + ": stability, " + map.backend);
        std::vector<std::string> header{map.backend + ": iterations (rows) by timeStep (columns)"};
        for (const Number& h : map.steps) header.push_back(h ? formatNumber(*h) : "scene");
        std::vector<std::vector<std::string>> rows;
        for (const Number& it : map.iterations) rows.push_back({it ? formatNumber(*it) : "scene"});
        for (auto& row : rows) row.resize(header.size(), "-");
        for (const auto& cell : map.cells) rows[cell.y][cell.x + 1] = toString(cell.cls);
        doc.table(std::move(header), std::move(rows));
    }
}

void cheapestSection(Document& doc, const SceneReport& s) {
    doc.subsection("Cheapest configuration per error level");
    doc.paragraph("Per level and backend, the least ms per simulated second with pos_error <= level x scene_scale and a "
                  "check that did not fail.");
    std::vector<std::vector<std::string>> rows;
    for (const CheapestAtLevel& level : s.cheapest)
        for (const auto& [backend, row] : level.perBackend) {
            std::vector<std::string> cells{formatNumber(level.level) + " x scale (" +
                                               formatNumber(s.scale ? Number(level.level * *s.scale) : std::nullopt) + " m)",
                                           backend};
            for (std::string& cell : configCells(row, s, false)) cells.push_back(std::move(cell));
            rows.push_back(std::move(cells));
        }
    doc.table({"error level", "backend", "configuration", "ms/sim s", "pos_error (m)"}, std::move(rows));
}

/// Whether "gravity+events" names `effect`.
bool simulates(const std::string& effects, const std::string& effect) {
    return ("+" + effects + "+").find("+" + effect + "+") != std::string::npos;
}

void effectSection(Document& doc, const SceneReport& s) {
    doc.subsection("Cost of each effect");
    if (s.effectCosts.empty()) {
        doc.paragraph("No row switches an effect off (no effectOff column or values): no effect costs.");
        return;
    }
    const std::string timing = s.effectTimingIsMin ? "ms_per_step_min" : "ms_per_step_median";
    doc.paragraph(timing + " with the effect switched off, relative to effectOff=none with the same other "
                  "settings (below 1: the effect costs that share of the step; above 1: it saves time, as sleeping "
                  "does). \"not in scene\": the scene does not call for the "
                  "effect, so switching it off changes nothing and the ratio is timing noise around 1.");
    std::vector<std::string> header{"backend", "other settings", "effects simulated (none off)", "none: " + timing};
    for (const std::string& effect : s.effects) header.push_back(effect + " off");
    std::vector<std::vector<std::string>> rows;
    for (const EffectCost& cost : s.effectCosts) {
        std::vector<std::string> cells{cost.backend, cost.settings.empty() ? "-" : cost.settings,
                                       cost.baseline && !cost.baseline->effects.empty() ? cost.baseline->effects : "-",
                                       cost.baseline ? formatNumber(s.effectTimingIsMin ? cost.baseline->msPerStepMin
                                                                                        : cost.baseline->msPerStepMedian)
                                                     : "-"};
        for (std::size_t i = 0; i < cost.ratio.size(); ++i) {
            const Number& ratio = cost.ratio[i];
            std::string cell = ratio ? formatNumber(*ratio) + "x" : "-";
            if (ratio && cost.baseline && !cost.baseline->effects.empty() &&
                !simulates(cost.baseline->effects, s.effects[i]))
                cell += " (not in scene)";
            cells.push_back(std::move(cell));
        }
        rows.push_back(std::move(cells));
    }
    doc.table(std::move(header), std::move(rows));
}

}  // namespace

std::vector<std::string> headlineLines(const std::vector<SceneReport>& scenes) {
    std::vector<std::string> lines;
    for (const SceneReport& s : scenes)
        for (const auto& [backend, row] : s.headline)
            lines.push_back(s.scene + " " + backend + ": " +
                            (row ? describeSettingsOrScene(*row, s) + ", " + formatNumber(row->msPerSimSecond) +
                                       " ms/sim s, pos_error " + formatNumber(row->posError) + " m"
                                 : noneWithinTarget(s, backend)));
    return lines;
}

void writePages(const ReportData& data, const std::vector<SceneReport>& scenes, const std::vector<ScenePlots>& plots,
                const std::string& outDir) {
    Document doc;
    doc.title("anyphys report");
    headlineTable(doc, scenes);
    doc.section("Provenance");
    provenance(doc, data);
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const SceneReport& s = scenes[i];
        doc.section("Scene " + s.scene);
        statusSection(doc, s);
        costSection(doc, s, plots[i]);
        convergenceSection(doc, s, plots[i]);
        stabilitySection(doc, s, plots[i]);
        cheapestSection(doc, s);
        effectSection(doc, s);
    }
    writeFile(outDir + "/index.html", doc.html());
    writeFile(outDir + "/README.md", doc.markdown());
}

}  // namespace anyphys::cli
