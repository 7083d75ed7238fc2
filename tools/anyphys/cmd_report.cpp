// `anyphys report RESULTS.csv [MORE.csv ...] --out DIR`: turns sweep results into a report per
// scene (error against cost with the Pareto front, convergence with fitted orders, stability map,
// cheapest configurations, effect costs, headline) as DIR/index.html and DIR/README.md with gnuplot
// plots in DIR/plots. docs/report.md describes how to read it.
#include <filesystem>
#include <iostream>
#include <system_error>

#include "cli.hpp"
#include "report_analysis.hpp"
#include "report_data.hpp"
#include "report_pages.hpp"
#include "report_plots.hpp"

namespace anyphys::cli {
namespace {

struct ReportOptions {
    std::vector<std::string> files;
    std::string out;
};

void makeDirectory(const std::string& path) {
    std::error_code error;
    std::filesystem::create_directories(path, error);
    if (error || !std::filesystem::is_directory(path)) throw Error(ErrorKind::Io, "", path + ": cannot create directory");
}

int runReport(const ReportOptions& options) {
    const ReportData data = loadReportData(options.files);  // reads everything before writing anything
    const std::vector<SceneReport> scenes = analyse(data);
    const std::string plotDir = options.out + "/plots";
    makeDirectory(plotDir);
    std::vector<ScenePlots> plots;
    std::vector<std::string> scripts;
    for (const SceneReport& scene : scenes) {
        plots.push_back(writeScenePlots(scene, plotDir));
        scripts.push_back(plots.back().script);
    }
    if (!scripts.empty()) runGnuplot(plotDir, scripts);
    writePages(data, scenes, plots, options.out);
    for (const std::string& line : headlineLines(scenes)) std::cout << line << '\n';
    std::cout << "report: " << options.out << "/index.html\n";
    return 0;
}

}  // namespace

Command addReportCommand(CLI::App& parent) {
    auto options = std::make_shared<ReportOptions>();
    CLI::App* app = parent.add_subcommand(
        "report", "Write an HTML and Markdown report with plots from results CSVs of `compare --out`");
    app->add_option("results", options->files, "results CSV files (concatenated)")->required();
    app->add_option("--out", options->out, "directory for index.html, README.md and plots/")->required();
    return {app, [options] { return runReport(*options); }};
}

}  // namespace anyphys::cli
