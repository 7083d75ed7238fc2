#include "app.hpp"

#include <GL/glew.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "projections.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace anyphys::testbed {
namespace {

constexpr double kDegrees = 3.141592653589793 / 180.0;
constexpr float kPlotHeight = 150.0f;

App* appOf(GLFWwindow* window) { return static_cast<App*>(glfwGetWindowUserPointer(window)); }

void glfwError(int code, const char* text) { std::fprintf(stderr, "anyphys_testbed: GLFW error %d: %s\n", code, text); }

}  // namespace

std::vector<Rect> layoutViews(std::size_t count, int width, int height) {
    std::vector<Rect> rects;
    if (count == 0) return rects;
    if (count == 4) {
        const int w = width / 2, h = height / 2;
        for (int i = 0; i < 4; ++i) rects.push_back(Rect{(i % 2) * w, (i / 2) * h, w, h});
        return rects;
    }
    const int w = width / static_cast<int>(count);
    for (std::size_t i = 0; i < count; ++i) rects.push_back(Rect{static_cast<int>(i) * w, 0, w, height});
    return rects;
}

App::App(const TestbedOptions& options) : options_(options) {
    glfwSetErrorCallback(glfwError);
    if (!glfwInit())
        throw Error("cannot open a window (no display?): run the testbed on a desktop, or headless under "
                    "xvfb-run -a -s \"-screen 0 1920x1080x24\"");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, options_.headless ? GLFW_FALSE : GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, 0);
    window_ = glfwCreateWindow(options_.width, options_.height, "anyphys testbed", nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw Error("cannot create an OpenGL 3.3 core window (is Mesa's libgl1-mesa-dri installed?)");
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(options_.headless ? 0 : 1);
    glewExperimental = GL_TRUE;
    if (const GLenum e = glewInit(); e != GLEW_OK)
        throw Error(std::string("cannot load OpenGL functions: ") + reinterpret_cast<const char*>(glewGetErrorString(e)));
    glGetError();  // GLEW may leave GL_INVALID_ENUM behind on core profiles

    glfwSetWindowUserPointer(window_, this);
    // Ours first: ImGui's GLFW backend chains to callbacks installed before it.
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) { appOf(w)->onKey(key, action); });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) { appOf(w)->onMouseButton(button, action); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { appOf(w)->onScroll(dy); });
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    imgui_ = true;

    renderer_ = std::make_unique<Renderer>();
    renderer_->init();
    if (options_.headless) offscreen_ = std::make_unique<OffscreenTarget>(options_.width, options_.height);

    ui_.paused = options_.paused;
    ui_.draw = DrawToggles{options_.contacts, options_.joints, options_.bounds, options_.sleep};
    ui_.sceneNames = builtinSceneNames();
    for (const BackendInfo& b : availableBackends()) ui_.allBackends.push_back(b.name);
    ui_.selected.assign(ui_.allBackends.size(), 0);
    open(options_.scene, options_.backends);
    if (options_.camera.size() >= 3) {
        camera_.yaw = options_.camera[0] * kDegrees;
        camera_.pitch = options_.camera[1] * kDegrees;
        camera_.distance = options_.camera[2];
        if (options_.camera.size() >= 6) camera_.target = Vec3(options_.camera[3], options_.camera[4], options_.camera[5]);
    }
    if (!options_.video.empty()) {
        int w = options_.width, h = options_.height;
        if (!options_.headless) glfwGetFramebufferSize(window_, &w, &h);
        video_ = std::make_unique<VideoWriter>(options_.video, w, h, 60);
    }
}

