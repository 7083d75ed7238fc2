// The hard cases: scenes that break weak solvers (tall stacks, wide pyramids, high mass ratios,
// deep initial overlap, far from the origin, fast small bodies, fast spin, mixed shapes on a
// mesh, heavy chains, ragdoll piles). Each has one measure and a bound, with the reason for the
// bound beside it; `anyphys hardcases` runs them on every backend, sleeping off.
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "anyphys/containers/assembly.hpp"
#include "catalogue_parts.hpp"

namespace anyphys::catalogue_parts {
namespace {

constexpr double kPi = std::numbers::pi;

/// Sleeping off for every body: a sleeping pile hides the drift it would show awake.
void keepAwake(Scene& scene) {
    for (BodyDef& b : scene.bodies) b.allowSleep = false;
}

/// Largest distance any of `bodies` moved from its start (all three axes).
EndpointProbe::Measure maxDisplacement(std::vector<std::size_t> bodies) {
    return [bodies](const std::vector<BodyState>& first, const std::vector<BodyState>& now, double) {
        double worst = 0.0;
        for (std::size_t i : bodies) {
            const double d = (now[i].position - first[i].position).norm();
            if (!(d <= worst)) worst = d;  // keeps a NaN (blow-up) visible
        }
        return worst;
    };
}

/// Fastest linear speed of any of `bodies`.
EndpointProbe::Measure maxSpeed(std::vector<std::size_t> bodies) {
    return [bodies](const std::vector<BodyState>&, const std::vector<BodyState>& now, double) {
        double worst = 0.0;
        for (std::size_t i : bodies) {
            const double v = now[i].linearVelocity.norm();
            if (!(v <= worst)) worst = v;
        }
        return worst;
    };
}

/// A check whose measure is worst over the run, with expected value 0: passes at value <= bound.
SceneCheck worstCheck(const std::string& label, const std::string& unit, double bound, const std::string& why,
                      const std::string& criterion, EndpointProbe::Measure measure) {
    return worstOverRunCheck(SceneCheck{label, unit, 0.0, bound, why, {}, criterion}, std::move(measure));
}

/// Joint gap: the largest distance, over the scene's joints, between the anchor as carried by
/// body A and as carried by body B (the world for a joint to it). Anchors are fixed in each
/// body's frame at the first observation. Ball, hinge, cone and fixed joints keep them together.
class JointGapProbe : public SceneProbe {
public:
    struct Link {
        std::optional<std::size_t> a, b;  ///< body indices; nullopt = the world
        Vec3 anchor;                      ///< world frame, at the start
    };
    explicit JointGapProbe(std::vector<Link> links) : links_(std::move(links)) {}

    void observe(double, const std::vector<BodyState>& states) override {
        if (localA_.empty()) {
            for (const Link& l : links_) {
                localA_.push_back(local(l.a, l.anchor, states));
                localB_.push_back(local(l.b, l.anchor, states));
            }
        }
        for (std::size_t j = 0; j < links_.size(); ++j) {
            const double gap = (world(links_[j].a, localA_[j], states) - world(links_[j].b, localB_[j], states)).norm();
            if (!(gap <= worst_)) worst_ = gap;
        }
    }
    double value() const override { return worst_; }

private:
    static Vec3 local(const std::optional<std::size_t>& body, const Vec3& anchor, const std::vector<BodyState>& s) {
        if (!body) return anchor;
        return s[*body].orientation.conjugate() * (anchor - s[*body].position);
    }
    static Vec3 world(const std::optional<std::size_t>& body, const Vec3& local, const std::vector<BodyState>& s) {
        if (!body) return local;
        return s[*body].position + s[*body].orientation * local;
    }

