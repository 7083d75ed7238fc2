#pragma once
// The ImGui panels: controls (run, scene and backends, live settings, what to draw), one label
// per view (backend, step time, the scene's check) and the plot strip (step time and energy over
// the last seconds, per view).
#include <string>
#include <vector>

#include "batch.hpp"
#include "renderer.hpp"
#include "views.hpp"

namespace anyphys::testbed {

/// What the panels show and what the user asked for this frame (the app acts on the requests).
struct UiState {
    bool paused = false;
    float timeScale = 1.0f;
    DrawToggles draw;
    bool showPlots = true;
    // Live settings as edited; `settingsChanged` when the user changed one this frame.
    LiveSettings edit;
    bool settingsChanged = false;
    // Scene and backends: `reopen` when the user picked another scene or set of backends.
    std::vector<std::string> sceneNames;
    int sceneIndex = 0;
    std::string sceneFile;
    std::string openScene;  ///< what to open on `reopen`
    std::vector<std::string> allBackends;
    std::vector<char> selected;  ///< per allBackends entry
    bool reopen = false;
    // One-frame requests.
    bool stepOnce = false;
    bool reset = false;
    bool shoot = false;
    std::string message;  ///< last error of a request, shown in the panel
};

void drawControlPanel(UiState& ui, const Views& views);
/// `scale`: framebuffer pixels per window unit (ImGui works in window units).
void drawViewLabels(const Views& views, const std::vector<Rect>& rects, float scale);
void drawPlots(const Views& views, float windowWidth, float windowHeight);

}  // namespace anyphys::testbed
