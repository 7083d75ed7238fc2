#pragma once
// Measures of one run of a catalogue scene, shared by `anyphys compare`'s table and its sweeps:
// conserved quantities, what a backend lacks for a scene, and the verdict of a scene's check.
#include <optional>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"

namespace anyphys::cli {

/// Kinetic plus gravitational potential energy (-m g.p, with each body's gravity scale), J.
double mechanicalEnergy(const World& world, const std::vector<Body>& bodies, const Scene& scene);
/// |sum of the bodies' angular momenta about their centres|, world frame, kg m^2/s.
double angularMomentumNorm(const std::vector<Body>& bodies);
/// (end - start) / |start|; nothing when start is 0 (no scale to compare against).
std::optional<double> relativeChange(double start, double end);
/// Every body's state, in scene order (what a SceneProbe observes).
std::vector<BodyState> bodyStates(const std::vector<Body>& bodies);
/// What the backend declares it lacks for this scene at these settings; empty when it claims
/// everything.
std::vector<std::string> missingFor(const Capabilities& caps, const WorldSettings& settings, const Scene& scene);
/// Radius of a sphere about the body origin holding the shape, m (0 for planes and meshes).
double boundingRadius(const ShapeDef& shape);

/// A scene check's value judged against its bound and the backend's declarations.
struct CheckVerdict {
    double value = 0.0;
    bool passed = false;          ///< within the check's tolerance
    bool knownDeviation = false;  ///< failed, and the backend declares that criterion missed (within its ceiling)
    std::optional<double> ceiling;  ///< the backend's declared ceiling for the criterion, if any
    bool overCeiling = false;     ///< declared, but the value is worse than the ceiling
};
CheckVerdict judgeCheck(const SceneCheck& check, const Capabilities& caps, double value);

}  // namespace anyphys::cli
