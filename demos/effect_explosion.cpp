// An explosion in a stack: a tower of crates stands for a second, then a charge at its foot goes
// off (an explosion field: impulses falling with distance, blocked by static geometry).
#include <cmath>
#include <cstdio>

#include "effects_demos.hpp"

namespace anyphys::demo {

int runExplosion(const DemoOptions& o) {
    WorldSettings settings = settingsFor(o.backend);
    World world(settings);
    std::vector<Body> crates;
    BodyDef ground;
    ground.name = "ground";
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::box(Vec3(20, 0.5, 20));
    ground.position = Vec3(0, -0.5, 0);
    world.createBody(ground);
    // A pyramid of 5 layers of 0.5 m crates (15 crates).
    for (int layer = 0; layer < 5; ++layer)
        for (int k = 0; k < 5 - layer; ++k) {
            BodyDef crate;
            crate.name = "crate" + std::to_string(crates.size());
            crate.shape = ShapeDef::box(Vec3(0.25, 0.25, 0.25));
            crate.density = 300.0;
            crate.position = Vec3(-1.0 + 0.5 * k + 0.25 * layer, 0.25 + 0.5 * layer, 0);
            crates.push_back(world.createBody(crate));
        }
    world.addField(FieldDef::explosion(Vec3(0.3, 0.05, 0), 1.0, 400.0, 3.0));
    double heightBefore = 0.0;
    StepHooks hooks;
    hooks.before = [&](long long) {
        if (heightBefore == 0.0 && world.time() >= 0.9) heightBefore = crates.back().position().y();
    };
    const SimulationResult r = simulate(world, crates, o, hooks);
    int moved = 0;
    double fastest = 0.0;
    for (const Body& c : crates) {
        fastest = std::max(fastest, c.linearVelocity().norm());
        if (std::abs(c.position().x()) > 2.0 || c.position().y() > 2.6) ++moved;
    }
    std::printf("explosion on %s%s: %.1f s, %.3f ms per step\n", o.backend.c_str(), settings.planar ? " (planar)" : "",
                world.time(), r.msPerStep);
    std::printf("  top crate at %.2f m before the blast; %d of %zu crates thrown clear of the stack's footprint\n",
                heightBefore, moved, crates.size());
    const bool stood = heightBefore > 2.1, blown = moved >= 3;
    std::printf("  %s; %s\n", stood ? "the stack stood" : "the stack had FALLEN before the blast",
                blown ? "the blast scattered it" : "the blast did NOT scatter it");
    return r.finite && stood && blown ? 0 : 1;
}

}  // namespace anyphys::demo
