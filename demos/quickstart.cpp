// The README's example: game code written once against anyphys; the backend is one setting.
#include <anyphys/anyphys.hpp>
#include <iostream>

int main(int argc, char** argv) {
    anyphys::WorldSettings settings;
    settings.backend = argc > 1 ? argv[1] : "native";  // "native", "ode", "bullet" or "box2d"
    // A 2D engine takes planar worlds only; this scene lies in the XY plane, so it runs anywhere.
    settings.planar = anyphys::backendInfo(settings.backend).capabilities.dimensions == 2;
    anyphys::World world(settings);

    anyphys::BodyDef ground;
    ground.type = anyphys::BodyType::Static;
    ground.shape = anyphys::ShapeDef::plane({0, 1, 0}, 0.0);
    world.createBody(ground);

    anyphys::BodyDef def;
    def.shape = anyphys::ShapeDef::box({0.5, 0.25, 0.5});
    def.position = {0, 3, 0};
    def.linearVelocity = {2, 3, 0};
    def.angularVelocity = {0, 0, 4};
    anyphys::Body box = world.createBody(def);

    while (world.time() < 3.0) world.step();  // fixed step, 1/60 s by default
    std::cout << world.backendName() << ": after " << world.time() << " s the box is at "
              << box.position().transpose() << (box.isAwake() ? "" : ", asleep") << '\n';
}
