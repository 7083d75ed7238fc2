// Native contact stiffness: the soft step caps contactHertz so that every period of the contact
// spring spans at least five substeps (StepSolver::solve). Stiffer than that, Gauss-Seidel at one
// iteration per substep does not settle a pile: it rings for ever.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"

namespace anyphys {
namespace {

using test::backendSettings;
using test::boxDef;

// Fastest box after dropping a 3 x 3 x 10 grid of unit cubes (0.1 m gaps) on a box ground and
// stepping it `seconds` at 60 Hz, sleeping off, with the default contactHertz (60).
double fastestAfterDrop(int substeps, int iterations, double seconds) {
    WorldSettings settings = backendSettings("native");
    settings.substeps = substeps;
    settings.iterations = iterations;
    World world(settings);
    BodyDef ground = boxDef("ground", {20, 1, 20}, {0, -1, 0});
    ground.type = BodyType::Static;
    world.createBody(ground);
    std::vector<Body> boxes;
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 3; ++x)
            for (int z = 0; z < 3; ++z) {
                BodyDef box = boxDef("box", {0.5, 0.5, 0.5}, {(x - 1) * 1.1, 0.5 + y * 1.1, (z - 1) * 1.1});
                box.allowSleep = false;
                boxes.push_back(world.createBody(box));
            }
    while (world.time() < seconds) world.step();
    double fastest = 0.0;
    for (const Body& b : boxes) fastest = std::max(fastest, b.linearVelocity().norm());
    return fastest;
}

// Box3D's pass count (4 substeps x 1 iteration) and one substep fewer. Under Box2D v3's cap (a
// quarter of the substep rate: 60 Hz at 4 substeps, 45 Hz at 3) the pile never comes to rest: its
// fastest box still moves at 0.12 and 0.15 m/s after 10 s. Under the five-substep cap (48 and
// 36 Hz) the fastest moves at 0.00015 and 0.0014 m/s. Bound 2 cm/s: a sixth of the ringing, over
// ten times the slower settling.
TEST(NativeContactStiffness, PileDroppedAtFewSubstepsComesToRest) {
    for (const int substeps : {3, 4}) {
        const double fastest = fastestAfterDrop(substeps, 1, 10.0);
        std::cout << "[ MEASURED ] " << substeps << " substeps x 1 iteration: fastest box after 10 s " << fastest
                  << " m/s\n";
        EXPECT_LT(fastest, 0.02) << substeps << " substeps";
    }
}

}  // namespace
}  // namespace anyphys
