// Gnuplot data files and scripts of `anyphys report`. Data is written at full precision (the plot
// shows the CSV's values); titles are single-quoted gnuplot strings, drawn without enhanced-text
// markup so scene and setting names show as written.
#include "report_plots.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cli.hpp"

namespace anyphys::cli {
namespace {

std::string quote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
}

std::string shellQuote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string fileSafe(const std::string& name) {
    std::string out;
    for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return out;
}

/// The plot body `body` drawn twice: PNG, then the same plot as SVG (replot on the new terminal).
std::string bothFormats(const std::string& stem, const std::string& body) {
    std::ostringstream gp;
    gp << "reset\n"
       << "set terminal pngcairo noenhanced size 1000,600 font 'sans,10'\n"
       << "set output " << quote(stem + ".png") << "\n"
       // Gnuplot's eighth default colour is black, the Pareto front's: brown instead.
       << "set linetype 8 lc rgb '#8c564b' lw 1 pt 7\n"
       << body
       << "set terminal svg noenhanced size 1000,600 font 'sans,10'\n"
       << "set output " << quote(stem + ".svg") << "\n"
       << "replot\n"
       << "set output\n\n";
    return gp.str();
}

std::string costPlot(const SceneReport& s, const std::string& stem, const std::string& plotDir) {
    std::ostringstream data, plot;
    std::size_t block = 0;
    for (const CostCurve& curve : s.costCurves) {
        for (const ReportRow* row : curve.rows)
            data << exactNumber(*row->msPerSimSecond) << ' ' << exactNumber(*row->posError) << '\n';
        data << "\n\n";
        plot << (block ? ", \\\n  " : "plot ") << quote(stem + ".dat") << " index " << block
             << " using 1:2 with linespoints pt 7 ps 0.8 title " << quote(curve.label);
        ++block;
    }
    std::size_t drawn = 0;  // front points a log axis can show
    for (const ReportRow* row : s.pareto)
        if (*row->posError > 0 && *row->msPerSimSecond > 0) {
            data << exactNumber(*row->msPerSimSecond) << ' ' << exactNumber(*row->posError) << '\n';
            ++drawn;
        }
    if (drawn) {
        plot << (block ? ", \\\n  " : "plot ") << quote(stem + ".dat") << " index " << block
             << " using 1:2 with linespoints lw 3 pt 6 ps 2 lc rgb 'black' title 'Pareto front'";
        ++block;
    }
    if (!block) return "";  // nothing a log-log plot can show
    if (s.scale) plot << ", \\\n  " << exactNumber(1e-2 * *s.scale) << " with lines dt 2 lc rgb 'gray40' title 'error target'";
    writeFile(plotDir + "/" + stem + ".dat", data.str());
    std::ostringstream body;
    body << "set logscale xy\nset grid\nset key below\nset format x '%g'\nset format y '%.0e'\n"
         << "set xlabel 'cost: ms per simulated second'\nset ylabel 'position error (m)'\n"
         << "set title " << quote(s.scene + ": error against cost") << "\n"
         << plot.str() << "\n";
    return bothFormats(stem, body.str());
}

std::string convergencePlot(const SceneReport& s, const std::string& stem, const std::string& plotDir) {
    std::ostringstream data, plot;
    std::size_t block = 0, line = 0;
    for (const ConvergenceLine& c : s.convergence) {
        if (c.rows.size() < 2) continue;
        ++line;
        for (const ReportRow* row : c.rows) data << exactNumber(*row->timeStep) << ' ' << exactNumber(*row->posError) << '\n';
        data << "\n\n";
        const std::string order = c.order ? formatFixed(*c.order) : "-";
        const std::string theory = c.theoretical ? std::to_string(*c.theoretical) : "-";
        plot << (block ? ", \\\n  " : "plot ") << quote(stem + ".dat") << " index " << block << " using 1:2 with linespoints lt "
             << line << " pt 7 title " << quote(c.label + ": order " + order + " (theory " + theory + ")");
        ++block;
        if (c.order) {  // the fitted line over the fitted steps' range
            for (double h : {c.fitFrom, c.fitTo}) data << exactNumber(h) << ' ' << exactNumber(std::exp(c.intercept + *c.order * std::log(h))) << '\n';
            data << "\n\n";
            plot << ", \\\n  " << quote(stem + ".dat") << " index " << block << " using 1:2 with lines lt " << line
                 << " dt 2 notitle";
            ++block;
        }
    }
    if (!block) return "";
    writeFile(plotDir + "/" + stem + ".dat", data.str());
    std::ostringstream body;
    body << "set logscale xy\nset grid\nset key below\nset format x '%g'\nset format y '%.0e'\n"
         << "set xlabel 'timeStep (s)'\nset ylabel 'position error (m)'\n"
         << "set title " << quote(s.scene + ": convergence (dashed: fitted order)") << "\n"
         << plot.str() << "\n";
    return bothFormats(stem, body.str());
}

std::string axisTics(const std::vector<Number>& values) {
    std::string tics = "(";
    for (std::size_t i = 0; i < values.size(); ++i)
        tics += (i ? ", " : "") + quote(values[i] ? formatNumber(*values[i]) : "scene") + " " + std::to_string(i);
    return tics + ")";
}

const char* colour(Stability s) {
    switch (s) {
        case Stability::stable: return "0x2ca02c";
        case Stability::drifted: return "0xff9f1c";
        case Stability::exploded: return "0xd62728";
    }
    return "0x000000";
}

std::string stabilityPlot(const SceneReport& s, const StabilityMap& map, const std::string& stem, const std::string& plotDir) {
    std::ostringstream data;
    for (const auto& cell : map.cells) data << cell.x << ' ' << cell.y << ' ' << colour(cell.cls) << '\n';
    writeFile(plotDir + "/" + stem + ".dat", data.str());
    std::ostringstream body;
    body << "set xrange [-0.5:" << map.steps.size() - 0.5 << "]\nset yrange [-0.5:" << map.iterations.size() - 0.5 << "]\n"
         << "set xtics " << axisTics(map.steps) << "\nset ytics " << axisTics(map.iterations) << "\n"
         << "set xlabel 'timeStep (s)'\nset ylabel 'iterations'\nset key outside right top\n"
         << "set title " << quote(s.scene + ": stability, " + map.backend) << "\n"
         << "plot " << quote(stem + ".dat") << " using 1:2:(0.45):(0.45):3 with boxxyerror fs solid 1.0 lc rgb variable notitle, \\\n"
         << "  keyentry with boxes fs solid 1.0 lc rgb '#2ca02c' title 'stable', \\\n"
         << "  keyentry with boxes fs solid 1.0 lc rgb '#ff9f1c' title 'drifted', \\\n"
         << "  keyentry with boxes fs solid 1.0 lc rgb '#d62728' title 'exploded'\n";
    return bothFormats(stem, body.str());
}

/// The directory on PATH holding an executable gnuplot, or "".
std::string findGnuplot() {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (!dir.empty() && ::access((dir + "/gnuplot").c_str(), X_OK) == 0) return dir + "/gnuplot";
    return "";
}

/// Gnuplot's first error line ("file" line N: message), else its last line.
std::string firstError(const std::string& logPath) {
    std::ifstream log(logPath);
    std::string line, last;
    while (std::getline(log, line)) {
        if (line.find("\" line ") != std::string::npos) return line;
        if (!line.empty()) last = line;
    }
    return last;
}

}  // namespace

