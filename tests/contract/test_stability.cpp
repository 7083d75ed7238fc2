// Hard cases stay stable over the whole run, with sleeping off, on every solver a backend offers
// and at 1 and 4 substeps. Sleeping can freeze a stack before its drift shows and reading the
// drift once at the end misses a pile that came apart and fell back; so every step is measured,
// up and down as well as sideways.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

/// Worst motion of a resting structure over a run: sideways drift of any box from where it was
/// built, and the top box's sinking (positive) or lifting (negative).
struct StructureRun {
    double drift = 0.0;
    double sink = 0.0;
    double lift = 0.0;
    bool finite = true;
};

StructureRun runStructure(const CatalogueScene& entry, WorldSettings s, double seconds) {
    World world(s, entry.scene.materials);
    std::vector<Body> boxes;
    std::vector<Vec3> built;
    std::size_t top = 0;
    for (BodyDef def : entry.scene.bodies) {
        def.allowSleep = false;
        Body body = world.createBody(def);
        if (def.type != BodyType::Dynamic) continue;
        if (boxes.empty() || def.position.y() > built[top].y()) top = boxes.size();
        boxes.push_back(body);
        built.push_back(def.position);
    }
    StructureRun run;
    while (world.time() < seconds) {
        world.step();
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const Vec3 p = boxes[i].position();
            if (!p.allFinite()) {
                run.finite = false;
                return run;
            }
            const Vec3 d = p - built[i];
            run.drift = std::max(run.drift, std::hypot(d.x(), d.z()));
        }
        const double dy = boxes[top].position().y() - built[top].y();
        run.sink = std::max(run.sink, -dy);
        run.lift = std::max(run.lift, dy);
    }
    return run;
}

class StabilityTest : public ContractTest {
protected:
    /// Every solver the backend offers, at 1 and (where substeps are honoured) 4 substeps.
    std::vector<WorldSettings> variants(const CatalogueScene& entry, bool direct) const {
        return variants(entry.scene.settings, entry.name, direct);
    }
    std::vector<WorldSettings> variants(const WorldSettings& base, const std::string& name, bool direct) const {
        std::vector<WorldSettings> out;
        const bool substeps = caps().parameters.contains("settings.substeps");
        std::vector<int> counts = substeps ? std::vector<int>{1, 4} : std::vector<int>{1};
#ifdef ANYPHYS_SANITIZED
        if (!direct && counts.size() > 1) {  // the pyramid: 4 substeps cost four times as much
            counts = {1};
            std::cout << "[ NOT RUN  ] " << backend() << " " << name
                      << " at 4 substeps: left to the release run under the sanitizers\n";
        }
#endif
        for (Solver solver : caps().solvers) {
            if (solver == Solver::Direct && !direct) {
                // Visible, not silent: a direct solver's cost grows with the cube of the contacts.
                std::cout << "[ NOT RUN  ] " << backend() << " " << name
                          << " with the direct solver: O(n^3) in the contacts, minutes per run at this size\n";
                continue;
            }
            for (int n : counts) {
                WorldSettings s = base;
                s.backend = backend();
                s.planar = planarTest();
                s.solver = solver;
                s.substeps = n;
                out.push_back(s);
            }
        }
        return out;
    }

    // drift: the sideways bound; contacts: how many resting contacts are below the top box (it
    // may sink by their allowed overlap, linearSlop each, and no more).
    void expectStandsOverRun(const std::string& scene, const std::string& id, double seconds, double driftBound,
                             int contactsBelowTop, bool direct) {
        const CatalogueScene& entry = catalogueScene(scene);
        for (const WorldSettings& s : variants(entry, direct)) {
            const StructureRun run = runStructure(entry, s, seconds);
            const std::string variant = variantName(s);
            std::ostringstream measured;
            measured << variant << ": drift " << run.drift << " m, sank " << run.sink << " m, lifted " << run.lift << " m";
            std::cout << "[ MEASURED ] " << backend() << " " << scene << " over " << seconds << " s, sleeping off, "
                      << measured.str() << '\n';
            EXPECT_TRUE(run.finite) << variant;
            const double sinkBound = contactsBelowTop * s.linearSlop;
            // Lifting: built without gaps or overlap, nothing may push the top up; 1 mm covers
            // the contacts settling to their designed overlap unevenly.
            // The measure a declared deviation's ceiling applies to: the worst of the three as a
            // multiple of its bound (<= 1 stands).
            const double times = run.finite ? std::max({run.drift / driftBound, run.sink / sinkBound, run.lift / 1e-3})
                                            : std::numeric_limits<double>::infinity();
            expectCriterion(id + "." + variant, times <= 1.0,
                            measured.str() + " (bounds: drift " + std::to_string(driftBound) + ", sink " +
                                std::to_string(sinkBound) + ", lift 0.001; " + std::to_string(times) + " x)",
                            times);
        }
    }

