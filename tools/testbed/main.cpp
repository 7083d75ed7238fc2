// anyphys_testbed: a scene on 1 to 4 backends side by side, stepped together, with one camera.
// See docs/testbed.md.
#include <CLI/CLI.hpp>

#include <cstdio>

#include "anyphys/anyphys.hpp"
#include "options.hpp"

namespace {

std::vector<std::string> split(const std::string& list) {
    std::vector<std::string> out;
    std::string item;
    for (char c : list + ",") {
        if (c == ',') {
            if (!item.empty()) out.push_back(item);
            item.clear();
        } else {
            item += c;
        }
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace anyphys::testbed;
    TestbedOptions o;
    std::string backends;
    std::string size;
    CLI::App app{"anyphys_testbed: a scene on 1 to 4 physics backends side by side, stepped together", "anyphys_testbed"};
    app.add_option("--scene", o.scene, "Built-in scene or assembly (see `anyphys scenes`), or a scene file")->capture_default_str();
    app.add_option("--backends", backends, "1 to 4 backends, comma separated (a backend may repeat); default: the first built");
    app.add_flag("--headless", o.headless, "Hidden window, off-screen rendering, one step per frame (needs --frames)");
    app.add_option("--frames", o.frames, "Frames to run, then exit (0: until the window closes)")->check(CLI::Range(0, 1000000));
    app.add_option("--screenshot", o.screenshot, "PNG of the last frame (needs --frames)");
    app.add_option("--record", o.record, "Folder to write every frame to, as frame_NNNNN.png");
    app.add_option("--video", o.video, "Video of the run through ffmpeg: FILE.mp4 or FILE.gif");
    app.add_option("--dump-projections", o.dumpProjections,
                   "JSON of the last frame: each view's rectangle and each body's state and screen position (needs --frames)");
    app.add_option("--size", size, "Window or picture size WIDTHxHEIGHT, default 1280x720");
    app.add_flag("--hide-ui", o.hideUi, "No panels and no labels");
    app.add_flag("--paused", o.paused, "Start paused");
    app.add_option("--camera", o.camera, "yaw,pitch (degrees),distance (m)[,target x,y,z (m)]; default: framed on the bodies")
        ->delimiter(',')
        ->expected(3, 6);
    app.add_flag("--contacts,!--no-contacts", o.contacts, "Draw contact points and normals (default off)");
    app.add_flag("--joints,!--no-joints", o.joints, "Draw joint frames (default on)");
    app.add_flag("--bounds,!--no-bounds", o.bounds, "Draw bounding boxes (default off)");
    app.add_flag("--sleep,!--no-sleep", o.sleep, "Draw sleeping bodies in their own colour (default on)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);  // prints help, or the usage error
        return code == 0 ? 0 : 2;      // usage errors exit 2, as the demos do
    }
    try {
        o.backends = split(backends);
        if (o.backends.empty()) o.backends.push_back(anyphys::availableBackends().front().name);
        if (!size.empty()) {
            int w = 0, h = 0;
            char tail = 0;
            if (std::sscanf(size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 64 || h < 64 || w > 8192 || h > 8192)
                throw anyphys::Error("--size: must be WIDTHxHEIGHT, each 64 to 8192, got " + size);
            o.width = w;
            o.height = h;
        }
        if ((o.headless || !o.screenshot.empty() || !o.dumpProjections.empty()) && o.frames <= 0)
            throw anyphys::Error("--frames: --headless, --screenshot and --dump-projections need a number of frames > 0");
        if (o.camera.size() != 0 && o.camera.size() != 3 && o.camera.size() != 6)
            throw anyphys::Error("--camera: give yaw,pitch,distance or yaw,pitch,distance,x,y,z, got " +
                                 std::to_string(o.camera.size()) + " numbers");
        if (!o.camera.empty() && !(o.camera[2] > 0))
            throw anyphys::Error("--camera: the distance must be > 0, got " + std::to_string(o.camera[2]));
        for (const std::string& b : o.backends) {
            try {
                anyphys::backendInfo(b);
            } catch (const anyphys::Error& e) {
                throw e.renamed("--backends");
            }
        }
        if (o.backends.size() > 4)
            throw anyphys::Error("--backends: give 1 to 4 backends, got " + std::to_string(o.backends.size()));
        return runTestbed(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "anyphys_testbed: %s\n", e.what());
        return 1;
    }
}
