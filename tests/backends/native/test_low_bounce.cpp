// Native restitution on a low bounce, one whose rise stays within the contact's speculative
// margin: the contact keeps it, so the solver's substeps carry its whole flight, and its rebound
// speed must be stored with their half-substep lag, not the integrator's half step (with the latter
// a ball landing at 3.1 m/s with e = 0.2 rose 2.47 cm instead of 2.0 at 60 Hz). And a ball that
// meets the ground just after a step's end, bounced a step early from the gap, must rise no higher.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "anyphys/anyphys.hpp"
#include "contact_helpers.hpp"

namespace anyphys {
namespace {

using test::backendSettings;

// Rise of a 0.25 m ball dropped from `drop` (bottom above the ground) with restitution e: its
// first rebound's highest step-end position above its resting height.
double lowBounceRise(const WorldSettings& base, double e, double drop, double slide = 0.0, double friction = 0.6) {
    constexpr double kRadius = 0.25;
    WorldSettings settings = base;
    settings.restitutionThreshold = 0.1;  // the slowest impact here is 3.1 m/s: every one bounces
    MaterialLibrary materials;
    materials.add("ball", Material{friction, e, 1000.0});
    World world(settings, materials);
    world.createBody(test::groundDef());
    BodyDef def = test::ballDef("ball", kRadius, Vec3(0, kRadius + drop, 0), "ball");
    def.allowSleep = false;
    def.linearVelocity = Vec3(slide, 0, 0);
    Body ball = world.createBody(def);
    const double apex = test::firstReboundApex(world, ball, 3.0);
    return apex - kRadius;
}

// Drops of 0.5, 0.522 and 1 m (impacts at 3.1, 3.2 and 4.4 m/s) with e = 0.1 and 0.2 where the
// rise e^2 drop is at most 2 cm, the speculative distance, in 3D and planar worlds and with both
// solvers. At 3.2 m/s the ball meets the ground just after the step's end, and the soft step's
// last relax bounces it from 5.4 mm up (bounceVelocity). Bound 3 % of the rise plus g dt^2 / 8
// (0.17 mm): the substeps (1/480 s) leave the rebound speed off by g h_sub / 2, 0.33 % of the
// slowest rebound's square when doubled, the impact time is found within the step to the same
// order, and the apex is sampled at step ends, up to g dt^2 / 8 below the true one. The
// integrator's half step gave +24 % to +48 %, the bounce from 5.4 mm up +102 %.
TEST(NativeLowBounce, RisesToRestitutionSquaredOfTheDrop) {
    for (const bool planar : {false, true}) {
        for (const Solver solver : {Solver::SoftStep, Solver::ProjectedGaussSeidel}) {
            WorldSettings settings = backendSettings("native");
            settings.solver = solver;
            settings.planar = planar;
            const std::string variant = std::string(planar ? "planar " : "") + (solver == Solver::SoftStep ? "soft_step" : "pgs");
            for (const double e : {0.1, 0.2}) {
                for (const double drop : {0.5, 0.522, 1.0}) {
                    if (e * e * drop > 0.03) continue;  // a 4 cm rise leaves the contact: free flight
                    const double expected = e * e * drop, dt = settings.timeStep;
                    const double rise = lowBounceRise(settings, e, drop);
                    std::cout << "[ MEASURED ] " << variant << " e " << e << " drop " << drop << " m: rise " << rise
                              << " m for " << expected << "\n";
                    EXPECT_NEAR(rise, expected, 0.03 * expected + 9.81 * dt * dt / 8)
                        << variant << ", e " << e << ", drop " << drop << " m";
                }
            }
        }
    }
}

// A ball sliding along the ground as it bounces (frictionless, so it keeps its slide) stays in the
// narrow phase's reach for longer: ContactManager keeps points within the speculative distance
// plus a step at the pair's whole speed, and the solver's substeps carry the body while it is in
// reach. Counting only the rise in that reach, a ball sliding at 6 m/s rose up to 10 % high
// (e = 0.5, impacts 2.5 to 4 m/s). Same bound as above.
TEST(NativeLowBounce, SlidingBallRisesToRestitutionSquaredOfTheDrop) {
    for (const bool planar : {false, true}) {
        WorldSettings settings = backendSettings("native");
        settings.planar = planar;
        const double dt = settings.timeStep;
        for (const double slide : {0.0, 3.0, 6.0}) {
            for (const double impact : {2.5, 3.1, 4.0}) {
                const double drop = impact * impact / (2 * 9.81), e = 0.5, expected = e * e * drop;
                const double rise = lowBounceRise(settings, e, drop, slide, 0.0);
                std::cout << "[ MEASURED ] " << (planar ? "planar " : "") << "slide " << slide << " m/s, impact " << impact
                          << " m/s: rise " << rise << " m for " << expected << "\n";
                EXPECT_NEAR(rise, expected, 0.03 * expected + 9.81 * dt * dt / 8)
                    << (planar ? "planar, " : "") << "slide " << slide << " m/s, impact " << impact << " m/s";
            }
        }
    }
}

}  // namespace
}  // namespace anyphys