    // A straight stack has nothing pushing it sideways: 1 cm over 10 s is solver error only.
    void tenBoxStack() {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    expectStandsOverRun(planarTest() ? "box_stack_10_planar" : "box_stack_10", planarTest() ? "planar.stability.stack10" : "stability.stack10",
                        10.0, 0.01, 10, true);
}

    // Every mass scaled by one factor changes no motion under gravity and contacts alone: each
    // force scales with the masses and no acceleration changes. So the ten-box stack of 100 t
    // boxes (density 1e5), and of 10 000 t, must rest as the one of 1 t boxes does. A contact
    // softness fixed in absolute terms, not relative to the masses it holds, lets a heavy stack
    // sink (ODE's contacts did: 100 t boxes sank 9.2 m into the ground over 10 s), and one applied
    // to the normal rows only lets it walk (ODE's friction rows: 0.87 m at 1 000 t).
    void heavyStack() {
        const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
        ANYPHYS_REQUIRE(missing.empty(), missing);
        const CatalogueScene& light = catalogueScene(planarTest() ? "box_stack_10_planar" : "box_stack_10");
        WorldSettings s = light.scene.settings;
        s.backend = backend();
        s.planar = planarTest();
        const StructureRun asLight = runStructure(light, s, 10.0);
        std::ostringstream measured;
        measured << "1 t boxes: drift " << asLight.drift << " m, sank " << asLight.sink << " m";
        bool finite = asLight.finite;
        // Some engines' light stack already sways by centimetres (massScalingBound).
        double times = 0.0;
        for (const double factor : {100.0, 10000.0}) {
            CatalogueScene heavy = light;
            for (BodyDef& b : heavy.scene.bodies) {
                if (b.type != BodyType::Dynamic) continue;
                ASSERT_FALSE(b.mass || b.inertia) << "the stack's masses come from its density";
                b.density = factor * b.density.value_or(1000.0);
            }
            const StructureRun asHeavy = runStructure(heavy, s, 10.0);
            measured << "; " << factor << " t boxes: drift " << asHeavy.drift << " m, sank " << asHeavy.sink << " m";
            finite = finite && asHeavy.finite;
            times = std::max({times, asHeavy.sink / massScalingBound(asLight.sink),
                              asHeavy.drift / massScalingBound(asLight.drift)});
        }
        std::cout << "[ MEASURED ] " << backend() << " ten-box stack over 10 s, sleeping off, " << measured.str() << '\n';
        EXPECT_TRUE(finite);
        expectCriterion(planarTest() ? "planar.stability.stack10_heavy" : "stability.stack10_heavy", times <= 1.0,
                        measured.str() + " (" + std::to_string(times) + " x the bound)", times);
    }

    // A column of ten unit cubes dropped onto the ground (a plane, or a static box, whose pairs
    // some engines collide by another path) with gaps between them, so every cube lands on the
    // one below: over the last 5 s of 20 it must be at rest and upright. Stacked touching, as in
    // tenBoxStack, nothing excites a column; landings do, and a solver that feeds energy back
    // (one that warm-starts its contacts with more of the last step's push-out than the push
    // allows) makes it rock harder every second.
    void droppedColumn() {
        const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
        ANYPHYS_REQUIRE(missing.empty(), missing);
        const std::string id = planarTest() ? "planar.stability.dropped_column" : "stability.dropped_column";
        for (const WorldSettings& s : variants(WorldSettings{}, "dropped column", true))
            for (const bool onBox : {false, true}) {
                // One criterion per solver, substeps and ground: the worst of both drops.
                std::ostringstream measured;
                double times = 0.0;
                bool finite = true;
                for (const double gap : {0.001, 0.05}) {
                    const ColumnRest rest = dropColumn(s, gap, onBox);
                    std::ostringstream drop;
                    drop << gap * 1e3 << " mm gaps: fastest cube " << rest.speed << " m/s, most tilted "
                         << rest.tilt * 180.0 / std::numbers::pi << " deg, top cube " << rest.drift << " m off";
                    std::cout << "[ MEASURED ] " << backend() << " dropped column of 10 onto the " << (onBox ? "box" : "plane")
                              << ", over 15 to 20 s, sleeping off, " << variantName(s) << ", " << drop.str() << '\n';
                    measured << (gap < 0.01 ? "" : "; ") << drop.str();
                    finite = finite && rest.finite;
                    // At rest: after the landings only the solver's residual moves a cube (native's
                    // PGS at 1 substep, still settling, 9.0 mm/s, down to 0.75 mm/s after a minute;
                    // its soft step and Box2D below 0.5 mm/s); 1 cm/s is 60 times below the rocking
                    // guarded against (0.61 m/s). Upright: a column may settle a little out of true
                    // (0.11 deg at most where it settles), 1 deg puts its top 17 cm over. In place:
                    // landings nudge the cubes by millimetres (1 cm at most where it settles, 3.7 cm
                    // with ODE's jitter); a tenth of a cube more is a column walking or leaning
                    // over. The measure a ceiling applies to: the worst of the three as a multiple
                    // of its bound.
                    times = std::max({times, rest.speed / 0.01, rest.tilt / (std::numbers::pi / 180.0), rest.drift / 0.1});
                }
                EXPECT_TRUE(finite) << variantName(s) << ": " << measured.str();
                if (!finite) times = std::numeric_limits<double>::infinity();
                expectCriterion(id + "." + variantName(s) + (onBox ? ".box" : ".plane"), times <= 1.0,
                                variantName(s) + " onto the " + (onBox ? "box: " : "plane: ") + measured.str() + " (" +
                                    std::to_string(times) + " x the bounds 0.01 m/s, 1 deg, 0.1 m)",
                                times);
            }
    }

