// A steady native step allocates nothing: every per-step array is reused, so a running game
// never waits on the heap. Counted with a replaced global operator new that counts only while
// a step runs (on any thread: workers count too).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>

#include "anyphys/anyphys.hpp"

// The replacements pair malloc with free on purpose; GCC cannot see that when it inlines them
// into a new-expression and warns of a mismatch (an error under the sanitizer build's -Werror).
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
    if (counting) ++allocations;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t size, std::align_val_t align) {
    if (counting) ++allocations;
    const std::size_t a = static_cast<std::size_t>(align);
    if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace anyphys {
namespace {

// Columns that settle and then stay put: boxes three high and hulls on a ground box, spheres
// and lying capsules on a plane, boxes on a static triangle mesh. Every pair routine the
// steady step runs is on the path: box-box, box-plane, hull-box, sphere-plane, capsule-plane,
// box-mesh.
void buildPile(World& world) {
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::box({6, 1, 6});
    ground.position = {0, -1, 0};
    world.createBody(ground);
    BodyDef plane;
    plane.type = BodyType::Static;
    plane.shape = ShapeDef::plane({0, 1, 0}, 0.0);
    world.createBody(plane);
    BodyDef slab;  // a mesh floor beside the box, level with it
    slab.type = BodyType::Static;
    slab.shape = ShapeDef::mesh({{8, 0, -4}, {16, 0, -4}, {16, 0, 4}, {8, 0, 4}}, {0, 2, 1, 0, 3, 2});
    world.createBody(slab);
    const ShapeDef prism = ShapeDef::convex({{-0.4, 0, -0.4}, {0.4, 0, -0.4}, {0, 0, 0.4}, {-0.4, 0.6, -0.4}, {0.4, 0.6, -0.4}, {0, 0.6, 0.4}});
    for (int i = 0; i < 25; ++i) {
        const double x = (i % 5) * 2.0 - 4.0, z = (i / 5) * 2.0 - 4.0;
        BodyDef d;
        if (i % 2 == 0) {
            d.shape = ShapeDef::box({0.4, 0.4, 0.4});
            for (int level = 0; level < 3; ++level) {
                d.position = {x, 0.4 + 0.8 * level, z};
                world.createBody(d);
                d.position.x() += 10.0;  // the same column on the mesh floor (up to x = 16)
                if (d.position.x() < 15.5) world.createBody(d);
            }
        } else {
            d.shape = prism;
            d.position = {x, 0.0, z};
            world.createBody(d);
        }
        BodyDef round;  // on the plane, off the ground box
        round.shape = i % 2 == 0 ? ShapeDef::sphere(0.3) : ShapeDef::capsule(0.25, 0.4);
        round.orientation = Quat(Eigen::AngleAxisd(i % 2 == 0 ? 0.0 : 1.5707963267948966, Vec3::UnitZ()));
        round.position = {x, 0.3, z - 12.0};
        world.createBody(round);
    }
    // A chain hanging at rest beside the pile (hinge, ball, slider with a spring): the joint
    // stages run every step too.
    BodyDef link;
    link.shape = ShapeDef::sphere(0.1);
    Body previous;
    const JointType types[] = {JointType::Hinge, JointType::Ball, JointType::Slider};
    for (int i = 0; i < 3; ++i) {
        link.position = {20, 5.0 - 0.5 * (i + 1), 0};
        Body body = world.createBody(link);
        JointDef j;
        j.type = types[i];
        j.bodyA = previous;
        j.bodyB = body;
        j.anchor = {20, 5.0 - 0.5 * i, 0};
        if (j.type == JointType::Slider) {
            j.axis = Vec3::UnitY();
            j.spring = JointSpring{100.0, 5.0};
        }
        world.createJoint(j);
        previous = body;
    }
}

// Steps `world` `steps` times and returns how many allocations the steps made.
long allocationsDuring(World& world, int steps) {
    allocations = 0;
    counting = true;
    for (int i = 0; i < steps; ++i) world.step();
    counting = false;
    return allocations;
}

// A pile of boxes and spheres, and a chain, with everything they use except events (the layer's).
std::unique_ptr<World> pileWorld(int workers, bool sleeping) {
    WorldSettings settings;
    settings.workers = workers;
    settings.effects = Effect::Gravity | Effect::Contacts | Effect::Friction | Effect::ContinuousCollision | Effect::Joints;
    if (sleeping) settings.effects->add(Effect::Sleeping);
    auto world = std::make_unique<World>(settings);
    buildPile(*world);
    return world;
}

TEST(NativeAllocations, SteadyStepAllocatesNothing) {
    {
        auto world = pileWorld(1, false);
        allocationsDuring(*world, 240);  // settle: contacts and arrays reach their steady sizes
        EXPECT_EQ(allocationsDuring(*world, 60), 0) << "1 worker";
    }
    // With two workers, ranges go to whichever thread is free, and the collision routines'
    // per-thread scratch (grow-only, collision/scratch.hpp) grows the first time a thread meets a
    // shape pair, which a loaded machine may delay past any settling time. That growth happens
    // a bounded number of times; an allocation every step would show in every window. So: one of
    // five 60-step windows after settling must allocate nothing.
    auto world = pileWorld(2, false);
    allocationsDuring(*world, 240);
    long windows[5] = {};
    bool quiet = false;
    for (long& allocated : windows) {
        allocated = allocationsDuring(*world, 60);
        if (allocated == 0) {
            quiet = true;
            break;
        }
    }
    EXPECT_TRUE(quiet) << "2 workers: every 60-step window allocated (first " << windows[0] << ", last " << windows[4] << ")";
}

TEST(NativeAllocations, SleepingPileAllocatesNothing) {
    auto world = pileWorld(1, true);
    allocationsDuring(*world, 300);
    EXPECT_EQ(allocationsDuring(*world, 60), 0);
}

}  // namespace
}  // namespace anyphys
