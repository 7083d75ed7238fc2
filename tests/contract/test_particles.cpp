// Fluids and cloths (the particle stage above the backends) against closed forms and conservation
// laws, on every backend. The fluid cases run in planar worlds, which every backend offers, so each
// one runs everywhere at a few hundred particles; the cloth cases need a sheet's third dimension
// and run on the 3D backends, with a planar membrane case for every backend.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "contract_fixture.hpp"
#include "contact_helpers.hpp"

namespace anyphys::test {
namespace {

// A static box from its lower and upper corner.
Body staticBox(World& world, const Vec3& lo, const Vec3& hi, const std::string& name = "") {
    BodyDef def;
    def.type = BodyType::Static;
    def.name = name;
    def.shape = ShapeDef::box(0.5 * (hi - lo));
    def.position = 0.5 * (lo + hi);
    return world.createBody(def);
}

// An open tank of inner width [0, width] along X, floor at y = 0, walls 0.1 m thick and 2 m high
// (planar: the walls' depth along Z is the slab's, their extent does not matter).
struct Tank {
    Body floor, left, right;
};
Tank makeTank(World& world, double width) {
    return {staticBox(world, Vec3(-0.2, -0.1, -0.5), Vec3(width + 0.2, 0.0, 0.5), "floor"),
            staticBox(world, Vec3(-0.1, 0.0, -0.5), Vec3(0.0, 2.0, 0.5), "left"),
            staticBox(world, Vec3(width, 0.0, -0.5), Vec3(width + 0.1, 2.0, 0.5), "right")};
}

FluidDef water(const Vec3& lo, const Vec3& hi, double spacing) {
    FluidDef f;
    f.name = "water";
    f.boxMin = lo;
    f.boxMax = hi;
    f.spacing = spacing;
    f.density = 1000.0;
    f.viscosity = 0.001;
    return f;
}

const std::vector<Vec3>& particlesOf(const World& world, std::size_t k = 0) { return *world.particleSystems().at(k).positions; }

// A static triangle mesh: a grid of cells x cells quads over [lo, hi] in X and Z at height y(x)
// (a flat floor, a ramp, a valley), each quad split along alternating diagonals so the particles
// cross shared edges both ways. Counter-clockwise seen from above.
template <class Height>
Body meshGround(World& world, double lo, double hi, int cells, Height y, const std::string& name = "mesh") {
    std::vector<Vec3> v;
    std::vector<std::uint32_t> idx;
    const double d = (hi - lo) / cells;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) v.emplace_back(lo + i * d, y(lo + i * d), lo + j * d);
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), e = at(i, j + 1);
            if ((i + j) % 2 == 0) idx.insert(idx.end(), {a, c, b, a, e, c});
            else idx.insert(idx.end(), {a, e, b, b, e, c});
        }
    BodyDef def;
    def.type = BodyType::Static;
    def.name = name;
    def.shape = ShapeDef::mesh(std::move(v), std::move(idx));
    return world.createBody(def);
}

// Particles on a static mesh move the same on every engine (the fields stage is the layer's; no
// body moves): native, ode and bullet print the same digits. Under the sanitizers these long runs
// (12 to 15 s each there) go on the first built backend with meshes only, so the layer's code is
// checked once; the release run keeps every backend.
#ifdef ANYPHYS_SANITIZED
std::string firstMeshBackend() {
    for (const BackendInfo& info : availableBackends())
        if (info.capabilities.shapes.contains(ShapeType::Mesh)) return info.name;
    return {};
}
#define ANYPHYS_MESH_PARTICLES_ONCE()                                                              \
    if (backend() != firstMeshBackend())                                                          \
    GTEST_SKIP() << "particles on a static mesh: engine-independent, run on " << firstMeshBackend() \
                 << " only under the sanitizers (every backend in the release run)"
// The floating box: its particles and their push on the box are the layer's code, and an engine's
// part (a box moved by an applied force) runs instrumented in many lighter cases. Under the
// sanitizers its 6 s of fluid (22 to 31 s per backend there, 110 s in all) go on the first built
// backend only; the release run keeps every backend.
#define ANYPHYS_FLOATING_BOX_ONCE()                                                                        \
    if (backend() != availableBackends().front().name)                                                    \
    GTEST_SKIP() << "floating box: run on " << availableBackends().front().name                           \
                 << " only under the sanitizers, its fluid being the layer's (every backend in the release run)"
