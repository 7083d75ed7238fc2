// Free flight at any speed: a body with no force on it keeps its velocity exactly (Newton's first
// law holds bit for bit in semi-implicit Euler), however fast. Engines that cap speed to protect
// their solver must say so.
#include <cmath>

#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

class FreeFlightTest : public ContractTest {
protected:
    void fastBodyKeepsItsSpeed(const std::string& criterion) {
        WorldSettings s = settings();
        s.gravity = Vec3::Zero();
        World world(s);
        // 300 m/s: a rifle bullet; 5 m per step at 60 Hz.
        BodyDef def = ballDef("bullet", 0.05, Vec3::Zero());
        def.linearVelocity = Vec3(300, 0, 0);
        def.allowSleep = false;
        Body b = world.createBody(def);
        while (world.time() < 1.0) world.step();
        const double speed = b.linearVelocity().norm(), x = b.position().x();
        report(backend() + " 300 m/s body after 1 s: speed", speed, "m/s");
        // Constant velocity integrates exactly: only rounding, relative 1e-12.
        const bool kept = std::abs(speed - 300.0) <= 300.0 * 1e-12 && std::abs(x - 300.0 * world.time()) <= 1e-9 * x;
        expectCriterion(criterion, kept,
                        "speed " + std::to_string(speed) + " m/s (exact 300), x " + std::to_string(x) + " m (exact " +
                            std::to_string(300.0 * world.time()) + ")",
                        std::abs(speed - 300.0));
    }
};

TEST_P(FreeFlightTest, FastBodyKeepsItsSpeed) { fastBodyKeepsItsSpeed("free_flight.fast_body_speed"); }

ANYPHYS_CONTRACT_SUITE(FreeFlightTest);

class PlanarFreeFlightTest : public FreeFlightTest {
protected:
    bool planarTest() const override { return true; }
};

TEST_P(PlanarFreeFlightTest, FastBodyKeepsItsSpeed) { fastBodyKeepsItsSpeed("planar.free_flight.fast_body_speed"); }

ANYPHYS_CONTRACT_SUITE(PlanarFreeFlightTest);

}  // namespace
}  // namespace anyphys::test
