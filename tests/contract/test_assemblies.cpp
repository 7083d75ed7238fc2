// The built-in assemblies on every backend that has their joints: a pile of ragdolls stays
// whole and comes to rest, sleeping off.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "anyphys/containers/assembly.hpp"
#include "anyphys/containers/mass_regularization.hpp"
#include "anyphys/containers/scene.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

/// The largest distance, over a run, between where a joint's anchor sits on body A (or in the
/// world, for a joint to the world) and where it sits on body B: zero for a rigid joint.
class JointGapMeter {
public:
    JointGapMeter(const Scene& scene, const SceneObjects& objects) {
        for (std::size_t i = 0; i < scene.joints.size(); ++i) {
            const JointDef& d = scene.joints[i].def;
            const Body a = scene.joints[i].bodyA.empty() ? Body() : objects.body(scene.joints[i].bodyA);
            const Body b = objects.body(scene.joints[i].bodyB);
            anchors_.push_back({a, b, a.isValid() ? local(a, d.anchor) : d.anchor, local(b, d.anchor)});
        }
    }
    /// Measures now; false once a gap is not finite.
    bool observe() {
        for (const Anchored& j : anchors_) {
            const Vec3 pa = j.a.isValid() ? Vec3(j.a.position() + j.a.orientation() * j.onA) : j.onA;
            const double gap = (pa - (j.b.position() + j.b.orientation() * j.onB)).norm();
            if (!std::isfinite(gap)) return finite_ = false;
            worst_ = std::max(worst_, gap);
        }
        return true;
    }
    double worst() const { return worst_; }
    bool finite() const { return finite_; }

private:
    static Vec3 local(const Body& body, const Vec3& point) { return body.orientation().conjugate() * (point - body.position()); }
    struct Anchored {
        Body a, b;
        Vec3 onA, onB;  // the anchor in each body's frame (onA in the world frame without A)
    };
    std::vector<Anchored> anchors_;
    double worst_ = 0.0;
    bool finite_ = true;
};

// A chain of ten 0.1 kg capsule links (20 cm each) ending in a 10 kg ball, held at one end and
// released horizontally, for 5 s with sleeping off: the worst joint gap, as built and with the
// assembly's masses regularised (mass ratio 10 across each joint, parents at least as hard to
// turn as their children).
double heavyEndedChainGap(const WorldSettings& settings, const MassRegularization& regularization) {
    const bool planar = settings.planar;
    Scene scene;
    scene.settings = settings;
    const double length = 0.2, y = 2.0;
    const auto joint = [planar](const std::string& a, const std::string& b, double x, double y0) {
        SceneJoint j;
        j.def.type = planar ? JointType::Hinge : JointType::Ball;
        j.def.axis = Vec3::UnitZ();
        j.def.anchor = Vec3(x, y0, 0);
        j.bodyA = a;
        j.bodyB = b;
        return j;
    };
    for (int i = 0; i < 10; ++i) {
        BodyDef link;
        link.name = "link" + std::to_string(i);
        link.shape = ShapeDef::capsule(0.02, 0.5 * length - 0.02);
        link.position = Vec3(length * (i + 0.5), y, 0);
        link.orientation = Quat(Eigen::AngleAxisd(0.5 * std::numbers::pi, Vec3::UnitZ()));  // along X
        link.mass = 0.1;
        link.allowSleep = false;
        scene.bodies.push_back(link);
        scene.joints.push_back(joint(i ? "link" + std::to_string(i - 1) : "", link.name, length * i, y));
    }
    BodyDef end;
    end.name = "end";
    end.shape = ShapeDef::sphere(0.1);
    end.position = Vec3(10 * length + 0.1, y, 0);
    end.mass = 10.0;
    end.allowSleep = false;
    scene.bodies.push_back(end);
    scene.joints.push_back(joint("link9", "end", 10 * length, y));
    regularizeMasses(scene, regularization);
    World world(scene.settings, scene.materials);
    const SceneObjects objects = createSceneObjects(world, scene);
    JointGapMeter gaps(scene, objects);
    while (world.time() < 5.0 && gaps.observe()) world.step();
    return gaps.finite() ? gaps.worst() : std::numeric_limits<double>::infinity();
}

// One draw of the ragdoll pile below: its worst joint gap, its fastest body at the end, its
// lowest body and its worst hinge-limit violation.
struct RagdollPileDraw {
    double worstGap = 0.0;    // m
    double fastest = 0.0;     // m/s, after 10 s
    double lowest = 1e9;      // m
    double worstLimit = 0.0;  // rad beyond a hinge's limits
    bool finite = true;
};