#else
#define ANYPHYS_MESH_PARTICLES_ONCE() static_cast<void>(0)
#define ANYPHYS_FLOATING_BOX_ONCE() static_cast<void>(0)
#endif

// ---- fluids (planar: every backend) ---------------------------------------------------------

class PlanarFluidTest : public ContractTest {
protected:
    bool planarTest() const override { return true; }
};

// A settled column of depth H in a tank of width W (slab depth D): the water pushes a side wall
// with the hydrostatic force integral of rho g (H - y) over the wall, rho g H^2 D / 2, and the floor
// with rho g H W D (its weight). The wall force tests the pressure's distribution, not only the
// weight: a heap of sand on the same floor would push the wall far less.
TEST_P(PlanarFluidTest, HydrostaticPressureInASettledColumn) {
    World world(settings());
    const double width = 0.4, depth = 0.3, spacing = 0.025, slab = 0.2;
    const Tank tank = makeTank(world, width);
    world.addFluid(water(Vec3(0, 0, -0.5 * slab), Vec3(width, depth, 0.5 * slab), spacing));
    for (int i = 0; i < 90; ++i) world.step();  // 1.5 s: the start's small compression wave has died
    Vec3 wall = Vec3::Zero(), floor = Vec3::Zero();
    const int samples = 30;
    for (int i = 0; i < samples; ++i) {
        world.step();
        wall += world.particleForce(tank.right) / samples;
        floor += world.particleForce(tank.floor) / samples;
    }
    const double mass = 1000.0 * width * depth * slab;
    const double wallForce = 0.5 * 1000.0 * kG * depth * depth * slab;
    // The settled height from the particles: the mean top of the columns' highest particles.
    const auto& p = particlesOf(world);
    const double top = std::accumulate(p.begin(), p.end(), 0.0, [](double m, const Vec3& x) { return std::max(m, x.y()); }) +
                       0.5 * spacing;
    std::cout << "  " << backend() << ": floor " << floor.y() << " N (weight " << mass * kG << "), wall " << wall.x()
              << " N (rho g H^2 D / 2 = " << wallForce << "), relative error " << (wall.x() - wallForce) / wallForce
              << ", height " << top << " m (" << depth << ")\n";
    // The floor carries the weight: momentum balance of a fluid at rest, up to the last ripples (1 %).
    EXPECT_NEAR(-floor.y(), mass * kG, 0.01 * mass * kG);  // the water pushes the floor down
    // The wall: pressure rho g h over the wall. Tolerance 10 %: the particles nearest the wall sit
    // half a spacing from it and the free surface is resolved to a spacing, so the pressure's
    // integral is known to about s / H = 8 % at 12 particles of depth; the one-sided density
    // constraint leaves the column within 2 % of its rest height (checked below).
    EXPECT_NEAR(wall.x(), wallForce, 0.10 * wallForce);
    EXPECT_NEAR(top, depth, 0.02 * depth + 0.5 * spacing);
}

// A box of half the water's density floats with half its height under the surface (Archimedes),
// the fluid two-way coupled: the particles carry the box (its weight is what they push up with).
TEST_P(PlanarFluidTest, BoxFloatsAtItsArchimedesDraft) {
    ANYPHYS_FLOATING_BOX_ONCE();
    World world(settings());
    const double width = 1.0, depth = 0.3, spacing = 0.025, slab = 0.2;
    makeTank(world, width);
    world.addFluid(water(Vec3(0, 0, -0.5 * slab), Vec3(width, depth, 0.5 * slab), spacing));
    BodyDef def;
    def.name = "box";
    def.shape = ShapeDef::box(Vec3(0.15, 0.1, 0.5 * slab));  // as deep as the slab
    def.density = 500.0;
    def.position = Vec3(0.5 * width, depth + 0.1 + 0.5 * spacing, 0);
    def.allowSleep = false;
    Body box = world.createBody(def);
    for (int i = 0; i < 240; ++i) world.step();  // 4 s: the bobbing decays
    // Over the next 2 s: the draft from the water's surface away from the box (the mean of the
    // columns' top particles, spacing wide, farther than 0.3 m from the box: ripples average out)
    // down to the box's bottom, and the lift the particles give it.
    double draft = 0.0, lift = 0.0;
    const int samples = 120;
    for (int i = 0; i < samples; ++i) {
        world.step();
        std::vector<double> tops(static_cast<std::size_t>(width / spacing) + 1, -1.0);
        for (const Vec3& x : particlesOf(world))
            if (std::abs(x.x() - box.position().x()) > 0.3) {
                const auto k = static_cast<std::size_t>(std::clamp(x.x() / spacing, 0.0, double(tops.size() - 1)));
                tops[k] = std::max(tops[k], x.y());
            }
        double surface = 0.0;
        int columns = 0;
        for (double t : tops)
            if (t >= 0.0) {
                surface += t;
                ++columns;
            }
        surface = surface / columns + 0.5 * spacing;
        draft += (surface - (box.position().y() - 0.1)) / samples;
        lift += world.particleForce(box).y() / samples;
    }
    const double expected = 0.5 * 0.2;
    const double weight = box.massProperties().mass * kG;
    std::cout << "  " << backend() << ": draft " << draft << " m, Archimedes " << expected << " m, error "
              << draft - expected << " m; lift " << lift << " N, weight " << weight << " N\n";
    // Tolerance: half a spacing (12.5 mm), to which the surface is known from the top particles'
    // centres plus their radius, plus the 3 % the column is compressed under the one-sided density
    // constraint at 4 iterations (9 mm of its 0.3 m: the water stands lower than its volume says).
    // Measured: 8 to 13 mm shallow.
    EXPECT_NEAR(draft, expected, 0.5 * spacing + 0.03 * depth);
    // Over 2 s at rest, the particles hold the box up with its weight (2 %: residual bobbing).
    EXPECT_NEAR(lift, weight, 0.02 * weight);
}

