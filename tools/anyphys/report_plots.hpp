#pragma once
// `anyphys report` plots: gnuplot data files and one script per scene in DIR/plots, each plot
// written as PNG (pngcairo, for README.md) and SVG (for index.html); one gnuplot process runs all.
#include <string>
#include <vector>

#include "report_analysis.hpp"

namespace anyphys::cli {

/// The plots written for one scene: file names without extension, relative to the plot folder.
struct ScenePlots {
    std::string script;  ///< the scene's .gp file
    std::string cost;
    std::string convergence;                 ///< "" when the scene has no convergence line
    std::vector<std::string> stability;      ///< one per SceneReport::stability map
};

/// "%.2f": fitted orders ("1.00"), on the plots and the pages alike.
std::string formatFixed(double value);

/// Writes the scene's data files and script into `plotDir`; nothing runs yet.
ScenePlots writeScenePlots(const SceneReport& scene, const std::string& plotDir);

/// Runs gnuplot once on every script, in `plotDir`. Throws anyphys::Error when gnuplot is not on
/// PATH or fails (with its first error line; the whole log stays in plotDir/gnuplot.log).
void runGnuplot(const std::string& plotDir, const std::vector<std::string>& scripts);

}  // namespace anyphys::cli
