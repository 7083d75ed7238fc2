#pragma once
// The pages of `anyphys report`: DIR/index.html and DIR/README.md, and the headline lines printed
// on stdout.
#include <string>
#include <vector>

#include "report_analysis.hpp"
#include "report_plots.hpp"

namespace anyphys::cli {

/// One line per scene x backend: the fastest configuration within the error target.
std::vector<std::string> headlineLines(const std::vector<SceneReport>& scenes);

/// Writes index.html and README.md into `outDir`; `plots` is parallel to `scenes`.
void writePages(const ReportData& data, const std::vector<SceneReport>& scenes, const std::vector<ScenePlots>& plots,
                const std::string& outDir);

}  // namespace anyphys::cli
