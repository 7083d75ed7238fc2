#pragma once
// The window and the frame loop: input, stepping the views together, drawing each view into its
// part of the window, the panels, and the captures.
#include <memory>
#include <optional>
#include <vector>

#include "camera.hpp"
#include "capture.hpp"
#include "options.hpp"
#include "picking.hpp"
#include "renderer.hpp"
#include "ui.hpp"
#include "views.hpp"

struct GLFWwindow;

namespace anyphys::testbed {

/// The views' rectangles in a framebuffer `width` x `height`: side by side for up to three, two
/// by two for four.
std::vector<Rect> layoutViews(std::size_t count, int width, int height);

class App {
public:
    explicit App(const TestbedOptions& options);
    ~App();
    App(const App&) = delete;
    App& operator=(const App&) = delete;
    int run();

    // GLFW callbacks (through the window's user pointer).
    void onKey(int key, int action);
    void onMouseButton(int button, int action);
    void onScroll(double dy);

private:
    void open(const std::string& scene, const std::vector<std::string>& backends);
    void frameCamera();
    void handleMouse();
    void handleRequests();
    int stepsThisFrame(double elapsed);
    void render(int width, int height);
    std::optional<std::size_t> viewAt(double x, double y, double& localX, double& localY) const;
    void shoot();

    TestbedOptions options_;
    GLFWwindow* window_ = nullptr;
    bool imgui_ = false;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<OffscreenTarget> offscreen_;
    std::unique_ptr<VideoWriter> video_;
    Views views_;
    std::vector<Batch> batches_;
    std::vector<Rect> rects_;
    Camera camera_;
    Picker picker_;
    UiState ui_;
    double accumulator_ = 0.0;
    double cursorX_ = 0.0, cursorY_ = 0.0;  // framebuffer pixels
    bool orbiting_ = false, panning_ = false;
    float scale_ = 1.0f;                     // framebuffer pixels per window unit
};

}  // namespace anyphys::testbed