// Martin and Moyce (1952), Part IV, the column of width a and height 2 a (n^2 = 2) collapsing on a
// dry floor: the front's distance Z = z / a from the back wall against T = t sqrt(2 g / a). The
// experimental points used (read from their figure as reproduced in the SPH/MPS literature, e.g.
// Koshizuka and Oka 1996, Nucl. Sci. Eng. 123):
//   T 1.43 -> Z 1.67, T 1.83 -> Z 2.11, T 2.20 -> Z 2.56, T 2.51 -> Z 3.00.
// Simulations of an instantaneous release run ahead of these by about 0.2 to 0.4 in T (the
// experiment's gate took time to open), so the test asks the front to lie between the measured
// curve and a lead of 0.5 in T, at a coarse 10 x 20 particles.
TEST_P(PlanarFluidTest, DamBreakFrontFollowsMartinAndMoyce) {
    World world(settings());
    const double a = 0.1, spacing = a / 10, slab = 0.1;
    makeTank(world, 6 * a);
    world.addFluid(water(Vec3(0, 0, -0.5 * slab), Vec3(a, 2 * a, 0.5 * slab), spacing));
    struct Point {
        double T, Z;
    };
    const Point measured[] = {{1.43, 1.67}, {1.83, 2.11}, {2.20, 2.56}, {2.51, 3.00}};
    const double toT = std::sqrt(2 * kG / a);
    // The front: the farthest particle's reach (its centre plus its radius).
    const auto front = [&] {
        double z = 0.0;
        for (const Vec3& x : particlesOf(world)) z = std::max(z, x.x());
        return (z + 0.5 * spacing) / a;
    };
    std::vector<std::pair<double, double>> run;  // (T, Z) after each step
    while (world.time() * toT < 2.6) {
        world.step(1.0 / 240);  // the front moves 0.1 a per 1/60 s step: finer steps resolve it in T
        run.emplace_back(world.time() * toT, front());
    }
    const auto zAt = [&](double T) {
        for (std::size_t i = 1; i < run.size(); ++i)
            if (run[i].first >= T) {
                const double w = (T - run[i - 1].first) / (run[i].first - run[i - 1].first);
                return run[i - 1].second + w * (run[i].second - run[i - 1].second);
            }
        return run.back().second;
    };
    for (const Point& m : measured) {
        const double z = zAt(m.T);
        std::cout << "  " << backend() << ": T " << m.T << ": front Z " << z << ", measured " << m.Z << "\n";
        // Never behind the experiment (a front slower than a real one released with a lag is
        // wrong), and ahead of it by at most the gate's lag, 0.5 in T: Z(T) <= Z_measured(T + 0.5),
        // with dZ/dT ~ 1.2 there, i.e. Z within [Z_m, Z_m + 0.6].
        EXPECT_GE(z, m.Z - 0.05);
        EXPECT_LE(z, m.Z + 0.6);
    }
}

