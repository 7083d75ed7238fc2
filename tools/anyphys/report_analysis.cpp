// What each section of `anyphys report` shows for one scene (see docs/report.md for the
// definitions: Pareto front, fitted order, stability classes, cheapest configuration, effect cost).
#include "report_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

namespace anyphys::cli {
namespace {

bool finite(const Number& n) { return n && std::isfinite(*n); }

/// A row run with one of the scene's effects switched off: different physics, on purpose. Only the
/// effect-cost section compares it; everywhere else it would pass for a cheaper configuration.
bool effectSwitchedOff(const ReportRow& row) { return !row.effectOff.empty() && row.effectOff != "none"; }

/// Setting value as shown: numbers in the report's one format, names as written.
std::string showValue(const std::string& text) {
    if (text.empty()) return "(scene)";
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() ? formatNumber(value) : text;
}

std::string settingOf(const ReportRow& row, const std::string& name) {
    const auto it = row.settings.find(name);
    return it == row.settings.end() ? "" : it->second;
}

/// Lower-case letters, digits, '-' and '_' only; a clash gets a numeric suffix.
std::string uniqueStem(const std::string& scene, std::set<std::string>& used) {
    std::string stem;
    for (char c : scene) stem += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    if (stem.empty()) stem = "scene";
    std::string candidate = stem;
    for (int i = 2; used.count(candidate); ++i) candidate = stem + "_" + std::to_string(i);
    used.insert(candidate);
    return candidate;
}

template <class T>
std::size_t indexOf(std::vector<T>& items, const T& item) {
    const auto it = std::find(items.begin(), items.end(), item);
    if (it != items.end()) return static_cast<std::size_t>(it - items.begin());
    items.push_back(item);
    return items.size() - 1;
}

/// The fastest ok row of `candidates` by ms_per_sim_second (first on ties), or nullptr.
const ReportRow* fastest(const std::vector<const ReportRow*>& candidates) {
    const ReportRow* best = nullptr;
    for (const ReportRow* row : candidates)
        if (finite(row->msPerSimSecond) && (!best || *row->msPerSimSecond < *best->msPerSimSecond)) best = row;
    return best;
}

/// A setting varies when some backend runs it with two or more values. Backends' own defaults
/// (native's substeps, ODE's iterations) differ between backends without being swept: they would
/// only clutter every label.
void findVarying(SceneReport& s, const std::vector<std::string>& settingColumns) {
    for (const std::string& name : settingColumns) {
        std::map<std::string, std::set<std::string>> valuesPerBackend;
        for (const ReportRow* row : s.rows) valuesPerBackend[row->backend].insert(settingOf(*row, name));
        if (std::any_of(valuesPerBackend.begin(), valuesPerBackend.end(), [](const auto& v) { return v.second.size() > 1; }))
            s.varying.push_back(name);
    }
}

void summariseStatus(SceneReport& s) {
    for (const ReportRow* row : s.rows) {
        if (row->ok()) {
            ++s.okRows;
            continue;
        }
        const std::string key = row->status + (row->reason.empty() ? "" : ": " + row->reason);
        auto it = std::find_if(s.notOk.begin(), s.notOk.end(), [&](const auto& p) { return p.first == key; });
        if (it == s.notOk.end()) s.notOk.emplace_back(key, 1);
        else ++it->second;
    }
}

void findHeadline(SceneReport& s) {
    for (const std::string& backend : s.backends) {
        std::vector<const ReportRow*> within;
        for (const ReportRow* row : s.rows) {
            if (row->backend != backend || !row->ok() || row->checkOk == false || effectSwitchedOff(*row)) continue;
            const Number target = row->target();
            if (row->posError && target && !(*row->posError <= *target)) continue;  // nan is not within
            within.push_back(row);
        }
        s.headline.emplace_back(backend, fastest(within));
        const auto ran = [&](const ReportRow* row) { return row->backend == backend && row->status != "unsupported"; };
        if (std::none_of(s.rows.begin(), s.rows.end(), ran)) {  // its reason when all rows give the same
            std::set<std::string> reasons;
            for (const ReportRow* row : s.rows)
                if (row->backend == backend) reasons.insert(row->reason);
            s.notRun.emplace(backend, reasons.size() == 1 ? *reasons.begin() : "");
        }
    }
}

void buildCostPlot(SceneReport& s) {
    const bool integratorVaries = std::count(s.varying.begin(), s.varying.end(), "integrator") > 0;
    std::vector<const ReportRow*> measured;  // candidates for the Pareto front
    for (const ReportRow* row : s.rows) {
        if (!row->ok() || effectSwitchedOff(*row)) continue;
        if (finite(row->msPerSimSecond) && finite(row->posError)) measured.push_back(row);
        // Log axes: only positive values can be drawn.
        if (!finite(row->msPerSimSecond) || !finite(row->posError) || *row->msPerSimSecond <= 0 ||
            *row->posError <= 0) {
            ++s.unplottedCost;
            continue;
        }
        std::string label = row->backend;
        if (!row->solver.empty()) label += "/" + row->solver;
        if (integratorVaries && !row->integrator.empty()) label += "/" + row->integrator;
        auto it = std::find_if(s.costCurves.begin(), s.costCurves.end(), [&](const CostCurve& c) { return c.label == label; });
        if (it == s.costCurves.end()) it = s.costCurves.insert(s.costCurves.end(), CostCurve{label, {}});
        it->rows.push_back(row);
    }
    for (CostCurve& curve : s.costCurves)
        std::stable_sort(curve.rows.begin(), curve.rows.end(),
                         [](const ReportRow* a, const ReportRow* b) { return *a->msPerSimSecond < *b->msPerSimSecond; });

    // Pareto front: by cost (then error), keep a row when no cheaper-or-equal row has an error as
    // small; exact duplicates of a front point stay (neither beats the other).
    std::stable_sort(measured.begin(), measured.end(), [](const ReportRow* a, const ReportRow* b) {
        return *a->msPerSimSecond != *b->msPerSimSecond ? *a->msPerSimSecond < *b->msPerSimSecond
                                                        : *a->posError < *b->posError;
    });
    for (const ReportRow* row : measured) {
        const ReportRow* last = s.pareto.empty() ? nullptr : s.pareto.back();
        if (!last || *row->posError < *last->posError ||
            (*row->posError == *last->posError && *row->msPerSimSecond == *last->msPerSimSecond))
            s.pareto.push_back(row);
    }
}

/// Least-squares slope of log(error) on log(timeStep), over points above the rounding floor, when
/// they cover three or more distinct steps.
void fitOrder(ConvergenceLine& line, const std::vector<const ReportRow*>& finiteRows, const Number& scale) {
    std::vector<std::pair<double, double>> points;
    std::set<double> steps;
    for (const ReportRow* row : finiteRows) {
        if (*row->posError < roundingFloor(*row, scale) || *row->timeStep <= 0) {
            ++line.belowFloor;
            continue;
        }
        points.emplace_back(std::log(*row->timeStep), std::log(*row->posError));
        steps.insert(*row->timeStep);
    }
    line.fitPoints = points.size();
    if (steps.size() < 3) return;
    double mx = 0, my = 0;
    for (const auto& [x, y] : points) mx += x, my += y;
    mx /= static_cast<double>(points.size());
    my /= static_cast<double>(points.size());
    double sxy = 0, sxx = 0;
    for (const auto& [x, y] : points) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx);
    line.order = sxy / sxx;
    line.intercept = my - *line.order * mx;
    line.fitFrom = *steps.begin();
    line.fitTo = *steps.rbegin();
}

void buildConvergence(SceneReport& s) {
    std::vector<std::string> labels;
    std::vector<std::vector<const ReportRow*>> groups;  // ok rows with a time step and finite error
    for (const ReportRow* row : s.rows) {
        if (!row->ok() || !row->timeStep || !finite(row->posError) || effectSwitchedOff(*row)) continue;
        const std::string label = row->backend + " " + describeSettings(*row, s.varying, "timeStep");
        const std::size_t i = indexOf(labels, label);
        if (groups.size() <= i) groups.resize(i + 1);
        groups[i].push_back(row);
    }
    for (std::size_t i = 0; i < labels.size(); ++i) {
        std::set<double> steps;
        for (const ReportRow* row : groups[i]) steps.insert(*row->timeStep);
        if (steps.size() < 2) continue;  // one step is no convergence line
        ConvergenceLine line;
        line.label = labels[i];
        while (!line.label.empty() && line.label.back() == ' ') line.label.pop_back();
        line.theoretical = theoreticalOrder(groups[i].front()->integrator);
        fitOrder(line, groups[i], s.scale);
        for (const ReportRow* row : groups[i])
            if (*row->posError > 0) line.rows.push_back(row);
        std::stable_sort(line.rows.begin(), line.rows.end(),
                         [](const ReportRow* a, const ReportRow* b) { return *a->timeStep < *b->timeStep; });
        s.hasConvergence = s.hasConvergence || line.rows.size() >= 2;
        s.convergence.push_back(std::move(line));
    }
}

bool lessNumber(const Number& a, const Number& b) { return !a ? b.has_value() : b && *a < *b; }

void buildStability(SceneReport& s) {
    std::vector<const ReportRow*> ran;  // ok or failed: unsupported rows never ran
    std::set<Number, decltype(&lessNumber)> steps(&lessNumber), iterations(&lessNumber);
    for (const ReportRow* row : s.rows)
        if (row->status != "unsupported" && !effectSwitchedOff(*row)) {
            ran.push_back(row);
            steps.insert(row->timeStep);
            iterations.insert(row->iterations);
        }
    if (steps.size() <= 1 && iterations.size() <= 1) return;
    for (const std::string& backend : s.backends) {
        StabilityMap map;
        map.backend = backend;
        std::set<Number, decltype(&lessNumber)> xs(&lessNumber), ys(&lessNumber);
        for (const ReportRow* row : ran)
            if (row->backend == backend) xs.insert(row->timeStep), ys.insert(row->iterations);
        if (xs.empty()) continue;
        map.steps.assign(xs.begin(), xs.end());
        map.iterations.assign(ys.begin(), ys.end());
        for (const ReportRow* row : ran) {
            if (row->backend != backend) continue;
            const std::size_t x = static_cast<std::size_t>(std::find(map.steps.begin(), map.steps.end(), row->timeStep) - map.steps.begin());
            const std::size_t y = static_cast<std::size_t>(std::find(map.iterations.begin(), map.iterations.end(), row->iterations) - map.iterations.begin());
            auto it = std::find_if(map.cells.begin(), map.cells.end(), [&](const auto& c) { return c.x == x && c.y == y; });
            if (it == map.cells.end()) it = map.cells.insert(map.cells.end(), StabilityMap::Cell{x, y, Stability::stable, 0});
            it->cls = std::max(it->cls, classify(*row));  // the worst configuration of the cell
            ++it->rows;
        }
        std::sort(map.cells.begin(), map.cells.end(), [](const auto& a, const auto& b) {
            return a.y != b.y ? a.y < b.y : a.x < b.x;
        });
        s.stability.push_back(std::move(map));
    }
}

void buildCheapest(SceneReport& s) {
    for (double level : kCheapestLevels) {
        CheapestAtLevel entry{level, {}};
        for (const std::string& backend : s.backends) {
            std::vector<const ReportRow*> meeting;
            for (const ReportRow* row : s.rows)
                if (row->backend == backend && row->ok() && row->checkOk != false && !effectSwitchedOff(*row) &&
                    finite(row->posError) &&
                    row->sceneScale && *row->posError <= level * *row->sceneScale)
                    meeting.push_back(row);
            entry.perBackend.emplace_back(backend, fastest(meeting));
        }
        s.cheapest.push_back(std::move(entry));
    }
}

/// The time per step an effect-cost ratio compares (EffectCost).
Number effectTiming(const ReportRow& row, bool useMin) { return useMin ? row.msPerStepMin : row.msPerStepMedian; }

void buildEffectCosts(SceneReport& s) {
    std::vector<const ReportRow*> measured;  // ok rows of an effectOff sweep
    for (const ReportRow* row : s.rows) {
        if (row->effectOff.empty()) continue;
        if (row->effectOff != "none") indexOf(s.effects, row->effectOff);
        if (row->ok() && finite(row->msPerStepMedian)) measured.push_back(row);
    }
    s.effectTimingIsMin = !measured.empty() &&
                          std::all_of(measured.begin(), measured.end(), [](const ReportRow* r) { return finite(r->msPerStepMin); });
    std::vector<std::string> keys;
    const auto costOf = [&](const ReportRow* row) -> EffectCost& {
        const std::size_t i = indexOf(keys, row->backend + "\n" + describeSettings(*row, s.varying, "effectOff"));
        if (s.effectCosts.size() <= i)
            s.effectCosts.push_back(EffectCost{row->backend, describeSettings(*row, s.varying, "effectOff"), nullptr,
                                               std::vector<Number>(s.effects.size())});
        return s.effectCosts[i];
    };
    for (const ReportRow* row : measured) {
        EffectCost& cost = costOf(row);
        if (row->effectOff == "none" && !cost.baseline) cost.baseline = row;
    }
    for (const ReportRow* row : measured) {
        if (row->effectOff == "none") continue;
        EffectCost& cost = costOf(row);
        Number& ratio = cost.ratio[indexOf(s.effects, row->effectOff)];
        const Number base = cost.baseline ? effectTiming(*cost.baseline, s.effectTimingIsMin) : std::nullopt;
        if (base && *base > 0 && !ratio) ratio = *effectTiming(*row, s.effectTimingIsMin) / *base;
    }
}

}  // namespace

