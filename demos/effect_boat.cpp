// A boat on waves: a buoyancy field whose surface rises and tilts as a long swell passes (the field
// is replaced before each step with the surface of that moment), so the hull heaves and rolls.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "effects_demos.hpp"

namespace anyphys::demo {

int runBoat(const DemoOptions& o) {
    WorldSettings settings = settingsFor(o.backend);
    World world(settings);
    // A hull 3 x 0.6 x 1.2 m of density 400 (a wooden boat) with a mast.
    BodyDef boat;
    boat.name = "boat";
    boat.shape = ShapeDef::compound({ShapeDef::box(Vec3(1.5, 0.3, 0.6)),
                                     ShapeDef::box(Vec3(0.05, 1.0, 0.05)).placed(Vec3(0, 1.3, 0))});
    boat.density = 400.0;
    boat.position = Vec3(0, 0.1, 0);
    boat.allowSleep = false;
    Body hull = world.createBody(boat);
    // The swell: amplitude 0.3 m, period 5 s; the surface tilts with the wave's slope (up to 6 deg).
    const double amplitude = 0.3, period = 5.0, tilt = 0.1;
    const auto surfaceAt = [&](double t) {
        const double phase = 2 * std::numbers::pi * t / period;
        const Vec3 normal = Vec3(std::sin(tilt * std::cos(phase)), std::cos(tilt * std::cos(phase)), 0).normalized();
        return FieldDef::buoyancy(1000.0, normal, amplitude * std::sin(phase), 0.5, 0.5);
    };
    double lowest = 1e9, highest = -1e9, roll = 0.0;
    StepHooks hooks;
    hooks.before = [&](long long) {
        world.clearFields();
        world.addField(surfaceAt(world.time()));
    };
    hooks.after = [&](long long) {
        lowest = std::min(lowest, hull.position().y());
        highest = std::max(highest, hull.position().y());
        const Vec3 up = hull.orientation() * Vec3::UnitY();
        roll = std::max(roll, std::acos(std::clamp(up.y(), -1.0, 1.0)));
    };
    const SimulationResult r = simulate(world, {hull}, o, hooks);
    std::printf("boat on %s: %.1f s, %.3f ms per step\n", o.backend.c_str(), world.time(), r.msPerStep);
    std::printf("  heave: %.3f .. %.3f m (swell +-%.2f m), largest roll %.1f deg\n", lowest, highest, amplitude,
                roll * 180 / std::numbers::pi);
    // Afloat: it followed the swell and neither sank nor flew.
    const bool afloat = highest - lowest > amplitude && lowest > -1.0 && highest < 1.0;
    std::printf("  %s\n", afloat ? "afloat, riding the swell" : "NOT riding the swell");
    return r.finite && afloat ? 0 : 1;
}

}  // namespace anyphys::demo
