#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "anyphys/containers/scene.hpp"
#include "anyphys/error.hpp"

using namespace anyphys;

namespace {

const char* kIssueExample = R"({
  "settings": { "backend": "native", "gravity": [0, -10, 0], "timeStep": 0.0166667,
                "integrator": "rk4", "solver": "pgs", "substeps": 2, "iterations": 12,
                "effects": ["gravity", "damping"], "maxStepsPerUpdate": 4,
                "capabilityPolicy": "lenient", "backendOptions": {"erp": 0.2} },
  "materials": { "rubber": { "friction": 0.9, "restitution": 0.8, "density": 1100 },
                 "ice": { "friction": 0.05 } },
  "materialRules": { "friction": "average", "restitution": "min" },
  "materialPairs": [ { "a": "rubber", "b": "ice", "friction": 0.1, "restitution": 0.2 },
                     { "a": "ice", "b": "ice", "restitution": 0.3 } ],
  "bodies": [ { "name": "ground", "type": "static",
                "shape": { "type": "plane", "normal": [0, 1, 0], "offset": -1 } },
              { "name": "ball", "type": "dynamic", "position": [0, 10, 0], "orientation": [1, 0, 0, 0],
                "linearVelocity": [10, 10, 0], "angularVelocity": [0, 0, 1],
                "shape": { "type": "sphere", "radius": 0.5 }, "mass": 1.0, "density": 1000,
                "inertia": [0.1, 0.2, 0.3], "gyroscopic": "none", "material": "rubber",
                "linearDamping": 0.1, "angularDamping": 0.2, "gravityScale": 0.5 },
              { "name": "crate", "shape": { "type": "box", "halfExtents": [1, 2, 3] } },
              { "name": "pill", "type": "kinematic", "shape": { "type": "capsule", "radius": 0.25, "halfHeight": 1 } } ],
  "joints": [] })";