App::~App() {
    renderer_.reset();
    offscreen_.reset();
    if (imgui_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

void App::open(const std::string& scene, const std::vector<std::string>& backends) {
    const SceneSource source = loadSceneSource(scene);
    views_.open(source, backends, ui_.edit);
    batches_.assign(views_.views().size(), Batch{});
    accumulator_ = 0.0;
    picker_.end();
    for (std::size_t i = 0; i < ui_.allBackends.size(); ++i)
        ui_.selected[i] = std::find(backends.begin(), backends.end(), ui_.allBackends[i]) != backends.end();
    for (std::size_t i = 0; i < ui_.sceneNames.size(); ++i)
        if (ui_.sceneNames[i] == source.name) ui_.sceneIndex = static_cast<int>(i);
    frameCamera();
}

void App::frameCamera() {
    // Frame the dynamic bodies of the first view that runs (every body if none is dynamic).
    for (View& v : views_.views()) {
        if (!v.world) continue;
        Batch batch;
        batch.clear(Vec3::Zero());
        batch.draw(*v.world, DrawToggles{});
        Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
        bool any = false;
        for (int pass = 0; pass < 2 && !any; ++pass)
            for (const auto& [index, info] : batch.bodies) {
                if (!info.hasBounds) continue;
                if (pass == 0 && v.world->body(info.id).type() != BodyType::Dynamic) continue;
                lo = lo.cwiseMin(info.lo);
                hi = hi.cwiseMax(info.hi);
                any = true;
            }
        if (any) camera_.frame(lo, hi, v.world->settings().planar && views_.source().scene.settings.planar);
        return;
    }
}

void App::onKey(int key, int action) {
    if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
    switch (key) {
        case GLFW_KEY_P: ui_.paused = !ui_.paused; break;
        case GLFW_KEY_O: ui_.stepOnce = true; break;
        case GLFW_KEY_R: ui_.reset = true; break;
        case GLFW_KEY_B:
        case GLFW_KEY_SPACE: ui_.shoot = true; break;
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
        default: break;
    }
}

void App::onMouseButton(int button, int action) {
    if (action == GLFW_RELEASE) {
        if (button == GLFW_MOUSE_BUTTON_LEFT) {
            picker_.end();
            orbiting_ = false;
        }
        if (button == GLFW_MOUSE_BUTTON_RIGHT) orbiting_ = false;
        if (button == GLFW_MOUSE_BUTTON_MIDDLE) panning_ = false;
        return;
    }
    if (ImGui::GetIO().WantCaptureMouse) return;
    // Where the cursor is now (the press may come before this frame's motion was read).
    double wx = 0, wy = 0;
    glfwGetCursorPos(window_, &wx, &wy);
    cursorX_ = wx * scale_;
    cursorY_ = wy * scale_;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        double lx = 0, ly = 0;
        const auto view = viewAt(cursorX_, cursorY_, lx, ly);
        if (view && picker_.begin(views_, *view, camera_.ray(lx, ly, rects_[*view].w, rects_[*view].h), camera_)) return;
        orbiting_ = true;  // nothing grabbed: the left button turns the camera
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT) orbiting_ = true;
    if (button == GLFW_MOUSE_BUTTON_MIDDLE) panning_ = true;
}

void App::onScroll(double dy) {
    if (!ImGui::GetIO().WantCaptureMouse) camera_.zoom(dy);
}

std::optional<std::size_t> App::viewAt(double x, double y, double& localX, double& localY) const {
    for (std::size_t i = 0; i < rects_.size(); ++i) {
        const Rect& r = rects_[i];
        if (x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h) {
            localX = x - r.x;
            localY = y - r.y;
            return i;
        }
    }
    return std::nullopt;
}

void App::handleMouse() {
    double wx = 0, wy = 0;
    glfwGetCursorPos(window_, &wx, &wy);
    const double x = wx * scale_, y = wy * scale_;
    const double dx = x - cursorX_, dy = y - cursorY_;
    cursorX_ = x;
    cursorY_ = y;
    if (picker_.active()) {
        double lx = 0, ly = 0;
        if (const auto view = viewAt(x, y, lx, ly)) picker_.move(camera_.ray(lx, ly, rects_[*view].w, rects_[*view].h));
    } else if (orbiting_) {
        camera_.orbit(dx, dy);
    } else if (panning_ && !rects_.empty()) {
        camera_.pan(dx, dy, rects_[0].h);
    }
}

void App::shoot() {
    if (rects_.empty()) return;
    double lx = rects_[0].w * 0.5, ly = rects_[0].h * 0.5;
    std::size_t view = 0;
    if (const auto v = viewAt(cursorX_, cursorY_, lx, ly)) view = *v;
    const Ray ray = camera_.ray(lx, ly, rects_[view].w, rects_[view].h);
    if (views_.source().scene.settings.planar) {
        // In the plane: from the view's left edge toward the point under the cursor.
        const double t = std::abs(ray.direction.z()) > 1e-9 ? -ray.origin.z() / ray.direction.z() : camera_.distance;
        const Vec3 aim = ray.origin + t * ray.direction;
        const double halfWidth = camera_.distance * std::tan(0.5 * camera_.fovY) * rects_[view].w / rects_[view].h;
        Vec3 from = aim - 0.8 * halfWidth * camera_.right() + Vec3(0, 0.2 * halfWidth, 0);
        from.z() = 0.0;
        views_.shootBall(from, 20.0 * (aim - from).normalized());
    } else {
        views_.shootBall(ray.origin + 0.5 * ray.direction, 25.0 * ray.direction);
    }
}

void App::handleRequests() {
    try {
        if (ui_.reopen) {
            std::vector<std::string> backends;
            for (std::size_t i = 0; i < ui_.allBackends.size(); ++i)
                if (ui_.selected[i]) backends.push_back(ui_.allBackends[i]);
            if (backends.empty() || backends.size() > Views::kMaxViews) {
                ui_.message = "choose 1 to 4 backends";
            } else {
                open(ui_.openScene, backends);
                ui_.message.clear();
            }
        }
        if (ui_.settingsChanged) views_.apply(ui_.edit);
        if (ui_.reset) {
            views_.reset();
            picker_.end();
            accumulator_ = 0.0;
        }
        if (ui_.shoot) shoot();
    } catch (const Error& e) {
        ui_.message = e.what();
    }
    ui_.reopen = ui_.settingsChanged = ui_.reset = ui_.shoot = false;
}

int App::stepsThisFrame(double elapsed) {
    int steps = 0;
    if (options_.headless) {
        steps = ui_.paused ? 0 : 1;  // one step per frame: a run is the same whatever the machine
    } else if (!ui_.paused) {
        double dt = 1.0 / 60.0;
        for (const View& v : views_.views())
            if (v.world) {
                dt = v.world->settings().timeStep;
                break;
            }
        accumulator_ += elapsed * ui_.timeScale;
        steps = static_cast<int>(accumulator_ / dt);
        accumulator_ -= steps * dt;
        if (steps > 4) {  // slower than real time: drop the backlog rather than spiral
            steps = 4;
            accumulator_ = 0.0;
        }
    }
    if (ui_.stepOnce) ++steps;
    ui_.stepOnce = false;
    return steps;
}

void App::render(int width, int height) {
    if (offscreen_) offscreen_->bind();
    else glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (std::size_t i = 0; i < views_.views().size(); ++i) {
        Batch& batch = batches_[i];
        batch.clear(camera_.target, 6.0 * camera_.distance);
        View& v = views_.views()[i];
        if (v.world) batch.draw(*v.world, ui_.draw);
        renderer_->draw(batch, camera_, rects_[i], height);
    }
    glViewport(0, 0, width, height);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (!options_.hideUi) {
        drawViewLabels(views_, rects_, scale_);
        if (!options_.headless) {
            drawControlPanel(ui_, views_);
            if (ui_.showPlots) drawPlots(views_, width / scale_, height / scale_);
        }
    }
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

int App::run() {
    if (!options_.record.empty()) std::filesystem::create_directories(options_.record);
    Image last;
    auto previous = std::chrono::steady_clock::now();
    for (int frame = 0; !glfwWindowShouldClose(window_); ++frame) {
        glfwPollEvents();
        int width = options_.width, height = options_.height;
        if (!options_.headless) {
            glfwGetFramebufferSize(window_, &width, &height);
            int ww = 1, wh = 1;
            glfwGetWindowSize(window_, &ww, &wh);
            scale_ = ww > 0 ? static_cast<float>(width) / static_cast<float>(ww) : 1.0f;
            if (width <= 0 || height <= 0) {  // minimised
                glfwWaitEvents();
                continue;
            }
        }
        const bool plots = !options_.headless && !options_.hideUi && ui_.showPlots;
        const int viewHeight = plots ? std::max(1, height - static_cast<int>(kPlotHeight * scale_)) : height;
        rects_ = layoutViews(views_.views().size(), width, viewHeight);

        const auto now = std::chrono::steady_clock::now();
        const double elapsed = std::min(0.1, std::chrono::duration<double>(now - previous).count());
        previous = now;
        handleMouse();
        handleRequests();
        const int steps = stepsThisFrame(elapsed);
        for (int i = 0; i < steps; ++i) views_.step([this](View& v) { picker_.pull(v); });

        render(width, height);
        const bool lastFrame = options_.frames > 0 && frame + 1 >= options_.frames;
        if (!options_.record.empty() || video_ || (lastFrame && !options_.screenshot.empty())) {
            last = readFramebuffer(width, height);
            if (!options_.record.empty()) {
                char name[32];
                std::snprintf(name, sizeof name, "/frame_%05d.png", frame);
                writePng(last, options_.record + name);
            }
            if (video_) video_->add(last);
        }
        if (!options_.headless) glfwSwapBuffers(window_);
        if (lastFrame) {
            if (!options_.screenshot.empty()) writePng(last, options_.screenshot);
            if (!options_.dumpProjections.empty())
                writeProjections(options_.dumpProjections, views_, batches_, rects_, camera_, width, height);
            break;
        }
    }
    if (video_) video_->finish();
    // A view that cannot run (a 3D scene on a 2D engine, a setting a backend lacks) is shown, not
    // fatal; it is reported here too.
    for (const View& v : views_.views())
        if (!v.error.empty()) std::fprintf(stderr, "anyphys_testbed: %s: %s\n", v.backend.c_str(), v.error.c_str());
    for (const View& v : views_.views())
        std::printf("%s %s: t %.3f s, %zu bodies, mean step %.3f ms%s\n", v.backend.c_str(), v.sceneName.c_str(), v.time(),
                    v.bodies.size(), v.meanStepMs,
                    v.check ? (", " + v.check->label + " " + std::to_string(v.checkValue) + (v.checkPasses() ? " ok" : " FAIL")).c_str() : "");
    return 0;
}

int runTestbed(const TestbedOptions& options) {
    App app(options);
    return app.run();
}

}  // namespace anyphys::testbed