const char* toString(Stability s) {
    switch (s) {
        case Stability::stable: return "stable";
        case Stability::drifted: return "drifted";
        case Stability::exploded: return "exploded";
    }
    return "?";
}

std::optional<int> theoreticalOrder(const std::string& integrator) {
    static const std::map<std::string, int> orders{
        {"explicit_euler", 1}, {"semi_implicit_euler", 1}, {"verlet", 2}, {"midpoint", 2}, {"rk4", 4}};
    const auto it = orders.find(integrator);
    return it == orders.end() ? std::nullopt : std::optional<int>(it->second);
}

double roundingFloor(const ReportRow& row, const Number& scale) {
    const double steps = row.steps && *row.steps > 0 ? *row.steps : kFloorStepsUnknown;
    return kDoubleEpsilon * (scale && *scale > 0 ? *scale : 1.0) * steps;
}

std::string describeSettings(const ReportRow& row, const std::vector<std::string>& varying, const std::string& skip) {
    std::string out;
    for (const std::string& name : varying)
        if (name != skip) out += (out.empty() ? "" : " ") + name + "=" + showValue(settingOf(row, name));
    return out;
}

std::string describeConfig(const ReportRow& row, const std::vector<std::string>& varying) {
    const std::string settings = describeSettings(row, varying);
    return row.backend + " " + (settings.empty() ? "(scene settings)" : settings);
}