// Expects parseScene(json) to throw anyphys::Error whose message contains every fragment.
void expectParseError(const std::string& json, std::initializer_list<std::string> fragments) {
    try {
        (void)parseScene(json);
        ADD_FAILURE() << "expected anyphys::Error for " << json;
    } catch (const Error& e) {
        for (const auto& part : fragments) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

// A scene with one body whose JSON is `body`.
std::string withBody(const std::string& body) { return R"({"bodies": [)" + body + "]}"; }

// Exact (bitwise for doubles) comparison of two scenes.
void expectSameVec(const Vec3& a, const Vec3& b, const std::string& what) {
    for (int i = 0; i < 3; ++i) EXPECT_EQ(a[i], b[i]) << what << "[" << i << "]";
}

void expectSameScene(const Scene& a, const Scene& b) {
    const WorldSettings &sa = a.settings, &sb = b.settings;
    EXPECT_EQ(sa.backend, sb.backend);
    expectSameVec(sa.gravity, sb.gravity, "gravity");
    EXPECT_EQ(sa.timeStep, sb.timeStep);
    EXPECT_EQ(sa.integrator, sb.integrator);
    EXPECT_EQ(sa.solver, sb.solver);
    EXPECT_EQ(sa.iterations, sb.iterations);
    EXPECT_EQ(sa.substeps, sb.substeps);
    EXPECT_EQ(sa.effects.has_value(), sb.effects.has_value());
    if (sa.effects && sb.effects) {
        EXPECT_EQ(sa.effects->bits(), sb.effects->bits());
    }
    EXPECT_EQ(sa.maxStepsPerUpdate, sb.maxStepsPerUpdate);
    EXPECT_EQ(sa.capabilityPolicy, sb.capabilityPolicy);
    EXPECT_EQ(sa.backendOptions, sb.backendOptions);

    const MaterialLibrary &ma = a.materials, &mb = b.materials;
    EXPECT_EQ(ma.names(), mb.names());
    auto names = ma.names();
    names.push_back("");
    for (const auto& n : names) {
        if (!mb.contains(n)) continue;
        EXPECT_EQ(ma.get(n).friction, mb.get(n).friction) << n;
        EXPECT_EQ(ma.get(n).restitution, mb.get(n).restitution) << n;
        EXPECT_EQ(ma.get(n).density, mb.get(n).density) << n;
    }
    EXPECT_EQ(ma.frictionRule(), mb.frictionRule());
    EXPECT_EQ(ma.restitutionRule(), mb.restitutionRule());
    ASSERT_EQ(ma.pairOverrides().size(), mb.pairOverrides().size());
    for (const auto& [key, o] : ma.pairOverrides()) {
        const auto other = mb.pairOverride(key.first, key.second);
        ASSERT_TRUE(other.has_value()) << key.first << "/" << key.second;
        EXPECT_EQ(o.friction, other->friction);
        EXPECT_EQ(o.restitution, other->restitution);
    }

    ASSERT_EQ(a.bodies.size(), b.bodies.size());
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        const BodyDef &x = a.bodies[i], &y = b.bodies[i];
        SCOPED_TRACE("body " + x.name);
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.type, y.type);
        expectSameVec(x.position, y.position, "position");
        for (int k = 0; k < 4; ++k) EXPECT_EQ(x.orientation.coeffs()[k], y.orientation.coeffs()[k]);
        expectSameVec(x.linearVelocity, y.linearVelocity, "linearVelocity");
        expectSameVec(x.angularVelocity, y.angularVelocity, "angularVelocity");
        EXPECT_EQ(x.shape.type, y.shape.type);
        EXPECT_EQ(x.shape.radius, y.shape.radius);
        expectSameVec(x.shape.halfExtents, y.shape.halfExtents, "halfExtents");
        EXPECT_EQ(x.shape.halfHeight, y.shape.halfHeight);
        expectSameVec(x.shape.normal, y.shape.normal, "normal");
        EXPECT_EQ(x.shape.offset, y.shape.offset);
        EXPECT_EQ(x.mass, y.mass);
        EXPECT_EQ(x.density, y.density);
        EXPECT_EQ(x.inertia.has_value(), y.inertia.has_value());
        if (x.inertia && y.inertia) {
            expectSameVec(*x.inertia, *y.inertia, "inertia");
        }
        EXPECT_EQ(x.material, y.material);
        EXPECT_EQ(x.linearDamping, y.linearDamping);
        EXPECT_EQ(x.angularDamping, y.angularDamping);
        EXPECT_EQ(x.gravityScale, y.gravityScale);
        EXPECT_EQ(x.gyroscopic, y.gyroscopic);
    }
}

std::string tempPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("anyphys_test_" + std::to_string(::getpid()) + "_" + name)).string();
}

}  // namespace