// Two-way coupling conserves momentum: a free box thrown at a resting block of fluid in zero
// gravity gives it momentum; particles plus box keep the initial momentum.
TEST_P(PlanarFluidTest, CouplingConservesMomentum) {
    WorldSettings s = settings();
    s.gravity = Vec3::Zero();
    World world(s);
    BodyDef def;
    def.shape = ShapeDef::box(Vec3(0.1, 0.2, 0.1));
    def.density = 500.0;
    def.position = Vec3(0.45, 0.1, 0);
    def.allowSleep = false;
    Body box = world.createBody(def);
    FluidDef f = water(Vec3(0, 0, -0.05), Vec3(0.2, 0.2, 0.05), 0.025);
    world.addFluid(f);
    const double m = f.density * f.spacing * f.spacing * 0.1;  // per particle: the slab's share
    const auto momentum = [&] {
        Vec3 total = box.massProperties().mass * box.linearVelocity();
        for (const Vec3& v : *world.particleSystems()[0].velocities) total += m * v;
        return total;
    };
    box.setLinearVelocity(Vec3(-2.0, 0, 0));  // thrown at the resting fluid
    const Vec3 before = momentum();
    for (int i = 0; i < 60; ++i) world.step();
    const Vec3 after = momentum();
    std::cout << "  " << backend() << ": momentum before " << formatVec3(before) << ", after " << formatVec3(after)
              << ", box velocity " << formatVec3(box.linearVelocity()) << "\n";
    // The box gave momentum to the fluid (it slowed), and none was made or lost: the impulses are
    // equal and opposite. Tolerance: the engine's rounding of 60 impulses (float engines 6e-8 each).
    EXPECT_GT(box.linearVelocity().x(), -1.9);
    EXPECT_NEAR((after - before).norm(), 0.0, rounding(before.norm(), 600) + 1e-9);
}

// The effect is derived while a fluid is held, listed, and the world without one pays nothing:
// no particle stage, no effect.
TEST_P(PlanarFluidTest, EffectsFollowTheParticles) {
    World world(settings());
    BodyDef ball;
    ball.shape = ShapeDef::sphere(0.5);
    world.createBody(ball);
    EXPECT_FALSE(world.activeEffects().has(Effect::Fluid));
    EXPECT_FALSE(world.activeEffects().has(Effect::Cloth));
    world.addFluid(water(Vec3(0, 0, -0.05), Vec3(0.1, 0.1, 0.05), 0.05));
    EXPECT_TRUE(world.activeEffects().has(Effect::Fluid));
    EXPECT_EQ(world.fluids().size(), 1u);
    EXPECT_EQ(world.particleSystems().size(), 1u);
    EXPECT_EQ(world.particleSystems()[0].positions->size(), 4u);  // 2 x 2 in the plane
    world.clearParticles();
    EXPECT_FALSE(world.activeEffects().has(Effect::Fluid));
    EXPECT_TRUE(world.particleSystems().empty());
    // Bad input: named, and nothing added.
    FluidDef bad = water(Vec3(0, 0, 0), Vec3(1, 1, 1), 0.0);
    try {
        world.addFluid(bad);
        ADD_FAILURE() << "spacing 0 was accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "FluidDef.spacing: must be > 0, got 0");
    }
    EXPECT_TRUE(world.fluids().empty());
    WorldSettings declared = settings();
    declared.effects = Effects(Effect::Gravity);
    World strict(declared);
    EXPECT_THROW(strict.addFluid(water(Vec3(0, 0, -0.05), Vec3(0.1, 0.1, 0.05), 0.05)), Error);
    EXPECT_THROW(strict.addCloth(ClothDef{}), Error);
}

