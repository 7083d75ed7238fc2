#pragma once
// The one catalogue of built-in scenes, shared by tests, demos, benchmarks and the `anyphys`
// tool. Scenes with an analytic answer carry it, so any consumer can measure error.
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/containers/scene.hpp"

namespace anyphys {

/// Watches one run of a scene: fed every body's state (in scene order) at t = 0 and after each
/// step, it reduces the run to one number. Works on states only, so every backend is measured
/// the same way.
class SceneProbe {
public:
    virtual ~SceneProbe() = default;
    virtual void observe(double time, const std::vector<BodyState>& states) = 0;
    /// The measure so far (after the last observe()).
    virtual double value() const = 0;
};

/// A scene's own measure of success, for scenes whose full motion has no closed form (stacks,
/// piles, bounces): what to measure and what the exact physics gives.
struct SceneCheck {
    std::string label;        ///< what is measured, e.g. "top drift"
    std::string unit;         ///< of the value, e.g. "m"; "" for ratios
    double expected = 0.0;    ///< the value exact physics gives
    double tolerance = 0.0;   ///< passes when |value - expected| <= tolerance
    std::string why;          ///< the reason for the tolerance, one line
    std::function<std::unique_ptr<SceneProbe>()> makeProbe;  ///< a fresh probe per run
    /// The contract criterion this check measures (e.g. "stack10.top_drift"), so a backend's
    /// declared known deviation (Capabilities::knownDeviations) can be recognised; "" for none.
    std::string criterion;

    bool passes(double value) const { return std::abs(value - expected) <= tolerance; }
};

struct CatalogueScene {
    std::string name;          ///< e.g. "projectile"
    std::string description;   ///< one line
    Scene scene;
    double duration = 1.0;     ///< s, how long the scene is meant to run
    /// Exact state of a body (by name) at time t, where the scene has an analytic solution.
    /// Empty function: no analytic solution. Returns nothing for a body it does not describe.
    std::function<std::optional<BodyState>(const std::string& body, double t)> reference;
    /// Total mechanical energy (kinetic + gravitational potential) is conserved by the exact
    /// motion, so its drift measures the integrator.
    bool conservesEnergy = false;
    /// The sum of the bodies' angular momenta about their centres (world frame) is conserved by
    /// the exact motion: no torques act and gravity is uniform.
    bool conservesAngularMomentum = false;
    /// The scene's own measure (rebound height, top-box drift, ...), where it has one.
    std::optional<SceneCheck> check;
    /// Part of `anyphys compare` when no --scenes are given; off for loads too slow to run on
    /// every backend and integrator each time (they stay selectable by name).
    bool compareByDefault = true;
    /// One of the hard cases (`anyphys hardcases`): a scene that breaks weak solvers, with a
    /// pass criterion (its check) every backend is measured against, sleeping off.
    bool hardCase = false;
};

/// Every built-in scene, in a stable order (the hard cases among them).
const std::vector<CatalogueScene>& sceneCatalogue();
/// The named scene; throws anyphys::Error listing the known names otherwise.
const CatalogueScene& catalogueScene(const std::string& name);

/// Benchmark load: `count` free dynamic cubes (0.2 m, 1 kg) on a grid, each thrown upwards and
/// spinning, under default gravity with nothing to collide with (mask 0: they pass through each
/// other). Deterministic.
Scene freeBodiesScene(int count);

/// Benchmark load: a ground plane (body 0, "ground") and `nx` x `ny` x `nz` unit cubes (half
/// extent 0.5 m, 1000 kg/m^3) on a grid `spacing` m apart, the lowest layer's bottoms `dropHeight`
/// m above the ground, at rest. timeStep 1/60. The catalogue's box_grid_1000 is (10, 10, 10, 1.2, 1).
Scene boxGridScene(int nx, int ny, int nz, double spacing, double dropHeight);

}  // namespace anyphys
