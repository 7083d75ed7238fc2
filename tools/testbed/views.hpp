#pragma once
// The testbed's simulations: one world per backend, all made from the same scene and stepped
// together (the thesis' "simultaneous simulations"). Each view times its steps, feeds the scene's
// check and keeps a history of step time and energy for the plots.
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "scene_source.hpp"

namespace anyphys::testbed {

/// The settings the panel edits, applied to every view. Unset fields keep the scene's value (or
/// the backend's default when the scene leaves them unset).
struct LiveSettings {
    std::optional<double> timeStep;
    std::optional<int> substeps;
    std::optional<int> iterations;
    std::optional<Solver> solver;
    std::optional<Integrator> integrator;
    std::optional<Effects> effects;
};

struct HistorySample {
    float stepMs = 0.0f;
    float energy = 0.0f;
};

struct View {
    std::string backend;
    std::string sceneName;       ///< the scene this view runs (a planar variant on a 2D engine)
    std::string error;           ///< why this view does not run; empty when it does
    std::string sceneFile;       ///< where the scene came from; empty for a built-in scene
    Scene scene;
    std::optional<SceneCheck> check;
    std::unique_ptr<World> world;
    std::vector<Body> bodies;    ///< the scene's bodies in scene order, then the balls shot
    std::vector<BodyDef> balls;  ///< defs of the balls shot, to rebuild them
    std::size_t sceneBodies = 0;
    std::unique_ptr<SceneProbe> probe;
    double checkValue = 0.0;
    double timeOffset = 0.0;     ///< s simulated before the last rebuild
    double lastStepMs = 0.0;
    double meanStepMs = 0.0;     ///< exponential mean
    double energy = 0.0;         ///< J, kinetic + gravitational potential
    std::deque<HistorySample> history;

    double time() const { return timeOffset + (world ? world->time() : 0.0); }
    bool checkPasses() const { return check && check->passes(checkValue); }
};

class Views {
public:
    /// Opens `source` on each backend (at most 4). A view that cannot run keeps its reason.
    void open(const SceneSource& source, const std::vector<std::string>& backends, const LiveSettings& settings);
    /// Rebuilds every world from its scene at t = 0.
    void reset();
    /// Rebuilds every world with `settings`, carrying over each body's state (and the balls).
    void apply(const LiveSettings& settings);
    /// One step of every running view; `beforeStep` runs for each just before its world steps.
    void step(const std::function<void(View&)>& beforeStep = {});
    /// Adds a ball to every running view (flattened into the plane in planar worlds).
    void shootBall(const Vec3& position, const Vec3& velocity);

    std::vector<View>& views() { return views_; }
    const std::vector<View>& views() const { return views_; }
    const SceneSource& source() const { return source_; }
    const LiveSettings& settings() const { return settings_; }

    static constexpr std::size_t kMaxViews = 4;
    static constexpr std::size_t kHistory = 600;  ///< samples kept for the plots (10 s at 60 Hz)

private:
    void build(View& view, const std::vector<BodyState>* states);
    void measure(View& view);

    SceneSource source_;
    LiveSettings settings_;
    std::vector<View> views_;
};

/// Kinetic plus gravitational potential energy of `bodies` in `world`, J (gravity scales from
/// `defs`, one per body in the same order; bodies past its end take 1).
double mechanicalEnergy(const World& world, const std::vector<Body>& bodies, const std::vector<BodyDef>& defs);

}  // namespace anyphys::testbed