TEST(SceneJson, ParsesEveryField) {
    const Scene s = parseScene(kIssueExample);
    EXPECT_EQ(s.settings.backend, "native");
    EXPECT_EQ(s.settings.gravity, Vec3(0, -10, 0));
    EXPECT_EQ(s.settings.timeStep, 0.0166667);
    EXPECT_EQ(s.settings.integrator, Integrator::RK4);
    EXPECT_EQ(s.settings.solver, Solver::ProjectedGaussSeidel);
    EXPECT_EQ(s.settings.substeps, 2);
    EXPECT_EQ(s.settings.iterations, 12);
    ASSERT_TRUE(s.settings.effects.has_value());
    EXPECT_EQ(*s.settings.effects, Effect::Gravity | Effect::Damping);
    EXPECT_EQ(s.settings.maxStepsPerUpdate, 4);
    EXPECT_EQ(s.settings.capabilityPolicy, CapabilityPolicy::Lenient);
    EXPECT_EQ(s.settings.backendOptions.at("erp"), 0.2);

    EXPECT_EQ(s.materials.names(), (std::vector<std::string>{"ice", "rubber"}));
    EXPECT_EQ(s.materials.get("rubber").density, 1100);
    EXPECT_EQ(s.materials.get("ice").friction, 0.05);
    EXPECT_EQ(s.materials.get("ice").restitution, Material{}.restitution);  // absent: default
    EXPECT_EQ(s.materials.frictionRule(), CombineRule::Average);
    EXPECT_EQ(s.materials.restitutionRule(), CombineRule::Min);
    EXPECT_EQ(s.materials.resolve("ice", "rubber").friction, 0.1);
    EXPECT_EQ(s.materials.resolve("ice", "rubber").restitution, 0.2);
    EXPECT_EQ(s.materials.resolve("ice", "ice").restitution, 0.3);
    EXPECT_EQ(s.materials.resolve("ice", "ice").friction, 0.05);  // average of equal values

    ASSERT_EQ(s.bodies.size(), 4u);
    const BodyDef& ground = s.bodies[0];
    EXPECT_EQ(ground.name, "ground");
    EXPECT_EQ(ground.type, BodyType::Static);
    EXPECT_EQ(ground.shape.type, ShapeType::Plane);
    EXPECT_EQ(ground.shape.normal, Vec3(0, 1, 0));
    EXPECT_EQ(ground.shape.offset, -1);

    const BodyDef& ball = s.bodies[1];
    EXPECT_EQ(ball.type, BodyType::Dynamic);
    EXPECT_EQ(ball.position, Vec3(0, 10, 0));
    EXPECT_EQ(ball.orientation.w(), 1);
    EXPECT_EQ(ball.linearVelocity, Vec3(10, 10, 0));
    EXPECT_EQ(ball.angularVelocity, Vec3(0, 0, 1));
    EXPECT_EQ(ball.shape.type, ShapeType::Sphere);
    EXPECT_EQ(ball.shape.radius, 0.5);
    EXPECT_EQ(ball.mass, 1.0);
    EXPECT_EQ(ball.density, 1000.0);
    ASSERT_TRUE(ball.inertia.has_value());
    EXPECT_EQ(*ball.inertia, Vec3(0.1, 0.2, 0.3));
    EXPECT_EQ(ball.gyroscopic, GyroscopicMode::None);
    EXPECT_EQ(ball.material, "rubber");
    EXPECT_EQ(ball.linearDamping, 0.1);
    EXPECT_EQ(ball.angularDamping, 0.2);
    EXPECT_EQ(ball.gravityScale, 0.5);

    EXPECT_EQ(s.bodies[2].shape.type, ShapeType::Box);
    EXPECT_EQ(s.bodies[2].shape.halfExtents, Vec3(1, 2, 3));
    EXPECT_EQ(s.bodies[3].type, BodyType::Kinematic);
    EXPECT_EQ(s.bodies[3].shape.type, ShapeType::Capsule);
    EXPECT_EQ(s.bodies[3].shape.radius, 0.25);
    EXPECT_EQ(s.bodies[3].shape.halfHeight, 1.0);
}

TEST(SceneJson, AbsentKeysTakeTheDefsDefaults) {
    const Scene s = parseScene(withBody(R"({"name": "b", "shape": {"type": "sphere"}})"));
    const WorldSettings d;
    EXPECT_EQ(s.settings.backend, d.backend);
    EXPECT_EQ(s.settings.gravity, d.gravity);
    EXPECT_EQ(s.settings.timeStep, d.timeStep);
    EXPECT_EQ(s.settings.integrator, d.integrator);
    EXPECT_EQ(s.settings.solver, d.solver);
    EXPECT_EQ(s.settings.iterations, d.iterations);
    EXPECT_EQ(s.settings.substeps, d.substeps);
    EXPECT_FALSE(s.settings.effects.has_value());  // absent: derived from content later
    EXPECT_EQ(s.settings.maxStepsPerUpdate, d.maxStepsPerUpdate);
    EXPECT_EQ(s.settings.capabilityPolicy, CapabilityPolicy::Strict);
    EXPECT_TRUE(s.settings.backendOptions.empty());
    EXPECT_TRUE(s.materials.names().empty());
    EXPECT_EQ(s.materials.frictionRule(), CombineRule::GeometricMean);
    EXPECT_EQ(s.materials.restitutionRule(), CombineRule::Max);

    ASSERT_EQ(s.bodies.size(), 1u);
    const BodyDef& b = s.bodies[0];
    const BodyDef db;
    EXPECT_EQ(b.type, db.type);
    EXPECT_EQ(b.position, db.position);
    EXPECT_TRUE(b.orientation.isApprox(db.orientation, 0));
    EXPECT_EQ(b.shape.radius, db.shape.radius);
    EXPECT_FALSE(b.mass || b.density || b.inertia);
    EXPECT_EQ(b.material, "");
    EXPECT_EQ(b.gravityScale, db.gravityScale);
    EXPECT_EQ(b.gyroscopic, db.gyroscopic);

    // An empty document is an empty scene; an empty effects list means "simulate nothing".
    EXPECT_TRUE(parseScene("{}").bodies.empty());
    const Scene none = parseScene(R"({"settings": {"effects": []}})");
    ASSERT_TRUE(none.settings.effects.has_value());
    EXPECT_TRUE(none.settings.effects->empty());
}