// A fluid block dropped on a static mesh floor (a grid of triangles; walls are boxes) settles on
// it as on a box floor: no particle ever ends a step closer to the mesh than its radius (less a
// rounding tolerance), the floor carries the weight and the column keeps its height.
TEST_P(PlanarFluidTest, SettlesOnAMeshFloor) {
    ANYPHYS_REQUIRE(caps().shapes.contains(ShapeType::Mesh), "shape mesh");
    ANYPHYS_MESH_PARTICLES_ONCE();
    World world(settings());
    const double width = 0.4, depth = 0.3, spacing = 0.025, slab = 0.2, radius = 0.5 * spacing;
    const Body floor = meshGround(world, -0.5, 0.9, 7, [](double) { return 0.0; });
    staticBox(world, Vec3(-0.1, 0.0, -0.5), Vec3(0.0, 2.0, 0.5));
    staticBox(world, Vec3(width, 0.0, -0.5), Vec3(width + 0.1, 2.0, 0.5));
    world.addFluid(water(Vec3(0, 0.1, -0.5 * slab), Vec3(width, 0.1 + depth, 0.5 * slab), spacing));
    double lowest = 1e9;
    const auto bottom = [&] {
        for (const Vec3& x : particlesOf(world)) lowest = std::min(lowest, x.y());
    };
    for (int i = 0; i < 120; ++i) {
        world.step();
        bottom();
    }
    Vec3 force = Vec3::Zero();
    const int samples = 30;
    for (int i = 0; i < samples; ++i) {
        world.step();
        bottom();
        force += world.particleForce(floor) / samples;
    }
    const auto& p = particlesOf(world);
    const double top = std::accumulate(p.begin(), p.end(), 0.0, [](double m, const Vec3& x) { return std::max(m, x.y()); }) +
                       radius;
    const double weight = 1000.0 * width * depth * slab * kG;
    std::cout << "  " << backend() << ": lowest particle centre " << lowest << " m (radius " << radius << ", difference " << lowest - radius << "), floor "
              << -force.y() << " N (weight " << weight << "), height " << top << " m (" << depth << ")\n";
    // The last thing each substep does to positions is the collision pass, which puts a particle
    // exactly at its radius on the side it came from: 1e-9 m is rounding.
    EXPECT_GT(lowest, radius - 1e-9);
    // As on a box floor (HydrostaticPressureInASettledColumn): the weight to 1 %, the height to
    // 2 % plus half a spacing (the free surface is resolved to a spacing).
    EXPECT_NEAR(-force.y(), weight, 0.01 * weight);
    EXPECT_NEAR(top, depth, 0.02 * depth + 0.5 * spacing);
}

// A small block dropped 12 m onto a mesh ramp (slope 0.3, a grid of triangles) hits it at 15 m/s:
// its particles move about three radii along the ramp's normal per substep, so only the path test
// keeps them from passing through the surface. Over the ramp no particle is ever found below it or
// closer than its radius (less a rounding tolerance); the water runs down and off its lower edge.
TEST_P(PlanarFluidTest, FastDropOnAMeshRampDoesNotTunnel) {
    ANYPHYS_REQUIRE(caps().shapes.contains(ShapeType::Mesh), "shape mesh");
    ANYPHYS_MESH_PARTICLES_ONCE();
    World world(settings());
    const double spacing = 0.01, radius = 0.5 * spacing, drop = 12.0, slope = 0.3, end = 4.0;
    meshGround(world, -end, end, 16, [&](double x) { return slope * x; });
    world.addFluid(water(Vec3(0.05, drop, -0.05), Vec3(0.15, drop + 0.1, 0.05), spacing));
    const double dt = settings().timeStep, cosine = 1.0 / std::sqrt(1.0 + slope * slope);
    double closest = 1e9, fastest = 0.0;
    std::size_t over = 0;
    for (int i = 0; i < 150; ++i) {
        world.step();
        const auto& x = particlesOf(world);
        const auto& v = *world.particleSystems()[0].velocities;
        for (std::size_t k = 0; k < x.size(); ++k) {
            // Only where the ramp is (two radii in from its ends: beyond an open edge a particle
            // rounds it and may pass below the ramp's plane, as it should).
            if (std::abs(x[k].x()) > end - 2.0 * radius) continue;
            closest = std::min(closest, (x[k].y() - slope * x[k].x()) * cosine);  // signed distance to the ramp
            fastest = std::max(fastest, v[k].norm());
            ++over;
        }
    }
    // The fall's speed at the ramp, along its normal (a vertical fall: the slope's cosine), over
    // the fluid's most substeps per step (16): the least a falling particle moves in one.
    const double impact = std::sqrt(2.0 * kG * (drop - slope * 0.15)) * cosine;
    const double perSubstep = impact * dt / 16.0;
    std::cout << "  " << backend() << ": impact " << impact << " m/s along the normal (" << perSubstep / radius
              << " radii per substep; fastest particle over the ramp " << fastest << " m/s), closest to the ramp "
              << closest << " m (radius " << radius << ", difference " << closest - radius << ") over " << over << " particle-steps\n";
    EXPECT_GT(perSubstep, 2.0 * radius);  // the case is the one it claims
    EXPECT_GT(fastest, impact);           // and the water did reach the ramp at that speed
    // As on the floor: the collision pass is the last move of a substep, so 1e-9 m is rounding.
    EXPECT_GT(closest, radius - 1e-9);
    EXPECT_GT(over, 100u * 100u);  // the water was over the ramp for a good part of the run
}