    std::vector<Link> links_;
    std::vector<Vec3> localA_, localB_;
    double worst_ = 0.0;
};

std::function<std::unique_ptr<SceneProbe>()> jointGapProbe(const Scene& scene) {
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) index[scene.bodies[i].name] = i;
    std::vector<JointGapProbe::Link> links;
    const auto find = [&](const std::string& name) -> std::optional<std::size_t> {
        if (name.empty()) return std::nullopt;
        return index.at(name);
    };
    for (const SceneJoint& j : scene.joints) links.push_back({find(j.bodyA), find(j.bodyB), j.def.anchor});
    return [links] { return std::make_unique<JointGapProbe>(links); };
}

CatalogueScene planarCase(CatalogueScene c) {
    c.name += "_planar";
    c.description = "planar (XY): " + c.description;
    c.scene.settings.planar = true;
    c.check->criterion = "planar." + c.check->criterion;
    return c;
}

CatalogueScene hardCase(const std::string& name, const std::string& description, double duration) {
    CatalogueScene c;
    c.name = name;
    c.description = description;
    c.duration = duration;
    c.scene.settings.timeStep = 1.0 / 60.0;
    c.hardCase = true;
    c.compareByDefault = false;  // run by `anyphys hardcases`, or by name
    return c;
}

// ---- stacks and pyramids -----------------------------------------------------------------------

// `boxes` unit boxes stacked with no gap on a ground plane, kept awake; body k + 1 is box k.
void addColumn(Scene& scene, int boxes) {
    scene.bodies.push_back(groundPlane());
    for (int i = 0; i < boxes; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "box_%02d", i);
        scene.bodies.push_back(unitBox(name, Vec3(0, 0.5 + i, 0)));
    }
    keepAwake(scene);
}

CatalogueScene stack20() {
    constexpr int kBoxes = 20;
    CatalogueScene c = hardCase("hard_stack_20", "20 unit boxes stacked with no gap stand for 10 s; the top box's largest sideways drift", 10.0);
    addColumn(c.scene, kBoxes);
    c.check = worstCheck("top drift", "m", 0.01,
                         "1 cm at any time: nothing pushes a straight stack sideways, so any drift is solver error "
                         "(the same bound as the 10-box stack)",
                         "hard.stack20.drift", maxHorizontalDrift({static_cast<std::size_t>(kBoxes)}));
    return c;
}

CatalogueScene column40() {
    constexpr int kBoxes = 40;
    CatalogueScene c = hardCase("hard_column_40",
                                "40 unit boxes stacked with no gap stand for 30 s; the top box's largest sideways drift", 30.0);
    addColumn(c.scene, kBoxes);
    c.check = worstCheck("top drift", "m", 0.05,
                         "5 cm at any time (a twentieth of a box, as the 100-row pyramid): a column of rigid blocks stands; "
                         "soft contacts let it sway slowly by about a centimetre (Box3D: 3.4 cm over 30 s), and once "
                         "their anchors turn with the bodies a column this tall buckles under its own weight and falls",
                         "hard.column40.drift", maxHorizontalDrift({static_cast<std::size_t>(kBoxes)}));
    return c;
}

CatalogueScene pyramid100Planar() {
    constexpr int kRows = 100;
    CatalogueScene c = hardCase("hard_pyramid_100_planar",
                                "planar (XY) pyramid of 5050 unit boxes, 100 rows, friction 0.6 (Box2D v3's large_pyramid "
                                "benchmark); the largest sideways drift of any box over 5 s",
                                5.0);
    c.scene.settings.planar = true;
    c.scene.materials.add("box", Material{0.6, 0.0, 1000.0});
    c.scene.bodies.push_back(groundPlane());
    c.scene.bodies.back().material = "box";
    for (int row = 0; row < kRows; ++row) {
        const int count = kRows - row;
        for (int i = 0; i < count; ++i) {
            char name[40];
            std::snprintf(name, sizeof name, "box_r%03d_%03d", row, i);
            c.scene.bodies.push_back(unitBox(name, Vec3(i - 0.5 * (count - 1), 0.5 + row, 0)));
            c.scene.bodies.back().material = "box";
        }
    }
    keepAwake(c.scene);
    c.check = worstCheck("max box drift", "m", 0.05,
                         "5 cm (a twentieth of a box) at any time: the pyramid stands as built, as the 20-row one must",
                         "planar.hard.pyramid100.drift", maxHorizontalDrift(dynamicBodies(c.scene)));
    return c;
}

// ---- friction structures -----------------------------------------------------------------------