TEST(SceneJson, IntegersAcceptedForDoublesAndWholeDoublesForCounts) {
    const Scene s = parseScene(R"({"settings": {"timeStep": 1, "substeps": 4.0, "gravity": [0, -10, 0]}})");
    EXPECT_EQ(s.settings.timeStep, 1.0);
    EXPECT_EQ(s.settings.substeps, 4);
}

TEST(SceneJson, RoundTripReproducesTheSceneExactly) {
    Scene s = parseScene(kIssueExample);
    // Awkward doubles: none of these survive a printf("%g") or a 15-digit round trip.
    s.settings.timeStep = 1.0 / 60.0;
    s.settings.gravity = Vec3(std::numbers::pi, -9.81, std::nextafter(1.0, 2.0));
    s.settings.backendOptions["cfm"] = 1e-300;
    s.materials.add("", Material{0.3, 0.1, 1.0 / 3.0});  // a changed default material is saved too
    s.bodies[1].position = Vec3(0.1, 0.2 + 0.1, -0.0);
    s.bodies[1].orientation = Quat(std::sqrt(0.5), 0, 0, std::sqrt(0.5));
    s.bodies[1].mass = std::numeric_limits<double>::denorm_min();
    s.bodies[2].material = "";
    s.bodies[2].inertia.reset();

    const std::string text = sceneToJson(s);
    const Scene back = parseScene(text);
    expectSameScene(s, back);
    EXPECT_TRUE(std::signbit(back.bodies[1].position.z()));  // -0.0 stays -0.0
    EXPECT_EQ(sceneToJson(back), text);                     // and the text is stable

    // Unset optionals stay unset.
    EXPECT_FALSE(back.bodies[0].mass.has_value());
    EXPECT_FALSE(back.bodies[2].inertia.has_value());
}

TEST(SceneJson, RoundTripOfDefaultsAndUnsetEffects) {
    Scene s;
    BodyDef b;
    b.name = "only";
    s.bodies.push_back(b);
    const std::string text = sceneToJson(s);
    EXPECT_EQ(text.find("\"effects\""), std::string::npos);  // unset: derived, so not written
    EXPECT_EQ(text.find("\"mass\""), std::string::npos);
    EXPECT_NE(text.find("\"position\": [0.0, 0.0, 0.0]"), std::string::npos) << text;  // vectors stay on one line
    expectSameScene(s, parseScene(text));
}