std::string formatFixed(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2f", value);
    return buffer;
}

ScenePlots writeScenePlots(const SceneReport& s, const std::string& plotDir) {
    ScenePlots plots;
    plots.script = s.stem + ".gp";
    std::string script = costPlot(s, s.stem + "_cost", plotDir);
    if (!script.empty()) plots.cost = s.stem + "_cost";
    if (const std::string c = convergencePlot(s, s.stem + "_convergence", plotDir); !c.empty()) {
        plots.convergence = s.stem + "_convergence";
        script += c;
    }
    for (const StabilityMap& map : s.stability) {
        plots.stability.push_back(s.stem + "_stability_" + fileSafe(map.backend));
        script += stabilityPlot(s, map, plots.stability.back(), plotDir);
    }
    writeFile(plotDir + "/" + plots.script, "# anyphys report: plots of scene " + s.scene + "\n" + script);
    return plots;
}

void runGnuplot(const std::string& plotDir, const std::vector<std::string>& scripts) {
    const std::string gnuplot = findGnuplot();
    if (gnuplot.empty()) throw Error("gnuplot not found; install gnuplot-nox");
    std::string command = "cd " + shellQuote(plotDir) + " && " + shellQuote(gnuplot);
    for (const std::string& script : scripts) command += " " + shellQuote(script);
    command += " 2> gnuplot.log";
    const int status = std::system(command.c_str());
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw Error("gnuplot failed in " + plotDir + ": " + firstError(plotDir + "/gnuplot.log"));
}

}  // namespace anyphys::cli