/// A card 1 m x 0.7 m x 2 cm leaning in the XY plane, its top tilted `tilt` rad toward +x
/// (negative: toward -x), its lowest edge on y = `base`, its top outer edge at x = `apexX`.
BodyDef leaningCard(const std::string& name, double apexX, double base, double tilt) {
    constexpr double kHalfLength = 0.5, kHalfThickness = 0.01;
    const double a = std::abs(tilt), side = tilt > 0 ? -1.0 : 1.0;  // the card lies on this side of the apex
    BodyDef card;
    card.name = name;
    card.shape = ShapeDef::box(Vec3(kHalfThickness, kHalfLength, 0.35));
    card.material = "card";
    card.orientation = Quat(Eigen::AngleAxisd(-tilt, Vec3::UnitZ()));
    card.position = Vec3(apexX + side * (kHalfLength * std::sin(a) + kHalfThickness * std::cos(a)),
                         base + kHalfLength * std::cos(a) + kHalfThickness * std::sin(a), 0.0);
    return card;
}

CatalogueScene cardHouse() {
    constexpr double kTilt = 20.0 * kPi / 180.0;
    // Each A-frame's apex is 2 mm narrower than touching: the cards start pressed together by
    // 1 mm each (less than the 5 mm linear slop), so they hold each other from the first step.
    constexpr double kPress = 0.001;
    CatalogueScene c = hardCase("hard_card_house",
                                "house of 7 cards (1 m x 0.7 m x 2 cm, 20 deg from vertical, friction 0.7): two A-frames, "
                                "a flat card across them, a third A-frame on top; largest card displacement over 5 s",
                                5.0);
    c.scene.materials.add("card", Material{0.7, 0.0, 600.0});
    c.scene.bodies.push_back(groundPlane());
    c.scene.bodies.back().material = "card";
    const double apexHeight = std::cos(kTilt);  // card length 1 m
    const auto aFrame = [&](const std::string& name, double x, double base) {
        c.scene.bodies.push_back(leaningCard(name + "_left", x + kPress, base, kTilt));
        c.scene.bodies.push_back(leaningCard(name + "_right", x - kPress, base, -kTilt));
    };
    aFrame("low_a", -0.6, 0.0);
    aFrame("low_b", 0.6, 0.0);
    BodyDef floor;
    floor.name = "floor";
    floor.shape = ShapeDef::box(Vec3(0.9, 0.01, 0.35));
    floor.material = "card";
    floor.position = Vec3(0, apexHeight + 0.01, 0);  // on the two apexes
    c.scene.bodies.push_back(floor);
    aFrame("top", 0.0, apexHeight + 0.02);
    keepAwake(c.scene);
    // A card house leans on friction alone: each leaning card needs mu >= tan(20 deg) / 2 = 0.18
    // at its foot; 0.7 leaves a margin of almost 4.
    c.check = worstCheck("max card displacement", "m", 0.02,
                         "2 cm at any time: the cards hold each other by friction with a margin of 4; a card that "
                         "slips falls (decimetres)",
                         "hard.card_house.displacement", maxDisplacement(dynamicBodies(c.scene)));
    return c;
}