TEST(SceneJson, ErrorsNamePathValueAndRule) {
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "sphere", "radius": -1}})"),
                     {"bodies[0].shape.radius: must be > 0, got -1"});
    expectParseError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere"}}, {"name": "b", "position": "abc", "shape": {"type": "sphere"}}]})",
                     {"bodies[1].position: must be an array of 3 numbers, got \"abc\""});
    expectParseError(withBody(R"({"name": "b", "position": [1, 2], "shape": {"type": "sphere"}})"),
                     {"bodies[0].position: must be an array of 3 numbers, got [1,2]"});
    expectParseError(R"({"settings": {"integrator": "leapfrog"}})",
                     {"settings.integrator: must be one of explicit_euler, semi_implicit_euler, verlet, midpoint, rk4, "
                      "got \"leapfrog\""});
    expectParseError(R"({"settings": {"solver": 3}})", {"settings.solver: must be one of soft_step, pgs, direct, got 3"});
    expectParseError(R"({"settings": {"capabilityPolicy": "loose"}})", {"settings.capabilityPolicy", "strict, lenient", "\"loose\""});
    expectParseError(R"({"settings": {"effects": ["gravity", "magnetism"]}})",
                     {"settings.effects[1]: must be one of gravity, damping", "got \"magnetism\""});
    expectParseError(R"({"settings": {"substeps": 0}})", {"settings.substeps: must be an integer >= 1, got 0"});
    expectParseError(R"({"settings": {"iterations": 2.5}})", {"settings.iterations: must be an integer >= 1, got 2.5"});
    expectParseError(R"({"settings": {"timeStep": 0}})", {"settings.timeStep: must be > 0, got 0"});
    expectParseError(R"({"settings": {"backend": ""}})", {"settings.backend", "must name a backend"});
    expectParseError(R"({"settings": {"backendOptions": {"erp": "high"}}})",
                     {"settings.backendOptions.erp: must be a number, got \"high\""});
    expectParseError(R"({"materials": {"rubber": {"friction": -0.5}}})", {"materials.rubber.friction: must be >= 0, got -0.5"});
    expectParseError(R"({"materials": {"rubber": {"restitution": 1.5}}})",
                     {"materials.rubber.restitution: must be in [0, 1], got 1.5"});
    expectParseError(R"({"materials": {"rubber": {"density": 0}}})", {"materials.rubber.density: must be > 0, got 0"});
    expectParseError(R"({"materialRules": {"friction": "median"}})",
                     {"materialRules.friction: must be one of average, min, max, multiply, geometric_mean, got \"median\""});
    expectParseError(withBody(R"({"name": "b", "type": "ghost", "shape": {"type": "sphere"}})"),
                     {"bodies[0].type: must be one of static, kinematic, dynamic, got \"ghost\""});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "cone"}})"),
                     {"bodies[0].shape.type: must be one of sphere, box, capsule, plane, got \"cone\""});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "box", "halfExtents": [1, 0, 1]}})"),
                     {"bodies[0].shape.halfExtents[1]: must be > 0, got 0"});
    expectParseError(withBody(R"({"name": "b", "orientation": [1, 1, 0, 0], "shape": {"type": "sphere"}})"),
                     {"bodies[0].orientation", "unit quaternion"});
    expectParseError(withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "plane"}})"),
                     {"bodies[0].shape.type", "only on static bodies"});
    expectParseError(withBody(R"({"name": "b", "mass": -2, "shape": {"type": "sphere"}})"),
                     {"bodies[0].mass: must be > 0, got -2"});
    expectParseError(withBody(R"({"name": "b", "gyroscopic": "implicitly", "shape": {"type": "sphere"}})"),
                     {"bodies[0].gyroscopic: must be one of none, explicit, implicit"});
    expectParseError(R"({"bodies": {"name": "b"}})", {"bodies: must be an array of body objects"});
    expectParseError("[1, 2]", {"scene: must be a JSON object", "got [1,2]"});
}

TEST(SceneJson, NamesAreRequiredNonEmptyAndUnique) {
    expectParseError(withBody(R"({"shape": {"type": "sphere"}})"), {"bodies[0].name: required key is missing"});
    expectParseError(withBody(R"({"name": "", "shape": {"type": "sphere"}})"),
                     {"bodies[0].name: must be a non-empty string, got \"\""});
    expectParseError(withBody(R"({"name": 7, "shape": {"type": "sphere"}})"), {"bodies[0].name: must be a string, got 7"});
    expectParseError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere"}}, {"name": "a", "shape": {"type": "box"}}]})",
                     {"bodies[1].name: must be unique (already used by bodies[0]), got \"a\""});
    expectParseError(withBody(R"({"name": "b"})"), {"bodies[0].shape: required key is missing"});
    expectParseError(withBody(R"({"name": "b", "shape": {"radius": 1}})"),
                     {"bodies[0].shape.type: required key is missing", "sphere, box, capsule, plane"});
}

TEST(SceneJson, UnknownAndDuplicateKeysAreErrors) {
    expectParseError(withBody(R"({"name": "b", "radius": 1, "shape": {"type": "sphere"}})"),
                     {"bodies[0].radius: unknown key; allowed keys are name, type, position"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "sphere", "halfExtents": [1, 1, 1]}})"),
                     {"bodies[0].shape.halfExtents: unknown key for a sphere shape; allowed keys are type, radius"});
    expectParseError(R"({"settings": {"timestep": 0.01}})", {"settings.timestep: unknown key", "timeStep"});
    expectParseError(R"({"setings": {}})", {"setings: unknown key at the top level; allowed keys are settings"});
    expectParseError(R"({"materials": {"rubber": {"frction": 1}}})", {"materials.rubber.frction: unknown key"});
    expectParseError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere"}},
                                     {"name": "b", "shape": {"type": "sphere", "radius": 1, "radius": 2}}]})",
                     {"bodies[1].shape.radius: duplicate key"});
}