    struct ColumnRest {
        double speed = 0.0;  // m/s, the fastest cube over the last 5 s
        double tilt = 0.0;   // rad, the most tilted cube
        double drift = 0.0;  // m, the top cube's sideways distance from where it was dropped
        bool finite = true;
    };

    ColumnRest dropColumn(const WorldSettings& s, double gap, bool onBox) const {
        constexpr int kCubes = 10;
        constexpr double kHalf = 0.5, kSeconds = 20.0, kLate = 15.0;
        World world(s);
        if (onBox) {
            BodyDef ground = boxDef("ground", Vec3(5.0, 0.5, 5.0), Vec3(0.0, -0.5, 0.0));
            ground.type = BodyType::Static;
            world.createBody(ground);
        } else {
            world.createBody(groundDef());
        }
        std::vector<Body> cubes;
        for (int i = 0; i < kCubes; ++i) {
            BodyDef cube = boxDef("cube", Vec3(kHalf, kHalf, kHalf), Vec3(0.0, kHalf + gap + i * (2 * kHalf + gap), 0.0));
            cube.allowSleep = false;  // a sleeping column proves nothing
            cubes.push_back(world.createBody(cube));
        }
        const Vec3 dropped = cubes.back().position();
        ColumnRest rest;
        while (world.time() < kSeconds) {
            world.step();
            if (world.time() <= kLate) continue;
            for (const Body& cube : cubes) {
                if (!cube.position().allFinite() || !cube.linearVelocity().allFinite()) {
                    rest.finite = false;
                    return rest;
                }
                const Vec3 up = cube.orientation() * Vec3::UnitY();
                rest.tilt = std::max(rest.tilt, std::acos(std::clamp(up.y(), -1.0, 1.0)));
                rest.speed = std::max(rest.speed, cube.linearVelocity().norm());
            }
            const Vec3 moved = cubes.back().position() - dropped;
            rest.drift = std::max(rest.drift, std::hypot(moved.x(), moved.z()));
        }
        return rest;
    }

    // A 20-row pyramid: its rows spread a little as the contacts below compress, 1 cm over 5 s.
    void twentyRowPyramid() {
    const std::string missing = lacking(caps(), {ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    ANYPHYS_REQUIRE(missing.empty(), missing);
    expectStandsOverRun(planarTest() ? "pyramid_20_planar" : "pyramid_20", planarTest() ? "planar.stability.pyramid20" : "stability.pyramid20",
                        5.0, 0.01, 20, false);
    }
};

TEST_P(StabilityTest, TenBoxStackStandsOverTheWholeRun) { tenBoxStack(); }
TEST_P(StabilityTest, TwentyRowPyramidStandsOverTheWholeRun) { twentyRowPyramid(); }
TEST_P(StabilityTest, HeavyStackRestsAsALightOne) { heavyStack(); }
TEST_P(StabilityTest, DroppedColumnComesToRestUpright) { droppedColumn(); }

ANYPHYS_CONTRACT_SUITE(StabilityTest);

class PlanarStabilityTest : public StabilityTest {
protected:
    bool planarTest() const override { return true; }
};

TEST_P(PlanarStabilityTest, TenBoxStackStandsOverTheWholeRun) { tenBoxStack(); }
TEST_P(PlanarStabilityTest, TwentyRowPyramidStandsOverTheWholeRun) { twentyRowPyramid(); }
TEST_P(PlanarStabilityTest, HeavyStackRestsAsALightOne) { heavyStack(); }
TEST_P(PlanarStabilityTest, DroppedColumnComesToRestUpright) { droppedColumn(); }

ANYPHYS_CONTRACT_SUITE(PlanarStabilityTest);

}  // namespace
}  // namespace anyphys::test