/// A semicircular arch of `count` wedge blocks (annular sectors of radii 2 m and 2.6 m, 1 m
/// deep) standing on the ground, held by friction alone.
CatalogueScene arch() {
    constexpr int kBlocks = 9;
    constexpr double kInner = 2.0, kOuter = 2.6, kHalfDepth = 0.5;
    CatalogueScene c = hardCase("hard_arch",
                                "semicircular stone arch of 9 wedge blocks (radii 2 m and 2.6 m, friction 0.8, no glue) on "
                                "the ground; largest block displacement over 5 s",
                                5.0);
    c.scene.materials.add("stone", Material{0.8, 0.0, 2500.0});
    c.scene.bodies.push_back(groundPlane());
    c.scene.bodies.back().material = "stone";
    for (int i = 0; i < kBlocks; ++i) {
        const double a0 = kPi * i / kBlocks, a1 = kPi * (i + 1) / kBlocks;
        std::vector<Vec3> corners;
        for (double a : {a0, a1})
            for (double r : {kInner, kOuter}) corners.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
        Vec3 centre = Vec3::Zero();
        for (const Vec3& p : corners) centre += p / 4.0;
        std::vector<Vec3> points;
        for (const Vec3& p : corners)
            for (double z : {-kHalfDepth, kHalfDepth}) points.push_back(p - centre + Vec3(0, 0, z));
        BodyDef block;
        block.name = "block_" + std::to_string(i);
        block.shape = ShapeDef::convex(points);
        block.material = "stone";
        block.position = centre;
        c.scene.bodies.push_back(block);
    }
    keepAwake(c.scene);
    // The thrust line of a semicircular arch fits inside it when the ring is thicker than about
    // 0.11 of its mean radius (Heyman); this ring is 0.26 of it, and the joints' friction needed
    // is below 0.8. So it stands, and any motion is solver error.
    c.check = worstCheck("max block displacement", "m", 0.01,
                         "1 cm at any time: a ring 2.4 times the minimum thickness stands on friction alone",
                         "hard.arch.displacement", maxDisplacement(dynamicBodies(c.scene)));
    return c;
}

// ---- mass ratios -------------------------------------------------------------------------------

CatalogueScene plankOnBoxes() {
    CatalogueScene c = hardCase("hard_heavy_plank",
                                "100 kg plank (4 m x 0.2 m x 1 m) resting on two 1 kg boxes (0.4 m cubes): mass ratio 100; "
                                "largest displacement over 5 s",
                                5.0);
    c.scene.bodies.push_back(groundPlane());
    for (double x : {-1.5, 1.5}) {
        BodyDef box = unitBox(x < 0 ? "box_left" : "box_right", Vec3(x, 0.2, 0));
        box.shape = ShapeDef::box(Vec3(0.2, 0.2, 0.2));
        box.mass = 1.0;
        c.scene.bodies.push_back(box);
    }
    BodyDef plank = unitBox("plank", Vec3(0, 0.5, 0));
    plank.shape = ShapeDef::box(Vec3(2.0, 0.1, 0.5));
    plank.mass = 100.0;
    c.scene.bodies.push_back(plank);
    keepAwake(c.scene);
    c.check = worstCheck("max displacement", "m", 0.01,
                         "1 cm at any time: everything rests; the two contacts under each box may overlap by the 5 mm slop each",
                         "hard.heavy_plank.displacement", maxDisplacement(dynamicBodies(c.scene)));
    return c;
}

CatalogueScene lightOnHeavy() {
    CatalogueScene c = hardCase("hard_light_on_heavy",
                                "1 kg box (0.2 m cube) on a 1000 kg box (1 m cube): mass ratio 1000; largest displacement over 5 s",
                                5.0);
    c.scene.bodies.push_back(groundPlane());
    BodyDef heavy = unitBox("heavy", Vec3(0, 0.5, 0));
    heavy.mass = 1000.0;
    c.scene.bodies.push_back(heavy);
    BodyDef light = unitBox("light", Vec3(0, 1.1, 0));
    light.shape = ShapeDef::box(Vec3(0.1, 0.1, 0.1));
    light.mass = 1.0;
    c.scene.bodies.push_back(light);
    keepAwake(c.scene);
    c.check = worstCheck("max displacement", "m", 0.01, "1 cm at any time: both rest; two contacts of 5 mm slop each",
                         "hard.light_on_heavy.displacement", maxDisplacement(dynamicBodies(c.scene)));
    return c;
}