// The same fall into a mesh valley (two 45 degree slopes meeting in a fold): the water runs down
// one slope into the other, and the particles in the fold touch both faces at once. Over the
// valley none is ever closer to either slope than its radius (less a rounding tolerance). The
// splash climbs higher than the drop, as it does in a valley of two planes (a property of the
// fluid in a right-angled fold, not of the mesh: measured 2.6 m from a 1 m drop with planes).
TEST_P(PlanarFluidTest, FastDropIntoAMeshValleyDoesNotTunnel) {
    ANYPHYS_REQUIRE(caps().shapes.contains(ShapeType::Mesh), "shape mesh");
    ANYPHYS_MESH_PARTICLES_ONCE();
    World world(settings());
    const double spacing = 0.01, radius = 0.5 * spacing, drop = 12.0, end = 4.0;
    meshGround(world, -end, end, 16, [](double x) { return std::abs(x); });
    world.addFluid(water(Vec3(0.05, drop, -0.05), Vec3(0.15, drop + 0.1, 0.05), spacing));
    double closest = 1e9;
    std::size_t over = 0;
    for (int i = 0; i < 150; ++i) {
        world.step();
        for (const Vec3& x : particlesOf(world)) {
            if (std::abs(x.x()) > end - 2.0 * radius) continue;  // over the valley only, as on the ramp
            // Signed distance to the nearer slope (inside the valley, each slope's foot is on it).
            closest = std::min(closest, std::min(x.y() + x.x(), x.y() - x.x()) / std::sqrt(2.0));
            ++over;
        }
    }
    std::cout << "  " << backend() << ": closest to the valley " << closest << " m (radius " << radius << ", difference "
              << closest - radius << ") over " << over << " particle-steps\n";
    EXPECT_GT(closest, radius - 1e-9);  // the collision pass is the last move of a substep
    EXPECT_GT(over, 100u * 100u);
}

ANYPHYS_CONTRACT_SUITE(PlanarFluidTest);

// ---- cloths ---------------------------------------------------------------------------------

// The largest relative stretch of the structural links (along U and V) of a cloth.
double maxStretch(const World& world, const ClothDef& def) {
    const auto& x = *world.particleSystems().back().positions;
    const int nu = def.resolution[0], nv = def.resolution[1];
    const double du = def.size[0] / nu, dv = def.size[1] / nv;
    const auto at = [&](int i, int j) { return x[static_cast<std::size_t>(j) * (nu + 1) + i]; };
    double worst = 0.0;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            if (i < nu) worst = std::max(worst, (at(i + 1, j) - at(i, j)).norm() / du - 1.0);
            if (j < nv) worst = std::max(worst, (at(i, j + 1) - at(i, j)).norm() / dv - 1.0);
        }
    return worst;
}

// Kinetic plus gravitational energy of a cloth's nodes (J), gravity along -Y, each node carrying a
// quarter of the cells around it (pinned nodes included: they do not move). The elastic energy,
// zero at the start (rest lengths are the start's), is >= 0, so this never exceeding its start is
// implied by the total not growing.
double clothEnergy(const World& world, const ClothDef& def) {
    const ParticleSystemView v = world.particleSystems().back();
    const int nu = def.resolution[0], nv = def.resolution[1];
    const double quarter = 0.25 * def.areaDensity * def.size[0] / nu * def.size[1] / nv;
    double e = 0.0;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const double cells = ((i > 0) + (i < nu)) * ((j > 0) + (j < nv));
            const std::size_t k = static_cast<std::size_t>(j) * (nu + 1) + i;
            e += cells * quarter * (0.5 * (*v.velocities)[k].squaredNorm() + kG * (*v.positions)[k].y());
        }
    return e;
}

ClothDef sheet(const Vec3& corner, const Vec3& u, const Vec3& v, double size, int resolution) {
    ClothDef c;
    c.name = "sheet";
    c.corner = corner;
    c.axisU = u;
    c.axisV = v;
    c.size = {size, size};
    c.resolution = {resolution, resolution};
    c.areaDensity = 0.2;
    c.stiffness = 1e4;
    c.damping = 0.1;
    return c;
}

class ClothTest : public ContractTest {};

