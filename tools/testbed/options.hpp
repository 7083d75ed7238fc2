#pragma once
// The testbed's command line (main.cpp parses it with CLI11).
#include <optional>
#include <string>
#include <vector>

namespace anyphys::testbed {

struct TestbedOptions {
    std::string scene = "box_stack_10";  ///< built-in scene, assembly, or scene file
    std::vector<std::string> backends;   ///< 1 to 4; default: the first built backend
    bool headless = false;               ///< hidden window, off-screen target, one step per frame
    int frames = 0;                      ///< frames to run before exiting; 0: until the window closes
    std::string screenshot;              ///< PNG of the last frame
    std::string record;                  ///< folder for one PNG per frame
    std::string video;                   ///< .mp4 or .gif through ffmpeg
    std::string dumpProjections;         ///< JSON sidecar of the last frame
    int width = 1280;
    int height = 720;
    bool hideUi = false;                 ///< no panels and no labels (tests compare bare pictures)
    bool paused = false;
    /// yaw, pitch (degrees), distance (m), optionally the target x, y, z (m); default: framed.
    std::vector<double> camera;
    bool contacts = false, joints = true, bounds = false, sleep = true;
};

/// Runs the testbed; returns the process exit code. Throws anyphys::Error for bad input.
int runTestbed(const TestbedOptions& options);

}  // namespace anyphys::testbed
