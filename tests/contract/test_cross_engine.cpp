// Cross-engine agreement: the same catalogue scene, run unchanged on every built backend that
// can take it (only WorldSettings::backend differs), gives trajectories that agree with the
// reference engine's (the first built backend that can run the scene, native in a full build)
// within stated tolerances. Each bound is derived from the contract: two
// backends each within the contract's bound of the exact answer are within twice it of each other.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "contact_helpers.hpp"

namespace anyphys::test {
namespace {

using Trajectory = std::vector<std::vector<BodyState>>;  // [step][body], step 0 = initial state

/// Runs the scene for `seconds` on `backend`, recording every body after every step.
Trajectory record(const CatalogueScene& entry, const std::string& backend, double seconds) {
    WorldSettings s = entry.scene.settings;
    s.backend = backend;
    World world(s, entry.scene.materials);
    std::vector<Body> bodies;
    for (const BodyDef& def : entry.scene.bodies) bodies.push_back(world.createBody(def));
    Trajectory out;
    const auto snapshot = [&] {
        std::vector<BodyState> states;
        for (const Body& b : bodies) states.push_back(b.state());
        out.push_back(std::move(states));
    };
    snapshot();
    const long long steps = std::llround(seconds / s.timeStep);
    for (long long i = 0; i < steps; ++i) {
        world.step();
        snapshot();
    }
    return out;
}

/// Largest distance between the two runs' positions of `body`, projected on `axis` (or the full
/// distance when `axis` is zero), over every recorded step.
double largestGap(const Trajectory& a, const Trajectory& b, std::size_t body, const Vec3& axis = Vec3::Zero()) {
    double worst = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        const Vec3 d = a[i][body].position - b[i][body].position;
        const double gap = axis.isZero(0) ? d.norm() : std::abs(d.dot(axis));
        if (!(gap <= worst)) worst = gap;  // keeps a NaN visible
    }
    return worst;
}

/// The built backends that can run the scene: planar scenes need `planar`, 3D scenes three
/// dimensions, and every shape the scene uses.
std::vector<std::string> backendsFor(const Scene& scene) {
    std::vector<std::string> out;
    for (const BackendInfo& info : availableBackends()) {
        const Capabilities& caps = info.capabilities;
        bool able = scene.settings.planar ? caps.planar : caps.dimensions == 3;
        for (const BodyDef& def : scene.bodies) able = able && caps.shapes.contains(def.shape.type);
        if (able) out.push_back(info.name);
    }
    return out;
}

/// Compares every other capable backend with the first capable one (the reference) on `sceneName`; `measure` returns the gap
/// between two trajectories and `bound` is the agreement the test demands. A backend that
/// declares the scene's own contract criterion (`criterion`) a known deviation cannot be expected
/// to agree where it misses it: its gap is reported as KNOWN instead of failing.
void expectAgreement(const std::string& sceneName, const std::string& criterion, double seconds, double bound,
                     const std::string& what, const std::function<double(const Trajectory&, const Trajectory&)>& measure) {
    const CatalogueScene& entry = catalogueScene(sceneName);
    const std::vector<std::string> backends = backendsFor(entry.scene);
    if (backends.size() < 2)
        GTEST_SKIP() << sceneName << ": fewer than two built backends can run it (" << backends.size() << ")";
    const std::string& referenceName = backends.front();  // registration order: native first when built
    const Trajectory reference = record(entry, referenceName, seconds);
    for (std::size_t i = 1; i < backends.size(); ++i) {
        const Trajectory other = record(entry, backends[i], seconds);
        const double gap = measure(reference, other);
        report(sceneName + ": " + referenceName + " vs " + backends[i] + ", " + what, gap, "m");
        const auto& deviations = backendInfo(backends[i]).capabilities.knownDeviations;
        if (gap > bound && deviations.contains(criterion)) {
            std::cout << "[ KNOWN    ] " << backends[i] << " departs from " << referenceName << " on " << sceneName << " by " << gap
                      << " m (bound " << bound << "): it declares " << criterion << " (" << deviations.at(criterion)
                      << ")\n";
            continue;
        }
        EXPECT_LE(gap, bound) << sceneName << " on " << backends[i] << " departs from " << referenceName << " by " << gap << " m ("
                              << what << "; bound " << bound << " m)";
    }
}

// Bouncing ball (drop 4.5 m, e = 0.5), first 2 s: the fall and the first rebound. The contract
// puts each backend's rebound within 5 % of e^2 h = 1.125 m of the exact one, so two backends
// agree within 10 % of it (0.1125 m) at the apex, and the falls before impact are the same
// integrator's. Height only: nothing pushes the ball sideways.
constexpr double kBallBound = 0.1 * 1.125;

TEST(CrossEngine, BouncingBallHeightsAgree) {
    expectAgreement("bouncing_ball", "restitution.rebound_height", 2.0, kBallBound, "largest height gap over 2 s",
                    [](const Trajectory& a, const Trajectory& b) { return largestGap(a, b, 1, Vec3::UnitY()); });
}
TEST(CrossEngine, PlanarBouncingBallHeightsAgree) {
    expectAgreement("bouncing_ball_planar", "planar.restitution.rebound_height", 2.0, kBallBound, "largest height gap over 2 s",
                    [](const Trajectory& a, const Trajectory& b) { return largestGap(a, b, 1, Vec3::UnitY()); });
}

// Box sliding on a 30 deg slope for 1.5 s: s = a t^2 / 2 = 2.65 m. Each backend's acceleration
// is within 5 % of exact, so positions agree within 10 % of the slide (0.265 m), plus 1 cm for
// the first steps in which each engine's contact forms.
constexpr double kSlideBound = 0.1 * 2.65 + 0.01;

TEST(CrossEngine, SlopeSlideAgrees) {
    expectAgreement("slope_slide", "slope.kinetic_acceleration", 1.5, kSlideBound, "largest position gap over 1.5 s",
                    [](const Trajectory& a, const Trajectory& b) { return largestGap(a, b, 1); });
}
TEST(CrossEngine, PlanarSlopeSlideAgrees) {
    expectAgreement("slope_slide_planar", "planar.slope.kinetic_acceleration", 1.5, kSlideBound, "largest position gap over 1.5 s",
                    [](const Trajectory& a, const Trajectory& b) { return largestGap(a, b, 1); });
}

// 10-box stack for 10 s: the top box of each backend stays within 1 cm sideways of its start and
// sinks at most 10 x linearSlop (5 cm), so two backends' top boxes are within 2 cm sideways and
// 5 cm vertically of each other; the bound is the diagonal of that box.
TEST(CrossEngine, TenBoxStackTopAgrees) {
    const double bound = std::hypot(0.02, 0.05);
    expectAgreement("box_stack_10", "stack10.top_drift", 10.0, bound, "largest top-box position gap over 10 s",
                    [](const Trajectory& a, const Trajectory& b) { return largestGap(a, b, 10); });
}

}  // namespace
}  // namespace anyphys::test