TEST(SceneJson, MaterialReferencesMustBeKnown) {
    expectParseError(R"({"materials": {"rubber": {}, "ice": {}},
                        "bodies": [{"name": "b", "material": "steel", "shape": {"type": "sphere"}}]})",
                     {"bodies[0].material", "\"steel\"", "\"\" (the default), ice, rubber"});
    expectParseError(R"({"materials": {"rubber": {}}, "materialPairs": [{"a": "rubber", "b": "steel"}]})",
                     {"materialPairs[0].b", "\"steel\"", "rubber"});
    expectParseError(R"({"materials": {"rubber": {}}, "materialPairs": [{"a": "rubber"}]})",
                     {"materialPairs[0].b: required key is missing"});
    expectParseError(R"({"materials": {"rubber": {}}, "materialPairs": [{"a": "rubber", "b": "rubber", "friction": -1}]})",
                     {"materialPairs[0].friction: must be >= 0, got -1"});
    expectParseError(R"({"materials": {"rubber": {}, "ice": {}},
                        "materialPairs": [{"a": "rubber", "b": "ice"}, {"a": "ice", "b": "rubber"}]})",
                     {"materialPairs[1]: duplicate pair", "materialPairs[0]"});
    // The default material "" is always known, and may be redefined.
    const Scene s = parseScene(R"({"materials": {"": {"friction": 0.2}},
                                   "bodies": [{"name": "b", "material": "", "shape": {"type": "sphere"}}]})");
    EXPECT_EQ(s.materials.get("").friction, 0.2);
}

TEST(SceneJson, JointsMustBeEmptyForNow) {
    EXPECT_NO_THROW((void)parseScene(R"({"joints": []})"));
    expectParseError(R"({"joints": [{"type": "hinge"}, {"type": "ball"}]})", {"joints:", "not supported yet", "got 2 entries"});
    expectParseError(R"({"joints": {}})", {"joints: must be an array"});
}

TEST(SceneJson, SyntaxErrorsGiveLineAndColumn) {
    expectParseError("{\n  \"bodies\": [\n    }\n", {"scene: invalid JSON at line 3, column 5"});
    expectParseError("", {"scene: invalid JSON at line 1, column 1"});
    expectParseError(R"({"settings": {"timeStep": 1e400}})", {"scene: invalid JSON", "1e400"});
}

TEST(SceneJson, SaveAndLoadFiles) {
    const std::string path = tempPath("scene.json");
    const Scene s = parseScene(kIssueExample);
    saveScene(s, path);
    expectSameScene(s, loadScene(path));
    std::filesystem::remove(path);
}

TEST(SceneJson, LoadErrorsStartWithTheFilePath) {
    const std::string path = tempPath("bad.json");
    {
        std::ofstream out(path);
        out << withBody(R"({"name": "b", "shape": {"type": "sphere", "radius": -1}})");
    }
    try {
        (void)loadScene(path);
        ADD_FAILURE() << "expected anyphys::Error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), path + ": bodies[0].shape.radius: must be > 0, got -1");
    }
    {
        std::ofstream out(path);
        out << "{\n  oops\n}";
    }
    try {
        (void)loadScene(path);
        ADD_FAILURE() << "expected anyphys::Error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ": invalid JSON at line 2, column 3", 0), 0u) << e.what();
    }
    std::filesystem::remove(path);

    const std::string absent = tempPath("no_such_scene.json");
    try {
        (void)loadScene(absent);
        ADD_FAILURE() << "expected anyphys::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(absent + ": cannot read scene file"), std::string::npos) << e.what();
    }
    EXPECT_THROW(saveScene(Scene{}, absent + "/no_such_dir/x.json"), Error);
}