// A 1 m sheet (0.2 kg/m^2, stiffness 1e4 N/m) pinned at two adjacent corners of its horizontal
// start falls, swings and hangs. Its weight, 1.96 N, hangs from two nodes: the links at the pins
// carry about 1 N over a link stiffness of 1e4 N/m, a strain of 1e-3 at the exact solution.
TEST_P(ClothTest, HangsFromTwoCornersWithinAStretchBound) {
    World world(settings());
    ClothDef c = sheet(Vec3(0, 1.5, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), 1.0, 10);
    c.damping = 2.0;  // settles within the run
    c.pinned = {{0, 0}, {10, 0}};
    world.addCloth(c);
    double worst = 0.0;
    for (int i = 0; i < 240; ++i) {
        world.step();
        worst = std::max(worst, maxStretch(world, c));
    }
    const double hanging = maxStretch(world, c);
    const auto& x = *world.particleSystems()[0].positions;
    std::cout << "  " << backend() << ": stretch hanging " << hanging << ", worst while falling " << worst
              << ", lowest node y " << std::min_element(x.begin(), x.end(), [](auto& a, auto& b) { return a.y() < b.y(); })->y()
              << "\n";
    // Bounds: XPBD with 8 substeps x 4 iterations does not converge a 10 x 10 sheet to the exact
    // 1e-3: measured 0.56 % hanging and 1.4 % at worst while it swings. 1.5 % and 3 % are what a
    // game can show without visible rubber, with room for the order of a different sheet.
    EXPECT_LT(hanging, 0.015);
    EXPECT_LT(worst, 0.03);
    // It hangs: the free edge has fallen below the pins by most of the sheet's length.
    EXPECT_LT(x[c.resolution[1] * 11 + 5].y(), 1.5 - 0.8);
}

// A free sheet dropped on a static sphere drapes over it: its nodes never come closer to the
// centre than the radius (the thickness is the margin), and its edges fall below the sphere's top.
TEST_P(ClothTest, DrapesOverASphereWithoutPassingThrough) {
    World world(settings());
    const double r = 0.3;
    BodyDef ball;
    ball.type = BodyType::Static;
    ball.shape = ShapeDef::sphere(r);
    world.createBody(ball);
    ClothDef c = sheet(Vec3(-0.6, 0.4, -0.6), Vec3(1, 0, 0), Vec3(0, 0, 1), 1.2, 16);
    world.addCloth(c);
    double closest = 1e9;
    for (int i = 0; i < 90; ++i) {
        world.step();
        for (const Vec3& x : *world.particleSystems()[0].positions) closest = std::min(closest, x.norm());
    }
    const auto& x = *world.particleSystems()[0].positions;
    const double corner = x[0].y();
    std::cout << "  " << backend() << ": closest node " << closest << " m from the centre (radius " << r
              << ", thickness " << c.thickness << "), corner y " << corner << "\n";
    // Never inside: a node may end a substep inside by at most what the last constraint pass
    // moved it after the collision pass; 2 mm is a fifth of the thickness.
    EXPECT_GT(closest, r - 0.002);
    EXPECT_LT(corner, 0.0);  // draped: the corners hang below the equator
}

// No external work, no damping: the cloth's energy (kinetic, gravitational and elastic) never
// exceeds its start as it falls from one pinned edge and swings.
TEST_P(ClothTest, EnergyDoesNotGrow) {
    World world(settings());
    ClothDef c = sheet(Vec3(0, 1.0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), 1.0, 10);
    c.damping = 0.0;
    for (int i = 0; i <= 10; ++i) c.pinned.push_back({i, 0});
    world.addCloth(c);
    const double start = clothEnergy(world, c);
    const double drop = c.areaDensity * kG * 0.5;  // the energy the fall releases (weight x half the length)
    double highest = -1e9;
    for (int i = 0; i < 180; ++i) {
        world.step();
        highest = std::max(highest, clothEnergy(world, c) - start);
    }
    std::cout << "  " << backend() << ": largest energy above the start " << highest << " J (fall releases " << drop
              << " J)\n";
    // Position-based dynamics loses energy (each projection is inelastic); the elastic energy left
    // in the links is below 1e-4 J at these strains. 1e-3 of the released energy covers rounding.
    EXPECT_LT(highest, 1e-3 * drop);
}

