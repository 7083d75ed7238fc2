// The README's example: game code written once against anyphys; the backend is one setting.
#include <anyphys/anyphys.hpp>
#include <iostream>

int main(int argc, char** argv) {
    anyphys::WorldSettings settings;
    settings.backend = argc > 1 ? argv[1] : "native";  // "native", later "ode", "bullet", ...
    settings.integrator = anyphys::Integrator::RK4;
    anyphys::World world(settings);

    anyphys::BodyDef def;
    def.shape = anyphys::ShapeDef::box({0.5, 0.1, 0.3});
    def.position = {0, 10, 0};
    def.linearVelocity = {3, 5, 0};
    def.angularVelocity = {0.1, 0, 4};  // about the box's intermediate axis (z): it tumbles
    anyphys::Body box = world.createBody(def);

    while (world.time() < 2.0) world.step();  // fixed step, 1/60 s by default
    std::cout << "after " << world.time() << " s: position " << box.position().transpose()
              << ", spin " << box.angularVelocityLocal().transpose() << '\n';
}
