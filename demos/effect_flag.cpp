// A flag in the wind: a 2 x 1 m cloth pinned along its edge to a pole, a wind field blowing across
// it. In a planar world the sheet lies in the plane, where wind across it has no normal to push:
// it hangs from the pole, said so in the summary.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "effects_demos.hpp"

namespace anyphys::demo {

int runFlag(const DemoOptions& o) {
    WorldSettings settings = settingsFor(o.backend);
    World world(settings);
    BodyDef pole;
    pole.name = "pole";
    pole.type = BodyType::Static;
    pole.shape = ShapeDef::capsule(0.04, 1.5);
    pole.position = Vec3(-0.06, 1.5, 0);
    Body poleBody = world.createBody(pole);
    world.addField(FieldDef::wind(settings.planar ? Vec3(6, 0, 0) : Vec3(6, 0, 1.5), 1.2));
    ClothDef flag;
    flag.name = "flag";
    flag.corner = Vec3(0, 3.0, 0);
    flag.size = {2.0, 1.0};
    flag.resolution = {20, 10};
    flag.areaDensity = 0.2;
    flag.stiffness = 1e4;
    flag.damping = 0.1;
    flag.pinned = {{0, 0}, {0, 10}};
    world.addCloth(flag);
    const SimulationResult r = simulate(world, {poleBody}, o);
    const auto& x = *world.particleSystems()[0].positions;
    double reach = 0.0, sideways = 0.0;
    for (const Vec3& p : x) {
        reach = std::max(reach, p.x());
        sideways = std::max(sideways, std::abs(p.z()));
    }
    std::printf("flag on %s%s: %.1f s, %zu nodes, %.3f ms per step\n", o.backend.c_str(), settings.planar ? " (planar)" : "",
                world.time(), x.size(), r.msPerStep);
    std::printf("  the free edge reaches %.2f m from the pole (flag 2 m long), %.2f m out of its plane\n", reach, sideways);
    bool flying = reach > 1.0;
    if (settings.planar) {
        std::printf("  planar world: the sheet lies in the plane, so the wind (along it) cannot fill it; it hangs\n");
        flying = true;
    } else {
        std::printf("  %s\n", flying ? "flying in the wind" : "NOT flying");
    }
    return r.finite && flying ? 0 : 1;
}

}  // namespace anyphys::demo