// The mirror of the above, and the harder one: the light body carries the heavy one, so its
// contacts hold a thousand times its own weight (Box2D v3's and Jolt's "heavy on light" samples).
// A solver whose contact stiffness or iteration budget is sized by the light body's mass lets the
// heavy box sink into it, or through it and the ground.
CatalogueScene heavyOnLight() {
    CatalogueScene c = hardCase("hard_heavy_on_light",
                                "1000 kg unit cube on a 1 kg unit cube on the ground: mass ratio 1000; largest "
                                "displacement over 5 s",
                                5.0);
    c.scene.bodies.push_back(groundPlane());
    BodyDef light = unitBox("light", Vec3(0, 0.5, 0));
    light.mass = 1.0;
    c.scene.bodies.push_back(light);
    BodyDef heavy = unitBox("heavy", Vec3(0, 1.5, 0));
    heavy.mass = 1000.0;
    c.scene.bodies.push_back(heavy);
    keepAwake(c.scene);
    c.check = worstCheck("max displacement", "m", 0.01,
                         "1 cm at any time, as light-on-heavy: both rest; two contacts of 5 mm slop each. A heavy box "
                         "through the light one falls a metre",
                         "hard.heavy_on_light.displacement", maxDisplacement(dynamicBodies(c.scene)));
    return c;
}

// ---- recovery, precision, speed ----------------------------------------------------------------

CatalogueScene overlap25() {
    CatalogueScene c = hardCase("hard_overlap_25",
                                "two unit boxes starting 25 % overlapped: the lower one 0.25 m into the ground, the upper "
                                "0.25 m into it; fastest speed while they are pushed apart (3 s)",
                                3.0);
    c.scene.bodies.push_back(groundPlane());
    c.scene.bodies.push_back(unitBox("lower", Vec3(0, 0.25, 0)));
    c.scene.bodies.push_back(unitBox("upper", Vec3(0, 1.0, 0)));
    keepAwake(c.scene);
    // Pushed out, not thrown: a box leaving at v rises v^2 / 2g, and sqrt(2 g 0.25) = 2.2 m/s
    // rises no higher than the 0.25 m it had to recover.
    c.check = worstCheck("max speed", "m/s", std::sqrt(2 * 9.81 * 0.25),
                         "2.2 m/s: a box pushed out faster would fly higher than the 0.25 m overlap it recovers from",
                         "hard.overlap25.speed", maxSpeed(dynamicBodies(c.scene)));
    return c;
}

CatalogueScene farStack(bool planar) {
    constexpr int kBoxes = 5;
    constexpr double kFar = 10000.0;
    const Vec3 at = planar ? Vec3(kFar, 0, 0) : Vec3(kFar, 0, kFar);
    CatalogueScene c = hardCase("hard_far_stack",
                                "5 unit boxes stacked 10 km from the origin behave as at the origin: the top box's largest "
                                "displacement over 5 s",
                                5.0);
    c.scene.bodies.push_back(groundPlane());
    for (int i = 0; i < kBoxes; ++i) c.scene.bodies.push_back(unitBox("box_" + std::to_string(i), at + Vec3(0, 0.5 + i, 0)));
    keepAwake(c.scene);
    // Up and down too: a stack that sinks through its ground far out (Box2D's plane once ended
    // 1 km from the origin) never drifts sideways.
    c.check = worstCheck("top displacement", "m", 0.01,
                         "1 cm at any time, the stack's bound at the origin: doubles resolve 10 km to 2e-12 m; five "
                         "resting contacts give a few millimetres",
                         "hard.far_stack.drift", maxDisplacement({static_cast<std::size_t>(kBoxes)}));
    if (planar) c = planarCase(c);
    return c;
}

CatalogueScene thinWall300() {
    constexpr double kWallX = 10.0, kHalfThickness = 0.05, kRadius = 0.05;
    CatalogueScene c = hardCase("hard_thin_wall_300",
                                "a 5 cm ball at 300 m/s (5 m per step) at a static wall 10 cm thick, no gravity: how far "
                                "past the wall's face its centre gets",
                                0.5);
    c.scene.settings.gravity = Vec3::Zero();
    BodyDef wall = unitBox("wall", Vec3(kWallX, 0, 0));
    wall.type = BodyType::Static;
    wall.shape = ShapeDef::box(Vec3(kHalfThickness, 2, 2));
    c.scene.bodies.push_back(wall);
    BodyDef ball = sphereBody("ball", kRadius, 0.5);
    ball.position = Vec3(0.3, 0, 0);
    ball.linearVelocity = Vec3(300, 0, 0);
    c.scene.bodies.push_back(ball);
    keepAwake(c.scene);
    const double stop = kWallX - kHalfThickness - kRadius;  // centre when the ball touches the face
    c.check = worstCheck("past the face", "m", 0.01,
                         "1 cm: the slop and a speculative gap; a ball that tunnelled is metres past",
                         "hard.thin_wall_300.penetration",
                         [stop](const std::vector<BodyState>&, const std::vector<BodyState>& now, double) {
                             const double past = now[1].position.x() - stop;
                             return past > 0 || std::isnan(past) ? past : 0.0;
                         });
    return c;
}