Stability classify(const ReportRow& row) {
    if (row.status == "failed") return Stability::exploded;
    bool blewUp = (row.posError && !std::isfinite(*row.posError)) ||
                  (row.msPerSimSecond && !std::isfinite(*row.msPerSimSecond));
    for (const Number& metric : row.otherMetrics) blewUp = blewUp || (metric && !std::isfinite(*metric));
    if (blewUp || (row.posError && row.sceneScale && *row.posError > *row.sceneScale)) return Stability::exploded;
    if (row.checkOk == false) return Stability::drifted;
    const Number target = row.target();
    if (!row.checkOk && row.posError && target && *row.posError > *target) return Stability::drifted;
    return Stability::stable;
}

std::vector<SceneReport> analyse(const ReportData& data) {
    std::vector<SceneReport> scenes;
    std::set<std::string> stems;
    for (const ReportRow& row : data.rows) {
        auto it = std::find_if(scenes.begin(), scenes.end(), [&](const SceneReport& s) { return s.scene == row.scene; });
        if (it == scenes.end()) {
            it = scenes.insert(scenes.end(), SceneReport{});
            it->scene = row.scene;
            it->stem = uniqueStem(row.scene, stems);
        }
        it->rows.push_back(&row);
        indexOf(it->backends, row.backend);
        if (!it->scale && row.sceneScale) it->scale = row.sceneScale;
    }
    for (SceneReport& s : scenes) {
        findVarying(s, data.settingColumns);
        summariseStatus(s);
        findHeadline(s);
        buildCostPlot(s);
        buildConvergence(s);
        buildStability(s);
        buildCheapest(s);
        buildEffectCosts(s);
    }
    return scenes;
}

}  // namespace anyphys::cli