// The middle value of a draw's measure over every draw (an odd count: the middle one).
template <class Measure>
double medianOf(const std::vector<RagdollPileDraw>& draws, Measure measure) {
    std::vector<double> values;
    for (const RagdollPileDraw& d : draws) values.push_back(measure(d));
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

class AssemblyTest : public ContractTest {
protected:
    // Four ragdolls dropped onto each other (each turned, from 1 to 4.5 m up) on a ground plane,
    // for 10 s with sleeping off: no non-finite state, the largest gap between a joint's anchors
    // on its two bodies, and the fastest body at the end.
    //
    // The pile is chaotic. Moving ragdoll i by k x i mm along x (k = 0..8) gave native worst gaps
    // of 18 to 43 mm and fastest bodies of 0.02 to 0.46 m/s after 10 s, Bullet gaps of 30 to
    // 59 mm: one run is one draw, and a change of rounding anywhere could flip a verdict either
    // way (the single run, k = 0, had native pass the rest bound, which 5 of the 9 draws miss, and
    // Bullet the gap bound, which 4 miss). So the pile is run nine times so moved, and each
    // measure is judged by its median over the draws.
    RagdollPileDraw ragdollPileDraw(const Scene& ragdoll, const std::string& assembly, int k) {
        Scene scene;
        scene.settings = settings();
        BodyDef ground;
        ground.name = "ground";
        ground.type = BodyType::Static;
        ground.shape = ShapeDef::plane(Vec3::UnitY(), 0.0);
        scene.bodies.push_back(ground);
        for (int i = 0; i < 4; ++i) {
            // Lying down (a quarter turn about X, or about Z in a planar world), stacked.
            const Quat lie = planarTest() ? Quat(Eigen::AngleAxisd(0.5 * std::numbers::pi * (i % 2 ? 1 : -1), Vec3::UnitZ()))
                                          : Quat(Eigen::AngleAxisd(0.5 * std::numbers::pi, Vec3::UnitX())) *
                                                Quat(Eigen::AngleAxisd(0.9 * i, Vec3::UnitY()));
            const Vec3 at = planarTest() ? Vec3(0.9 * (i % 2 ? 1 : -1), 1.0 + 1.2 * i, 0.0) : Vec3(0.2 * i, 0.5 + 1.2 * i, -0.9);
            appendInstance(scene, ragdoll, Transform{at + Vec3(1e-3 * k * i, 0, 0), lie}, "r" + std::to_string(i) + "/");
        }
        for (BodyDef& b : scene.bodies) b.allowSleep = false;
        World world(scene.settings, scene.materials);
        const SceneObjects objects = createSceneObjects(world, scene);
        JointGapMeter gaps(scene, objects);
        RagdollPileDraw draw;
        const auto observeLimits = [&] {
            for (std::size_t i = 0; i < scene.joints.size(); ++i) {
                const JointDef& d = scene.joints[i].def;
                if (d.type != JointType::Hinge || !d.limits) continue;
                const double angle = objects.joints[i].position();
                draw.worstLimit = std::max({draw.worstLimit, d.limits->lower - angle, angle - d.limits->upper});
            }
        };
        while (world.time() < 10.0 && gaps.observe()) {
            observeLimits();
            world.step();
        }
        draw.worstGap = gaps.worst();
        draw.finite = gaps.finite();
        for (const Body& body : objects.bodies) {
            draw.fastest = std::max(draw.fastest, body.linearVelocity().norm());
            draw.lowest = std::min(draw.lowest, body.position().y());
        }
        std::cout << "[ MEASURED ] " << backend() << " " << toString(*world.settings().solver) << " pile of 4 " << assembly
                  << ", ragdolls moved " << k << " mm apart: worst joint gap " << draw.worstGap * 1e3
                  << " mm, fastest body after 10 s " << draw.fastest << " m/s, lowest body " << draw.lowest
                  << " m, worst hinge limit violation " << draw.worstLimit * 180.0 / std::numbers::pi << " deg\n";
        return draw;
    }

    void ragdollPile(const std::string& assembly) {
        const Scene& ragdoll = builtinAssembly(assembly);
        for (const SceneJoint& j : ragdoll.joints)
            ANYPHYS_REQUIRE(caps().jointTypes.contains(std::string(toString(j.def.type))),
                            "joint type " + std::string(toString(j.def.type)));
        // The median is then the fifth draw's. The sanitizers' run leaves the case out
        // (tests/CMakeLists.txt), as the piles' code paths run in lighter cases there.
        constexpr int count = 9;
        std::vector<RagdollPileDraw> draws;
        for (int k = 0; k < count; ++k) {
            draws.push_back(ragdollPileDraw(ragdoll, assembly, k));
            EXPECT_TRUE(draws.back().finite) << "draw " << k << ": a state went non-finite";
            EXPECT_GT(draws.back().lowest, -0.2) << "draw " << k << ": something fell through the ground";
        }
        const double gap = medianOf(draws, [](const RagdollPileDraw& d) { return d.worstGap; });
        const double fastest = medianOf(draws, [](const RagdollPileDraw& d) { return d.fastest; });
        const double limitDegrees = medianOf(draws, [](const RagdollPileDraw& d) { return d.worstLimit; }) * 180.0 / std::numbers::pi;
        std::cout << "[ MEASURED ] " << backend() << " pile of 4 " << assembly << ", medians of " << count
                  << " draws: worst joint gap " << gap * 1e3 << " mm, fastest body after 10 s " << fastest
                  << " m/s, worst hinge limit violation " << limitDegrees << " deg\n";
        // 5 cm: soft joints stretch for a moment when a 70 kg body lands on another from 4 m; a
        // torn limb is metres.
        expectCriterion(planarTest() ? "planar.assemblies.ragdoll_gap" : "assemblies.ragdoll_gap", gap < 0.05,
                        "median worst joint gap " + std::to_string(gap) + " m", gap);
        // At rest after 10 s: 0.1 m/s, well below a limb still falling (1 m/s after 0.1 s).
        expectCriterion(planarTest() ? "planar.assemblies.ragdoll_rest" : "assemblies.ragdoll_rest", fastest < 0.1,
                        "median fastest body " + std::to_string(fastest) + " m/s after 10 s", fastest);
        // Hinge limits (elbows, knees; every planar joint) held within 3 degrees: a soft limit
        // gives a little under a 70 kg landing; a broken one lets a knee bend the wrong way.
        expectCriterion(planarTest() ? "planar.assemblies.ragdoll_limits" : "assemblies.ragdoll_limits", limitDegrees <= 3.0,
                        "median: a hinge went " + std::to_string(limitDegrees) + " deg beyond its limits", limitDegrees);
    }

    void regularisedChain(const WorldSettings& settings, const std::string& criterion) {
        const double asBuilt = heavyEndedChainGap(settings, MassRegularization{});
        const double regularised = heavyEndedChainGap(settings, MassRegularization{10.0, true});
        std::cout << "[ MEASURED ] " << settings.backend << " heavy-ended chain (1:100 masses): worst joint gap as built "
                  << asBuilt << " m, regularised " << regularised << " m\n";
        // 5 cm, a quarter of a link: the chain is visibly whole. As built, the 1:100 mass ratio and
        // the links' small inertia tear it apart on three of the four backends (metres of gap).
        expectCriterion(criterion, regularised < 0.05, "worst joint gap " + std::to_string(regularised) + " m");
    }
};

TEST_P(AssemblyTest, RagdollPileStaysWholeAndComesToRest) { ragdollPile("ragdoll"); }

// The state of anyphys_soak (seed 15, native) 40 steps before its pile blew up at step 943 243:
// four ragdolls and 24 boxes, an elbow pinched 70 degrees off its hinge between the chest, the
// ground and another ragdoll's shin. The ragdolls are built where they were spawned (so their
// joints keep the frames they were made with), then every body is set to its state in the file.
// Native's old hinge rows (small-angle, axis . yB) went from 10 m/s to 1e4 m/s within 3 steps of
// this; every backend must hold it for 10 s, whole.
//
// The pile is chaotic: on native, nudging every velocity in the file by 7e-12 of itself changed
// the worst gap from 32 to 55 mm, and 7 of 30 such nudges (k 1e-12, k = 0..29) gave more than
// 5 cm, up to 75 mm. One run is one draw, so a change of rounding anywhere in the solver could
// flip the verdict either way. The pile is run several times, nudged so, and judged by the median
// of the draws' worst gaps; every draw must stay finite and unthrown.
struct PinchedPileDraw {
    double worstGap = 0.0;  // m
    double fastest = 0.0;   // m/s, fastest body over the run
    bool finite = true;
};

PinchedPileDraw runPinchedPile(const Scene& scene, const Scene& snapshot, double velocityNudge) {
    World world(scene.settings, scene.materials);
    const SceneObjects objects = createSceneObjects(world, scene);
    JointGapMeter gaps(scene, objects);  // the anchors as made
    for (const BodyDef& b : snapshot.bodies) {
        Body body = objects.body(b.name);
        body.setTransform(b.position, b.orientation);
        body.setLinearVelocity((1.0 + velocityNudge) * b.linearVelocity);
        body.setAngularVelocity((1.0 + velocityNudge) * b.angularVelocity);
    }
    PinchedPileDraw draw;
    while (world.time() < 10.0 && gaps.observe()) {
        world.step();  // a diverged state throws (the default policy), failing the test
        for (const Body& body : objects.bodies) draw.fastest = std::max(draw.fastest, body.linearVelocity().norm());
    }
    draw.worstGap = gaps.worst();
    draw.finite = gaps.finite();
    return draw;
}

TEST_P(AssemblyTest, PinchedPileFromTheSoakRunStaysWhole) {
    ANYPHYS_REQUIRE(caps().dimensions == 3 && !planarTest(), "3D worlds");
    const Scene& ragdoll = builtinAssembly("ragdoll");
    for (const SceneJoint& j : ragdoll.joints)
        ANYPHYS_REQUIRE(caps().jointTypes.contains(std::string(toString(j.def.type))),
                        "joint type " + std::string(toString(j.def.type)));
    const Scene snapshot = loadScene(std::string(ANYPHYS_CONTRACT_DATA_DIR) + "/soak_pinched_ragdolls.json");
    Scene scene;
    scene.settings = settings();  // the soak's: the backend's defaults
    std::vector<std::string> prefixes;
    for (const BodyDef& b : snapshot.bodies) {
        const auto slash = b.name.find('/');
        if (slash == std::string::npos) scene.bodies.push_back(b);  // the ground and the boxes
        else if (std::find(prefixes.begin(), prefixes.end(), b.name.substr(0, slash + 1)) == prefixes.end())
            prefixes.push_back(b.name.substr(0, slash + 1));
    }
    for (const std::string& prefix : prefixes) {
        // Spawned unturned: the offset is any joint's anchor in the file less the assembly's.
        const SceneJoint& first = ragdoll.joints.front();
        const auto spawned = std::find_if(snapshot.joints.begin(), snapshot.joints.end(),
                                          [&](const SceneJoint& j) { return j.def.name == prefix + first.def.name; });
        ASSERT_NE(spawned, snapshot.joints.end()) << prefix;
        appendInstance(scene, ragdoll, Transform{spawned->def.anchor - first.def.anchor, Quat::Identity()}, prefix);
    }
    // Nine draws: the median is then the fifth, and a minority of wide draws cannot move it.
    int draws = 9;
#ifdef ANYPHYS_SANITIZED
    // About 30 s per draw on native under the sanitizers: one draw runs the pile's code paths
    // there, and the gap is judged by the release run's median (one draw of a chaotic pile is no
    // verdict: native's first draw opens 51.6 mm where the median of nine is 47.1).
    draws = 1;
    std::cout << "[ NOT RUN  ] " << backend() << " pinched pile: draws 2 to 9, and the gap's verdict, left to the release run\n";
#endif
    std::vector<double> worstGaps;
    std::string listed;
    for (int k = 0; k < draws; ++k) {
        const PinchedPileDraw draw = runPinchedPile(scene, snapshot, 1e-12 * k);
        std::cout << "[ MEASURED ] " << backend() << " pinched pile from the soak run, velocities x (1 + " << k
                  << "e-12): worst joint gap " << draw.worstGap * 1e3 << " mm, fastest body " << draw.fastest
                  << " m/s over 10 s\n";
        EXPECT_TRUE(draw.finite) << "draw " << k;
        // Nothing is thrown: the fastest body in the file moves at 10 m/s; falling 10 m gives 14 m/s.
        EXPECT_LT(draw.fastest, 20.0) << "draw " << k;
        worstGaps.push_back(draw.worstGap);
        listed += (listed.empty() ? "" : ", ") + std::to_string(draw.worstGap);
    }
    std::sort(worstGaps.begin(), worstGaps.end());
    const double median = worstGaps[worstGaps.size() / 2];
    // Whole, by the pile's criterion (5 cm), under a key of its own: this pile and the four-ragdoll
    // pile above are different runs, and a backend may meet the bound in one and not the other.
    if (draws < 9) return;  // the sanitizers' single draw (above)
    expectCriterion("assemblies.pinched_pile_gap", median < 0.05,
                    "median worst joint gap " + std::to_string(median) + " m of draws " + listed, median);
}

TEST_P(AssemblyTest, RegularisedMassesHoldAHeavyEndedChainTogether) {
    ANYPHYS_REQUIRE(caps().jointTypes.contains("ball"), "joint type ball");
    regularisedChain(settings(), "assemblies.regularised_chain_gap");
}

ANYPHYS_CONTRACT_SUITE(AssemblyTest);

class PlanarAssemblyTest : public AssemblyTest {
protected:
    bool planarTest() const override { return true; }
};

TEST_P(PlanarAssemblyTest, RagdollPileStaysWholeAndComesToRest) { ragdollPile("ragdoll_planar"); }

TEST_P(PlanarAssemblyTest, RegularisedMassesHoldAHeavyEndedChainTogether) {
    ANYPHYS_REQUIRE(caps().jointTypes.contains("hinge"), "joint type hinge");
    regularisedChain(settings(), "planar.assemblies.regularised_chain_gap");
}

ANYPHYS_CONTRACT_SUITE(PlanarAssemblyTest);

}  // namespace
}  // namespace anyphys::test