CatalogueScene spinningBox() {
    CatalogueScene c = hardCase("hard_spinning_box",
                                "a unit box spinning at 100 rad/s about the vertical on the ground, friction 0.6: it spins "
                                "down in place; its largest displacement over 5 s",
                                5.0);
    c.scene.bodies.push_back(groundPlane());
    BodyDef box = unitBox("box", Vec3(0, 0.5, 0));
    box.angularVelocity = Vec3(0, 100, 0);
    c.scene.bodies.push_back(box);
    keepAwake(c.scene);
    // Friction on a symmetric footprint cancels in sum: no net force, so the centre stays. The
    // corners move at 71 m/s; contacts that lose or misplace points show as a walk or a hop.
    c.check = worstCheck("max displacement", "m", 0.02,
                         "2 cm at any time: symmetric friction has no net force; the slop allows 5 mm of sinking",
                         "hard.spinning_box.displacement", maxDisplacement({1}));
    return c;
}

/// A flat 100 m square of 2 x 2 quads (8 triangles) at y = 0, facing up: wide enough that
/// nothing rolling off the heap (spheres roll on without rolling resistance) reaches its edge
/// in 5 s.
ShapeDef flatMesh() {
    constexpr double kHalf = 50.0;
    std::vector<Vec3> vertices;
    for (int z = 0; z <= 2; ++z)
        for (int x = 0; x <= 2; ++x) vertices.emplace_back(-kHalf + kHalf * x, 0.0, -kHalf + kHalf * z);
    std::vector<std::uint32_t> indices;
    for (std::uint32_t z = 0; z < 2; ++z)
        for (std::uint32_t x = 0; x < 2; ++x) {
            const std::uint32_t i = z * 3 + x;
            // Counter-clockwise seen from above: normals +y.
            indices.insert(indices.end(), {i, i + 3, i + 1, i + 1, i + 3, i + 4});
        }
    return ShapeDef::mesh(vertices, indices);
}

CatalogueScene mixedPileOnMesh() {
    CatalogueScene c = hardCase("hard_mixed_pile_mesh",
                                "16 spheres, capsules, hulls and compounds dropped in a heap on a triangle-mesh floor: how far "
                                "any sinks into the floor over 5 s",
                                5.0);
    BodyDef floor;
    floor.name = "floor";
    floor.type = BodyType::Static;
    floor.shape = flatMesh();
    c.scene.bodies.push_back(floor);
    // Each body's smallest distance from its centre to its surface: resting on the floor its
    // centre is at least this high.
    std::vector<std::pair<std::size_t, double>> reach;
    const std::vector<Vec3> octahedron{{0.3, 0, 0}, {-0.3, 0, 0}, {0, 0.3, 0}, {0, -0.3, 0}, {0, 0, 0.3}, {0, 0, -0.3}};
    const double octahedronInradius = 0.3 / std::sqrt(3.0);
    for (int i = 0; i < 16; ++i) {
        BodyDef b;
        b.name = "piece_" + std::to_string(i);
        // 0.9 m apart in height: no two pieces (at most 0.96 m long) start overlapped.
        b.position = Vec3(0.35 * ((i % 4) - 1.5), 0.6 + 0.9 * i, 0.3 * ((i / 4) % 2) - 0.15);
        b.orientation = Quat(Eigen::AngleAxisd(0.7 * i, Vec3(1, 1, 0).normalized()));
        double r = 0.0;
        switch (i % 4) {
            case 0: b.shape = ShapeDef::sphere(0.25); r = 0.25; break;
            case 1: b.shape = ShapeDef::capsule(0.15, 0.3); r = 0.15; break;
            case 2: b.shape = ShapeDef::convex(octahedron); r = octahedronInradius; break;
            default:  // a dumbbell: two balls on a bar
                b.shape = ShapeDef::compound({ShapeDef::sphere(0.18).placed(Vec3(-0.3, 0, 0)),
                                              ShapeDef::sphere(0.18).placed(Vec3(0.3, 0, 0)),
                                              ShapeDef::box(Vec3(0.3, 0.05, 0.05))});
                r = 0.05;  // the bar's half thickness: the lowest the centre can rest
                break;
        }
        reach.emplace_back(c.scene.bodies.size(), r);
        c.scene.bodies.push_back(b);
    }
    keepAwake(c.scene);
    c.check = worstCheck("deepest sink", "m", 0.02,
                         "2 cm at any time: the 5 mm slop plus a fast landing's overshoot; a body through the floor "
                         "sinks without limit",
                         "hard.mixed_pile_mesh.sink",
                         [reach](const std::vector<BodyState>&, const std::vector<BodyState>& now, double) {
                             double worst = 0.0;
                             for (const auto& [i, r] : reach) {
                                 const double sink = r - now[i].position.y();
                                 if (!(sink <= worst)) worst = sink;
                             }
                             return worst;
                         });
    return c;
}

