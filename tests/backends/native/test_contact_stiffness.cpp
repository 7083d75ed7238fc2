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
// over 10 s at 60 Hz, sleeping off, at `hertz`.
double smallStackDrift(double size, double hertz) {
    WorldSettings settings = backendSettings("native");
    settings.contactHertz = hertz;
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

// What the scene format's contactHertz row tells users: small boxes need stiffer contacts, and 90
// Hz at the default substeps holds a ten-box stack of 2 and 4 cm cubes (at 60 Hz it falls). Bound:
// an eighth of the edge; a fallen stack moves its boxes by many edges.
TEST(NativeContactStiffness, SmallBoxStackStandsWithStifferContacts) {
    for (const double size : {0.02, 0.04}) {
        const double drift = smallStackDrift(size, 90.0);
        std::cout << "[ MEASURED ] ten " << size * 100 << " cm cubes at 90 Hz: largest sideways move " << drift * 1e3
                  << " mm; at 60 Hz " << smallStackDrift(size, 60.0) * 1e3 << " mm\n";
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
