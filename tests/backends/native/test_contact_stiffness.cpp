// Native contact stiffness: the soft step caps contactHertz so that every period of the contact
// spring spans at least five substeps (StepSolver::solve). Stiffer than that, Gauss-Seidel at one
// iteration per substep does not settle a pile: it rings for ever.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"

namespace anyphys {
namespace {

using test::backendSettings;
using test::boxDef;

// A static box of half extents `half` whose top face is the plane y = 0.
void addStaticGround(World& world, const Vec3& half) {
    BodyDef ground = boxDef("ground", half, {0, -half.y(), 0});
    ground.type = BodyType::Static;
    world.createBody(ground);
}

// Fastest box after dropping a 3 x 3 x 10 grid of unit cubes (0.1 m gaps) on a box ground and
// stepping it `seconds` at 60 Hz, sleeping off, with the default contactHertz (60).
double fastestAfterDrop(int substeps, int iterations, double seconds) {
    WorldSettings settings = backendSettings("native");
    settings.substeps = substeps;
    settings.iterations = iterations;
    World world(settings);
    addStaticGround(world, {20, 1, 20});
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

// Largest sideways move of any box of a ten-box stack of cubes of edge `size` on a box ground,
// over 10 s at 60 Hz, sleeping off, at `hertz` (3D, or in a planar world).
double smallStackDrift(double size, double hertz, bool planar = false) {
    WorldSettings settings = backendSettings("native");
    settings.contactHertz = hertz;
    settings.planar = planar;
    World world(settings);
    addStaticGround(world, {1, 0.5, 1});
    std::vector<Body> boxes;
    for (int i = 0; i < 10; ++i) {
        BodyDef box = boxDef("box", Vec3::Constant(size / 2), {0, size / 2 + i * size, 0});
        box.allowSleep = false;
        boxes.push_back(world.createBody(box));
    }
    double drift = 0.0;
    while (world.time() < 10.0) {
        world.step();
        for (const Body& b : boxes) drift = std::max(drift, std::hypot(b.position().x(), b.position().z()));
    }
    return drift;
}

// A contact's spring is written for its pair's mass, so a column's lower contacts, which carry the
// boxes above, sagged and yielded N times as far as the top one, and ten small cubes tipped over at
// the default 60 Hz: 179, 350 and 19.0 mm for 2, 4 and 8 cm cubes (3D; 32 cm: 16.8); 60.8 mm for
// 8 cm cubes in a planar world (32 cm: 22.9). Contacts that carry more than their pair's weight now
// stiffen, up to the cap (contactSoftness): 2.0, 2.8, 2.8 and 2.8 mm; 4.9 and 4.9 mm. Bound: an eighth
// of the edge; a fallen stack moves its boxes by many edges. What is left is a sway of a few
// millimetres at the start, before the contacts carry their load, whatever the size: planar 4 cm
// cubes sway 5.1 mm, just over their eighth (349 mm before), and planar 2 cm cubes still fall
// (202 mm; 177 before) at the default 8 substeps, whose cap (96 Hz) is too soft for them, as for
// 2 cm cubes twenty high in 3D. Both are printed as known.
TEST(NativeContactStiffness, SmallBoxStacksStandAtTheDefaultStiffness) {
    const struct {
        double size;
        bool planar;
    } stacks[] = {{0.02, false}, {0.04, false}, {0.08, false}, {0.32, false}, {0.08, true}, {0.32, true}};
    for (const auto& stack : stacks) {
        const double drift = smallStackDrift(stack.size, 60.0, stack.planar);
        std::cout << "[ MEASURED ] ten " << stack.size * 100 << " cm cubes" << (stack.planar ? ", planar" : "")
                  << ": largest sideways move " << drift * 1e3 << " mm\n";
        EXPECT_LT(drift, stack.size / 8) << stack.size << " m cubes" << (stack.planar ? ", planar" : "");
    }
    for (const double size : {0.02, 0.04})
        std::cout << "[ KNOWN    ] ten " << size * 100 << " cm cubes, planar, beyond an eighth of the edge: largest sideways move "
                  << smallStackDrift(size, 60.0, true) * 1e3 << " mm\n";
}

// What the scene format's contactHertz row tells users: stiffer contacts all over (90 Hz) hold ten
// 2 and 4 cm cubes in 3D as well. Bound: as above.
TEST(NativeContactStiffness, SmallBoxStackStandsWithStifferContacts) {
    for (const double size : {0.02, 0.04}) {
        const double drift = smallStackDrift(size, 90.0);
        std::cout << "[ MEASURED ] ten " << size * 100 << " cm cubes at 90 Hz: largest sideways move " << drift * 1e3 << " mm\n";
        EXPECT_LT(drift, size / 8) << size << " m cubes";
    }
}

// Joints keep their own stiffness (kJointHertz): contacts made stiffer for small bodies would
// otherwise stiffen every joint with them, past what the substeps resolve (a ragdoll pile's joints
// opened to 12 cm at 90 Hz). A pendulum on each joint type, no contacts: the same bits at any
// contactHertz.
TEST(NativeContactStiffness, JointsDoNotFollowTheContactStiffness) {
    const auto swing = [](JointType type, double hertz) {
        WorldSettings settings = backendSettings("native");
        settings.contactHertz = hertz;
        World world(settings);
        BodyDef bob = boxDef("bob", Vec3::Constant(0.1), {1, 0, 0});
        bob.allowSleep = false;
        JointDef d;
        d.type = type;
        d.bodyB = world.createBody(bob);
        if (type == JointType::Distance) d.anchorB = Vec3(1, 0, 0);
        if (type == JointType::Hinge) d.limits = JointLimits{-0.5, 0.5};  // and its limit
        world.createJoint(d);
        for (int i = 0; i < 120; ++i) world.step();
        return d.bodyB.state();
    };
    for (const JointType type : {JointType::Hinge, JointType::Ball, JointType::Distance}) {
        const BodyState at60 = swing(type, 60.0);
        for (const double hertz : {30.0, 90.0}) {
            const BodyState other = swing(type, hertz);
            EXPECT_EQ(other.position, at60.position) << toString(type) << " at " << hertz << " Hz";
            EXPECT_EQ(other.linearVelocity, at60.linearVelocity) << toString(type) << " at " << hertz << " Hz";
        }
    }
}

}  // namespace
}  // namespace anyphys