CatalogueScene ragdollPile(bool planar) {
    constexpr int kRagdolls = 10;
    CatalogueScene c = hardCase("hard_ragdoll_pile",
                                "10 ragdolls (11 bodies, 10 joints each) dropped lying on each other: the largest joint gap "
                                "over 5 s",
                                5.0);
    c.scene.bodies.push_back(groundPlane());
    const Scene& ragdoll = builtinAssembly(planar ? "ragdoll_planar" : "ragdoll");
    for (int i = 0; i < kRagdolls; ++i) {
        // As anyphys_ragdoll --mode pile: lying, each turned another way, 0.5 m apart in height.
        const Quat lie = planar ? Quat(Eigen::AngleAxisd(0.5 * kPi * (i % 2 ? 1 : -1), Vec3::UnitZ()))
                                : Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX())) * Quat(Eigen::AngleAxisd(0.9 * i, Vec3::UnitY()));
        const Vec3 at = planar ? Vec3(0.9 * (i % 2 ? 1 : -1), 1.0 + 0.5 * i, 0) : Vec3(0.2 * (i % 3), 0.5 + 0.5 * i, -0.9);
        appendInstance(c.scene, ragdoll, Transform{at, lie}, "r" + std::to_string(i) + "/");
    }
    keepAwake(c.scene);
    SceneCheck check{"max joint gap", "m", 0.0, 0.05,
                     "5 cm at any time: a limb this far from its socket is visibly torn off", {}, "hard.ragdoll_pile.joint_gap"};
    check.makeProbe = jointGapProbe(c.scene);
    c.check = check;
    if (planar) c = planarCase(c);
    return c;
}

}  // namespace

std::vector<CatalogueScene> hardCaseScenes() {
    std::vector<CatalogueScene> all;
    all.push_back(stack20());
    all.push_back(column40());
    all.push_back(planarCase(column40()));
    all.push_back(pyramid100Planar());
    all.push_back(cardHouse());
    all.push_back(arch());
    all.push_back(planarCase(arch()));
    all.push_back(plankOnBoxes());
    all.push_back(planarCase(plankOnBoxes()));
    all.push_back(lightOnHeavy());
    all.push_back(planarCase(lightOnHeavy()));
    all.push_back(heavyOnLight());
    all.push_back(planarCase(heavyOnLight()));
    all.push_back(overlap25());
    all.push_back(planarCase(overlap25()));
    all.push_back(farStack(false));
    all.push_back(farStack(true));
    all.push_back(thinWall300());
    all.push_back(planarCase(thinWall300()));
    all.push_back(spinningBox());
    all.push_back(mixedPileOnMesh());
    all.push_back(ragdollPile(false));
    all.push_back(ragdollPile(true));
    return all;
}

}  // namespace anyphys::catalogue_parts