// Two-way: a ball dropped on a drum (a sheet pinned all round) bounces on it and is held: it never
// goes through, and over the run the impulses the cloth gave it match its weight's plus its change
// of momentum (the cloth's pushes reached the body through the backend, as it reports them).
TEST_P(ClothTest, DrumHoldsABall) {
    World world(settings());
    ClothDef c = sheet(Vec3(-0.5, 1.0, -0.5), Vec3(1, 0, 0), Vec3(0, 0, 1), 1.0, 12);
    for (int i = 0; i <= 12; ++i)
        for (const auto& node : {std::array<int, 2>{i, 0}, std::array<int, 2>{i, 12}, std::array<int, 2>{0, i},
                                 std::array<int, 2>{12, i}})
            c.pinned.push_back(node);
    world.addCloth(c);
    BodyDef def;
    def.shape = ShapeDef::sphere(0.15);
    def.density = 100.0;
    def.position = Vec3(0, 1.3, 0);
    def.allowSleep = false;
    Body ball = world.createBody(def);
    for (int i = 0; i < 30; ++i) world.step();
    const double m = ball.massProperties().mass;
    const double v0 = ball.linearVelocity().y();
    double impulse = 0.0, lowest = 1e9;
    const int steps = 240;
    for (int i = 0; i < steps; ++i) {
        world.step();
        impulse += world.particleForce(ball).y() * settings().timeStep;
        lowest = std::min(lowest, ball.position().y());
    }
    const double expected = m * kG * steps * settings().timeStep + m * (ball.linearVelocity().y() - v0);
    std::cout << "  " << backend() << ": lowest ball centre " << lowest << " m (drum at 1 m), cloth impulse " << impulse
              << " N s, weight x time + momentum change " << expected << " N s\n";
    EXPECT_GT(lowest, 1.0 - 0.15 - 0.3);  // on the drum (it gives under the ball), never through it
    // 1 %: the engine integrates the impulse and gravity in one step (float engines round them).
    EXPECT_NEAR(impulse, expected, 0.01 * std::abs(expected));
}

// A sheet dropped flat on a static mesh floor (a grid of triangles) lands and rests on it: no
// node ever ends a step below the floor's surface plus the thickness (less a rounding tolerance).
TEST_P(ClothTest, RestsOnAMeshFloor) {
    ANYPHYS_REQUIRE(caps().shapes.contains(ShapeType::Mesh), "shape mesh");
    ANYPHYS_MESH_PARTICLES_ONCE();
    World world(settings());
    meshGround(world, -1.0, 1.0, 5, [](double) { return 0.0; });
    ClothDef c = sheet(Vec3(-0.5, 0.5, -0.5), Vec3(1, 0, 0), Vec3(0, 0, 1), 1.0, 10);
    world.addCloth(c);
    double lowest = 1e9;
    for (int i = 0; i < 120; ++i) {
        world.step();
        for (const Vec3& x : *world.particleSystems()[0].positions) lowest = std::min(lowest, x.y());
    }
    const auto& x = *world.particleSystems()[0].positions;
    const double highest = std::accumulate(x.begin(), x.end(), -1e9, [](double m, const Vec3& p) { return std::max(m, p.y()); });
    std::cout << "  " << backend() << ": lowest node " << lowest << " m (thickness less " << c.thickness - lowest << "), highest at the end " << highest << " m (thickness "
              << c.thickness << ")\n";
    // The collision pass ends each iteration, after the links: 1e-9 m is rounding.
    EXPECT_GT(lowest, c.thickness - 1e-9);
    EXPECT_LT(highest, c.thickness + 0.01);  // resting flat: no node more than a centimetre up
}

ANYPHYS_CONTRACT_SUITE(ClothTest);

// A planar world's cloth is a membrane in the plane: hanging from two corners it stays within the
// same stretch bound, on every backend.
class PlanarClothTest : public ContractTest {
protected:
    bool planarTest() const override { return true; }
};

TEST_P(PlanarClothTest, MembraneHangsInThePlane) {
    World world(settings());
    ClothDef c = sheet(Vec3(0, 1.5, 0), Vec3(1, 0, 0), Vec3(0, -1, 0), 1.0, 10);
    c.damping = 2.0;
    c.pinned = {{0, 0}, {10, 0}};
    world.addCloth(c);
    for (int i = 0; i < 240; ++i) world.step();
    const double hanging = maxStretch(world, c);
    std::cout << "  " << backend() << ": planar membrane stretch " << hanging << "\n";
    EXPECT_LT(hanging, 0.015);  // as the 3D sheet (measured 0.58 %)
    for (const Vec3& x : *world.particleSystems()[0].positions) EXPECT_EQ(x.z(), 0.0);
    ClothDef outOfPlane = c;
    outOfPlane.axisV = Vec3(0, 0, 1);
    EXPECT_THROW(world.addCloth(outOfPlane), Error);
}

ANYPHYS_CONTRACT_SUITE(PlanarClothTest);

}  // namespace
}  // namespace anyphys::test
