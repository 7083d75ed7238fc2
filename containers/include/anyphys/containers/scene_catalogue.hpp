#pragma once
// The one catalogue of built-in scenes, shared by tests, demos, benchmarks and the `anyphys`
// tool. Scenes with an analytic answer carry it, so any consumer can measure error.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/containers/scene.hpp"

namespace anyphys {

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
};

/// Every built-in scene, in a stable order.
const std::vector<CatalogueScene>& sceneCatalogue();
/// The named scene; throws anyphys::Error listing the known names otherwise.
const CatalogueScene& catalogueScene(const std::string& name);

/// Benchmark load: `count` free dynamic cubes (0.2 m, 1 kg) on a grid, each thrown upwards and
/// spinning, under default gravity with nothing to collide with. Deterministic.
Scene freeBodiesScene(int count);

}  // namespace anyphys
