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
                "maxSpeed": 250, "maxAngularSpeed": 400, "divergencePolicy": "freeze",
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

// Exact (bitwise for doubles) comparison of two scenes. A size a shape type does not use stays
// unset (kUnset, NaN) on both sides, which counts as the same.
bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }
void expectSameVec(const Vec3& a, const Vec3& b, const std::string& what) {
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(same(a[i], b[i])) << what << "[" << i << "]: " << a[i] << " vs " << b[i];
}

void expectSameQuat(const Quat& a, const Quat& b, const std::string& what) {
    for (int k = 0; k < 4; ++k) EXPECT_EQ(a.coeffs()[k], b.coeffs()[k]) << what << " coeff " << k;
}

void expectSameShape(const ShapeDef& x, const ShapeDef& y, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_EQ(x.type, y.type);
    EXPECT_TRUE(same(x.radius, y.radius)) << x.radius << " vs " << y.radius;
    expectSameVec(x.halfExtents, y.halfExtents, "halfExtents");
    EXPECT_TRUE(same(x.halfHeight, y.halfHeight)) << x.halfHeight << " vs " << y.halfHeight;
    expectSameVec(x.normal, y.normal, "normal");
    EXPECT_EQ(x.offset, y.offset);
    ASSERT_EQ(x.points.size(), y.points.size());
    for (std::size_t i = 0; i < x.points.size(); ++i) expectSameVec(x.points[i], y.points[i], "points");
    ASSERT_EQ(x.vertices.size(), y.vertices.size());
    for (std::size_t i = 0; i < x.vertices.size(); ++i) expectSameVec(x.vertices[i], y.vertices[i], "vertices");
    EXPECT_EQ(x.indices, y.indices);
    ASSERT_EQ(x.shapes.size(), y.shapes.size());
    for (std::size_t i = 0; i < x.shapes.size(); ++i)
        expectSameShape(x.shapes[i], y.shapes[i], what + ".shapes[" + std::to_string(i) + "]");
    expectSameVec(x.position, y.position, "shape position");
    expectSameQuat(x.orientation, y.orientation, "shape orientation");
    EXPECT_EQ(x.density, y.density);
    EXPECT_EQ(x.material, y.material);
    EXPECT_EQ(x.isTrigger, y.isTrigger);
    EXPECT_EQ(x.layer, y.layer);
    EXPECT_EQ(x.mask, y.mask);
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
    EXPECT_EQ(sa.contactHertz, sb.contactHertz);
    EXPECT_EQ(sa.contactDampingRatio, sb.contactDampingRatio);
    EXPECT_EQ(sa.contactPushMaxVelocity, sb.contactPushMaxVelocity);
    EXPECT_EQ(sa.baumgarte, sb.baumgarte);
    EXPECT_EQ(sa.restitutionThreshold, sb.restitutionThreshold);
    EXPECT_EQ(sa.linearSlop, sb.linearSlop);
    EXPECT_EQ(sa.speculativeDistance, sb.speculativeDistance);
    EXPECT_EQ(sa.sleepLinearVelocity, sb.sleepLinearVelocity);
    EXPECT_EQ(sa.sleepAngularVelocity, sb.sleepAngularVelocity);
    EXPECT_EQ(sa.timeToSleep, sb.timeToSleep);
    EXPECT_EQ(sa.maxStepsPerUpdate, sb.maxStepsPerUpdate);
    EXPECT_EQ(sa.maxSpeed, sb.maxSpeed);
    EXPECT_EQ(sa.maxAngularSpeed, sb.maxAngularSpeed);
    EXPECT_EQ(sa.divergencePolicy, sb.divergencePolicy);
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
        expectSameShape(x.shape, y.shape, "shape");
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
        EXPECT_EQ(x.isTrigger, y.isTrigger);
        EXPECT_EQ(x.layer, y.layer);
        EXPECT_EQ(x.mask, y.mask);
        EXPECT_EQ(x.allowSleep, y.allowSleep);
        EXPECT_EQ(x.isAwake, y.isAwake);
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
    EXPECT_EQ(s.settings.maxSpeed, 250);
    EXPECT_EQ(s.settings.maxAngularSpeed, 400);
    EXPECT_EQ(s.settings.divergencePolicy, DivergencePolicy::Freeze);
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
    const Scene s = parseScene(withBody(R"({"name": "b", "shape": {"type": "sphere", "radius": 0.5}})"));
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
    EXPECT_EQ(s.settings.maxSpeed, kDefaultMaxSpeed);
    EXPECT_EQ(s.settings.maxAngularSpeed, kDefaultMaxAngularSpeed);
    EXPECT_EQ(s.settings.divergencePolicy, DivergencePolicy::Throw);
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
    EXPECT_EQ(b.shape.radius, 0.5);  // given: a shape's sizes have no default
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
    b.shape = ShapeDef::sphere(0.5);
    s.bodies.push_back(b);
    const std::string text = sceneToJson(s);
    EXPECT_EQ(text.find("\"effects\""), std::string::npos);  // unset: derived, so not written
    EXPECT_EQ(text.find("\"contactImpulses\""), std::string::npos);  // the default is not written
    EXPECT_EQ(text.find("\"mass\""), std::string::npos);
    EXPECT_NE(text.find("\"position\": [0.0, 0.0, 0.0]"), std::string::npos) << text;  // vectors stay on one line
    expectSameScene(s, parseScene(text));
}

TEST(SceneJson, ErrorsNamePathValueAndRule) {
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "sphere", "radius": -1}})"),
                     {"bodies[0].shape.radius: must be > 0, got -1"});
    expectParseError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.5}}, {"name": "b", "position": "abc", "shape": {"type": "sphere", "radius": 0.5}}]})",
                     {"bodies[1].position: must be an array of 3 numbers, got \"abc\""});
    expectParseError(withBody(R"({"name": "b", "position": [1, 2], "shape": {"type": "sphere", "radius": 0.5}})"),
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
    // A value is quoted as the file gave it, the shortest text of the same double (17 digits
    // printed -0.10000000000000001).
    expectParseError(R"({"materials": {"rubber": {"friction": -0.1}}})", {"materials.rubber.friction: must be >= 0, got -0.1"});
    expectParseError(R"({"materials": {"rubber": {"restitution": 1.5}}})",
                     {"materials.rubber.restitution: must be in [0, 1], got 1.5"});
    expectParseError(R"({"materials": {"rubber": {"density": 0}}})", {"materials.rubber.density: must be > 0, got 0"});
    expectParseError(R"({"materialRules": {"friction": "median"}})",
                     {"materialRules.friction: must be one of average, min, max, multiply, geometric_mean, got \"median\""});
    expectParseError(withBody(R"({"name": "b", "type": "ghost", "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].type: must be one of static, kinematic, dynamic, got \"ghost\""});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "cone"}})"),
                     {"bodies[0].shape.type: must be one of sphere, box, capsule, plane, convex, mesh, compound, got \"cone\""});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "box", "halfExtents": [1, 0, 1]}})"),
                     {"bodies[0].shape.halfExtents[1]: must be > 0, got 0"});
    expectParseError(withBody(R"({"name": "b", "orientation": [1, 1, 0, 0], "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].orientation", "unit quaternion"});
    expectParseError(withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "plane", "normal": [0, 1, 0]}})"),
                     {"bodies[0].shape.type", "only on static bodies"});
    expectParseError(withBody(R"({"name": "b", "mass": -2, "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].mass: must be > 0, got -2"});
    expectParseError(withBody(R"({"name": "b", "gyroscopic": "implicitly", "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].gyroscopic: must be one of none, explicit, implicit"});
    expectParseError(R"({"bodies": {"name": "b"}})", {"bodies: must be an array of body objects"});
    expectParseError("[1, 2]", {"scene: must be a JSON object", "got [1,2]"});
}

TEST(SceneJson, NamesAreRequiredNonEmptyAndUnique) {
    expectParseError(withBody(R"({"shape": {"type": "sphere", "radius": 0.5}})"), {"bodies[0].name: required key is missing"});
    expectParseError(withBody(R"({"name": "", "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].name: must be a non-empty string, got \"\""});
    expectParseError(withBody(R"({"name": 7, "shape": {"type": "sphere", "radius": 0.5}})"), {"bodies[0].name: must be a string, got 7"});
    expectParseError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.5}}, {"name": "a", "shape": {"type": "box", "halfExtents": [0.5, 0.5, 0.5]}}]})",
                     {"bodies[1].name: must be unique (already used by bodies[0]), got \"a\""});
    expectParseError(withBody(R"({"name": "b"})"), {"bodies[0].shape: required key is missing"});
    expectParseError(withBody(R"({"name": "b", "shape": {"radius": 1}})"),
                     {"bodies[0].shape.type: required key is missing", "sphere, box, capsule, plane"});
}

// Names are written as they are into the tool's CSV and reports: a NUL or a line break there would
// corrupt the output, so the loader refuses control characters in every string it reads.
TEST(SceneJson, NamesHoldNoControlCharacters) {
    expectParseError(withBody(R"({"name": "a\u0000b", "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].name: must not hold control characters (found U+0000 at byte 1), got \"a\\u0000b\""});
    expectParseError(withBody(R"({"name": "a\n", "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].name", "found U+000A at byte 1"});
    expectParseError(withBody(R"({"name": "\u007f", "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].name", "found U+007F at byte 0"});
    expectParseError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.5}}],
                         "joints": [{"name": "j\t", "type": "ball", "bodyB": "a"}]})",
                     {"joints[0].name", "found U+0009 at byte 1"});
    expectParseError(R"({"instances": [{"scene": "ragdoll", "prefix": "r\u001b/"}]})",
                     {"instances[0].prefix", "found U+001B at byte 1"});
    // Text beyond ASCII (UTF-8 bytes >= 0x80) and spaces stay names.
    const Scene s = parseScene(withBody(R"({"name": "Kiste \u00e4 1", "shape": {"type": "sphere", "radius": 0.5}})"));
    EXPECT_EQ(s.bodies.at(0).name, "Kiste \u00e4 1");
}

TEST(SceneJson, UnknownAndDuplicateKeysAreErrors) {
    expectParseError(withBody(R"({"name": "b", "radius": 1, "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].radius: unknown key; allowed keys are name, type, position"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "sphere", "halfExtents": [1, 1, 1]}})"),
                     {"bodies[0].shape.halfExtents: unknown key for a sphere shape; allowed keys are type, radius"});
    expectParseError(R"({"settings": {"timestep": 0.01}})", {"settings.timestep: unknown key", "timeStep"});
    expectParseError(R"({"setings": {}})", {"setings: unknown key at the top level; allowed keys are settings"});
    expectParseError(R"({"materials": {"rubber": {"frction": 1}}})", {"materials.rubber.frction: unknown key"});
    expectParseError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.5}},
                                     {"name": "b", "shape": {"type": "sphere", "radius": 1, "radius": 2}}]})",
                     {"bodies[1].shape.radius: duplicate key"});
}

TEST(SceneJson, MaterialReferencesMustBeKnown) {
    expectParseError(R"({"materials": {"rubber": {}, "ice": {}},
                        "bodies": [{"name": "b", "material": "steel", "shape": {"type": "sphere", "radius": 0.5}}]})",
                     {"bodies[0].material", "\"steel\"", "\"\" (the default), ice, rubber"});
    expectParseError(R"({"materials": {"rubber": {}}, "materialPairs": [{"a": "rubber", "b": "steel"}]})",
                     {"materialPairs[0].b", "\"steel\"", "rubber"});
    expectParseError(R"({"materials": {"rubber": {}}, "materialPairs": [{"a": "rubber"}]})",
                     {"materialPairs[0].b: required key is missing"});
    expectParseError(R"({"materials": {"rubber": {}}, "materialPairs": [{"a": "rubber", "b": "rubber", "friction": -1}]})",
                     {"materialPairs[0].friction: must be >= 0, got -1"});
    expectParseError(R"({"materials": {"rubber": {}, "ice": {}},
                        "materialPairs": [{"a": "rubber", "b": "ice"}, {"a": "ice", "b": "rubber"}]})",
                     {"materialPairs[1]: duplicate pair (\"ice\", \"rubber\")", "materialPairs[0]"});
    // The default material's empty name is quoted too, not left as "(, rubber)".
    expectParseError(R"({"materials": {"rubber": {}},
                        "materialPairs": [{"a": "", "b": "rubber"}, {"a": "rubber", "b": ""}]})",
                     {"materialPairs[1]: duplicate pair (\"rubber\", \"\")"});
    // The default material "" is always known, and may be redefined.
    const Scene s = parseScene(R"({"materials": {"": {"friction": 0.2}},
                                   "bodies": [{"name": "b", "material": "", "shape": {"type": "sphere", "radius": 0.5}}]})");
    EXPECT_EQ(s.materials.get("").friction, 0.2);
}

// Two bodies and one joint of every type, as the scene format names their fields.
constexpr const char* kJointScene = R"({
  "bodies": [
    {"name": "arm", "position": [0, 1, 0], "shape": {"type": "box", "halfExtents": [0.5, 0.1, 0.1]}},
    {"name": "hand", "position": [1, 1, 0], "shape": {"type": "sphere", "radius": 0.1}}],
  "joints": [
    {"name": "elbow", "type": "hinge", "bodyA": "arm", "bodyB": "hand", "anchor": [0.5, 1, 0], "axis": [0, 0, 1],
     "collideConnected": true, "limits": {"lower": 0.0, "upper": 2.5}, "motor": {"speed": 1.0, "maxForce": 20.0},
     "spring": {"stiffness": 50.0, "damping": 2.0}, "breakForce": 1e4, "breakTorque": 1e3},
    {"type": "ball", "bodyA": "world", "bodyB": "arm", "anchor": [-0.5, 1, 0]},
    {"name": "rope", "type": "distance", "bodyB": "hand", "anchorA": [1, 3, 0], "anchorB": [1, 1, 0],
     "minLength": 0.5, "maxLength": 2.5, "spring": {"hertz": 2, "dampingRatio": 0.5}},
    {"name": "hip", "type": "cone", "bodyA": "arm", "bodyB": "hand", "anchor": [1, 1, 0], "axis": [1, 0, 0],
     "swingLimit": 0.7, "twistLimits": {"lower": -0.2, "upper": 0.3}},
    {"name": "wheel", "type": "wheel", "bodyA": "arm", "bodyB": "hand", "anchor": [1, 1, 0], "axis": [0, 1, 0],
     "spinAxis": [0, 0, 1], "steering": true, "limits": {"lower": -0.1, "upper": 0.1}},
    {"name": "rail", "type": "slider", "bodyB": "hand", "anchor": [1, 1, 0], "axis": [1, 0, 0]},
    {"name": "weld", "type": "fixed", "bodyA": "arm", "bodyB": "hand", "anchor": [0.5, 1, 0]}]
})";

TEST(SceneJson, JointsParseWithTheirFields) {
    const Scene s = parseScene(kJointScene);
    ASSERT_EQ(s.joints.size(), 7u);
    const SceneJoint& elbow = s.joints[0];
    EXPECT_EQ(elbow.def.name, "elbow");
    EXPECT_EQ(elbow.def.type, JointType::Hinge);
    EXPECT_EQ(elbow.bodyA, "arm");
    EXPECT_EQ(elbow.bodyB, "hand");
    EXPECT_EQ(elbow.def.anchor, Vec3(0.5, 1, 0));
    ASSERT_TRUE(elbow.def.limits && elbow.def.motor && elbow.def.spring);
    EXPECT_EQ(elbow.def.limits->upper, 2.5);
    EXPECT_EQ(elbow.def.motor->maxForce, 20.0);
    EXPECT_EQ(elbow.def.spring->damping, 2.0);
    EXPECT_EQ(elbow.def.breakForce, 1e4);
    EXPECT_TRUE(elbow.def.collideConnected);
    EXPECT_EQ(s.joints[1].bodyA, "");  // "world"
    EXPECT_EQ(s.joints[2].def.maxLength, 2.5);
    EXPECT_EQ(s.joints[2].def.spring->hertz, 2.0);
    EXPECT_EQ(s.joints[3].def.twistLimits->lower, -0.2);
    EXPECT_TRUE(s.joints[4].def.steering);
}

TEST(SceneJson, JointsRoundTrip) {
    const Scene s = parseScene(kJointScene);
    const Scene back = parseScene(sceneToJson(s));
    ASSERT_EQ(back.joints.size(), s.joints.size());
    for (std::size_t i = 0; i < s.joints.size(); ++i) {
        const JointDef &a = s.joints[i].def, &b = back.joints[i].def;
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.type, b.type);
        EXPECT_EQ(s.joints[i].bodyA, back.joints[i].bodyA);
        EXPECT_EQ(s.joints[i].bodyB, back.joints[i].bodyB);
        EXPECT_EQ(a.anchor, b.anchor);
        EXPECT_EQ(a.axis, b.axis);
        EXPECT_EQ(a.anchorA, b.anchorA);
        EXPECT_EQ(a.minLength, b.minLength);
        EXPECT_EQ(a.swingLimit, b.swingLimit);
        EXPECT_EQ(a.limits.has_value(), b.limits.has_value());
        EXPECT_EQ(a.motor.has_value(), b.motor.has_value());
        EXPECT_EQ(a.spring.has_value(), b.spring.has_value());
        EXPECT_EQ(a.breakForce, b.breakForce);
        EXPECT_EQ(a.steering, b.steering);
        EXPECT_EQ(a.collideConnected, b.collideConnected);
    }
}

TEST(SceneJson, JointErrorsNameTheJsonPath) {
    const std::string bodies = R"("bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}},
                                             {"name": "b", "shape": {"type": "sphere", "radius": 1}}])";
    const auto scene = [&](const std::string& joint) { return "{" + bodies + R"(, "joints": [)" + joint + "]}"; };
    expectParseError(scene(R"({"type": "hinge", "bodyB": "shin"})"), {"joints[0].bodyB: no body named \"shin\""});
    expectParseError(scene(R"({"type": "hinge", "bodyB": "a", "limits": {"lower": 1.2, "upper": 0.4}})"),
                     {"joints[0].limits", "lower must be <= upper", "1.2", "0.4"});
    expectParseError(scene(R"({"type": "screw", "bodyB": "a"})"), {"joints[0].type", "screw"});
    expectParseError(scene(R"({"bodyB": "a"})"), {"joints[0].type"});
    expectParseError(scene(R"({"type": "ball"})"), {"joints[0].bodyB"});
    expectParseError(scene(R"({"type": "ball", "bodyA": "a", "bodyB": "a"})"), {"joints[0].bodyB", "must differ"});
    expectParseError(scene(R"({"type": "ball", "bodyB": "a", "motor": {"speed": 1, "maxForce": 1}})"),
                     {"joints[0].motor"});
    expectParseError(scene(R"({"type": "ball", "bodyB": "a", "lenght": 1})"), {"joints[0]", "lenght"});
    expectParseError(scene(R"({"name": "j", "type": "ball", "bodyB": "a"}, {"name": "j", "type": "ball", "bodyB": "b"})"),
                     {"joints[1].name", "must be unique"});
    expectParseError(R"({"joints": {}})", {"joints: must be an array"});
    // "world" is the static world only while no body has that name: otherwise it would mean both.
    const std::string withWorldBody = R"({"bodies": [{"name": "world", "shape": {"type": "sphere", "radius": 1}},
                                                     {"name": "x", "shape": {"type": "sphere", "radius": 1}}], "joints": [)";
    expectParseError(withWorldBody + R"({"type": "ball", "bodyA": "world", "bodyB": "x"}]})",
                     {"joints[0].bodyA: \"world\" names both the static world and a body of the scene", "omit bodyA"});
    EXPECT_EQ(parseScene(withWorldBody + R"({"type": "ball", "bodyA": "x", "bodyB": "world"}]})").joints[0].bodyB, "world");
    EXPECT_EQ(parseScene(scene(R"({"type": "ball", "bodyA": "world", "bodyB": "a"})")).joints[0].bodyA, "");
    // A motor faster than the scene's ceilings (its settings' or the defaults, 1e5 m/s and rad/s).
    expectParseError(scene(R"({"type": "slider", "bodyB": "a", "motor": {"speed": 1e20, "maxForce": 1e20}})"),
                     {"joints[0].motor.speed", "maxSpeed", "1e+20"});
    expectParseError("{" + bodies + R"(, "settings": {"maxAngularSpeed": 30},
                     "joints": [{"type": "hinge", "bodyB": "a", "motor": {"speed": -31, "maxForce": 1}}]})",
                     {"joints[0].motor.speed", "maxAngularSpeed", "-31"});
}

TEST(SceneJson, SyntaxErrorsGiveLineAndColumn) {
    expectParseError("{\n  \"bodies\": [\n    }\n", {"scene: invalid JSON at line 3, column 5"});
    expectParseError("", {"scene: invalid JSON at line 1, column 1"});
    expectParseError(R"({"settings": {"timeStep": 1e400}})", {"scene: invalid JSON", "1e400"});
}

// Nesting is bounded (256 levels, userData included): 200 000 nested arrays in a 400 KB file took
// tens of gigabytes (each level's path names its parents) before the bound.
TEST(SceneJson, DeepNestingIsRefusedWithoutReadingIt) {
    const auto nested = [](int depth) { return std::string(static_cast<std::size_t>(depth), '[') + std::string(static_cast<std::size_t>(depth), ']'); };
    const auto withUserData = [](const std::string& data) {
        return R"({"bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 1}, "userData": )" + data + "}]}";
    };
    // The root object, "bodies", the body and userData's own array are 4 levels: 252 more fit.
    EXPECT_EQ(parseScene(withUserData(nested(253))).bodyUserData.at("b").size(), 2u * 253u);
    expectParseError(withUserData(nested(254)), {"bodies[0].userData[0][0]", "nested more than 256 deep"});
    expectParseError(withUserData(nested(200000)), {"bodies[0].userData[0][0]", "...: objects and arrays nested more than 256"});
    expectParseError(nested(100000), {"scene[0][0]", "nested more than 256 deep"});
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

// ---- contact-era fields: convex, mesh and compound shapes, placements, filtering, sleeping ----

namespace {

const char* kContactScene = R"({
  "settings": { "contactHertz": 60, "contactDampingRatio": 2, "contactPushMaxVelocity": 4, "baumgarte": 0.3,
                "restitutionThreshold": 0.5, "linearSlop": 0.01, "speculativeDistance": 0.04,
                "sleepLinearVelocity": 0.1, "sleepAngularVelocity": 0.2, "timeToSleep": 1 },
  "bodies": [ { "name": "terrain", "type": "static",
                "shape": { "type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, -1], [1, 0, -1]],
                           "indices": [0, 1, 2, 2, 1, 3] } },
              { "name": "rock", "isTrigger": true, "layer": 4, "mask": 4294967295, "allowSleep": false,
                "isAwake": false,
                "shape": { "type": "convex", "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                           "position": [0.5, 0, 0], "orientation": [0, 0, 1, 0] } },
              { "name": "dumbbell", "layer": 2, "mask": 3,
                "shape": { "type": "compound", "shapes": [
                  { "type": "sphere", "radius": 0.25, "position": [-1, 0, 0], "density": 7800 },
                  { "type": "capsule", "radius": 0.05, "halfHeight": 1, "orientation": [0.7071067811865476, 0, 0, 0.7071067811865476] },
                  { "type": "box", "halfExtents": [0.1, 0.2, 0.3], "position": [1, 0, 0] } ] } } ] })";

}  // namespace

TEST(SceneJson, ParsesContactSettingsShapesAndFilters) {
    const Scene s = parseScene(kContactScene);
    EXPECT_EQ(s.settings.contactHertz, 60);
    EXPECT_EQ(s.settings.contactDampingRatio, 2);
    EXPECT_EQ(s.settings.contactPushMaxVelocity, 4);
    EXPECT_EQ(s.settings.baumgarte, 0.3);
    EXPECT_EQ(s.settings.restitutionThreshold, 0.5);
    EXPECT_EQ(s.settings.linearSlop, 0.01);
    EXPECT_EQ(s.settings.speculativeDistance, 0.04);
    EXPECT_EQ(s.settings.sleepLinearVelocity, 0.1);
    EXPECT_EQ(s.settings.sleepAngularVelocity, 0.2);
    EXPECT_EQ(s.settings.timeToSleep, 1);

    ASSERT_EQ(s.bodies.size(), 3u);
    const ShapeDef& mesh = s.bodies[0].shape;
    EXPECT_EQ(mesh.type, ShapeType::Mesh);
    ASSERT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.vertices[3], Vec3(1, 0, -1));
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 2, 1, 3}));

    const BodyDef& rock = s.bodies[1];
    EXPECT_TRUE(rock.isTrigger);
    EXPECT_EQ(rock.layer, 4u);
    EXPECT_EQ(rock.mask, 0xFFFFFFFFu);
    EXPECT_FALSE(rock.allowSleep);
    EXPECT_FALSE(rock.isAwake);
    EXPECT_EQ(rock.shape.type, ShapeType::Convex);
    ASSERT_EQ(rock.shape.points.size(), 4u);
    EXPECT_EQ(rock.shape.points[2], Vec3(0, 1, 0));
    EXPECT_EQ(rock.shape.position, Vec3(0.5, 0, 0));
    EXPECT_EQ(rock.shape.orientation.y(), 1);

    const BodyDef& dumbbell = s.bodies[2];
    EXPECT_EQ(dumbbell.layer, 2u);
    EXPECT_EQ(dumbbell.mask, 3u);
    EXPECT_FALSE(dumbbell.isTrigger);  // absent: the defs' defaults
    EXPECT_TRUE(dumbbell.allowSleep);
    EXPECT_TRUE(dumbbell.isAwake);
    ASSERT_EQ(dumbbell.shape.type, ShapeType::Compound);
    ASSERT_EQ(dumbbell.shape.shapes.size(), 3u);
    const ShapeDef& head = dumbbell.shape.shapes[0];
    EXPECT_EQ(head.type, ShapeType::Sphere);
    EXPECT_EQ(head.radius, 0.25);
    EXPECT_EQ(head.position, Vec3(-1, 0, 0));
    EXPECT_EQ(head.density, 7800.0);
    EXPECT_EQ(dumbbell.shape.shapes[1].orientation.z(), 0.7071067811865476);
    EXPECT_FALSE(dumbbell.shape.shapes[1].density.has_value());
    EXPECT_EQ(dumbbell.shape.shapes[2].halfExtents, Vec3(0.1, 0.2, 0.3));
}

TEST(SceneJson, AbsentContactKeysTakeTheDefaults) {
    const Scene s = parseScene(withBody(R"({"name": "b", "shape": {"type": "sphere", "radius": 0.5}})"));
    const WorldSettings d;
    EXPECT_EQ(s.settings.contactHertz, d.contactHertz);
    EXPECT_EQ(s.settings.contactDampingRatio, d.contactDampingRatio);
    EXPECT_EQ(s.settings.contactPushMaxVelocity, d.contactPushMaxVelocity);
    EXPECT_EQ(s.settings.baumgarte, d.baumgarte);
    EXPECT_EQ(s.settings.restitutionThreshold, d.restitutionThreshold);
    EXPECT_EQ(s.settings.linearSlop, d.linearSlop);
    EXPECT_EQ(s.settings.speculativeDistance, d.speculativeDistance);
    EXPECT_EQ(s.settings.sleepLinearVelocity, d.sleepLinearVelocity);
    EXPECT_EQ(s.settings.sleepAngularVelocity, d.sleepAngularVelocity);
    EXPECT_EQ(s.settings.timeToSleep, d.timeToSleep);
    const BodyDef& b = s.bodies[0];
    const BodyDef db;
    EXPECT_EQ(b.isTrigger, db.isTrigger);
    EXPECT_EQ(b.layer, db.layer);
    EXPECT_EQ(b.mask, db.mask);
    EXPECT_EQ(b.allowSleep, db.allowSleep);
    EXPECT_EQ(b.isAwake, db.isAwake);
    EXPECT_EQ(b.shape.position, Vec3::Zero());
    EXPECT_TRUE(b.shape.orientation.coeffs() == Quat::Identity().coeffs());
    EXPECT_FALSE(b.shape.density.has_value());
}

TEST(SceneJson, RoundTripOfContactFieldsIsExact) {
    Scene s = parseScene(kContactScene);
    s.settings.contactHertz = 1.0 / 3.0;
    s.settings.speculativeDistance = std::nextafter(0.02, 1.0);
    s.settings.contactImpulses = false;  // written only when not the default
    s.bodies[1].shape.points[0] = Vec3(0.1 + 0.2, -0.0, 1e-300);
    s.bodies[2].shape.shapes[0].density = 1.0 / 7.0;
    s.bodies[2].shape.shapes[2].orientation = Quat(1, -0.0, 0, 0);  // not bitwise identity: written
    s.bodies[2].mask = 0;

    const std::string text = sceneToJson(s);
    const Scene back = parseScene(text);
    expectSameScene(s, back);
    EXPECT_TRUE(std::signbit(back.bodies[1].shape.points[0].y()));
    EXPECT_TRUE(std::signbit(back.bodies[2].shape.shapes[2].orientation.x()));
    EXPECT_EQ(sceneToJson(back), text);
    // Placements are written only where set; every body writes its filter and sleep fields.
    EXPECT_EQ(back.bodies[2].shape.shapes[1].position, Vec3::Zero());
    EXPECT_NE(text.find("\"indices\": [0, 1, 2, 2, 1, 3]"), std::string::npos) << text;
    EXPECT_NE(text.find("\"mask\": 4294967295"), std::string::npos) << text;
    EXPECT_NE(text.find("\"contactHertz\": "), std::string::npos) << text;
    EXPECT_NE(text.find("\"contactImpulses\": false"), std::string::npos) << text;
    EXPECT_FALSE(back.settings.contactImpulses);
}

TEST(SceneJson, DefaultShapePlacementIsNotWritten) {
    Scene s;
    BodyDef b;
    b.name = "plain";
    b.shape = ShapeDef::sphere(0.5);
    s.bodies.push_back(b);
    const std::string text = sceneToJson(s);
    const auto shape = text.find("\"shape\"");
    ASSERT_NE(shape, std::string::npos);
    const std::string shapeText = text.substr(shape, text.find('}', shape) - shape);
    EXPECT_EQ(shapeText.find("position"), std::string::npos) << shapeText;
    EXPECT_EQ(shapeText.find("orientation"), std::string::npos) << shapeText;
    EXPECT_EQ(shapeText.find("density"), std::string::npos) << shapeText;
    expectSameScene(s, parseScene(text));
}

// A compound child's own material, sensor flag and filter: read, kept unset where not given, and
// written back only where set.
TEST(SceneJson, ChildSurfacesRoundTrip) {
    const char* text = R"({
      "materials": { "ice": { "friction": 0.02 }, "rubber": { "friction": 0.9 } },
      "bodies": [ { "name": "car", "material": "rubber",
                    "shape": { "type": "compound", "shapes": [
                      { "type": "box", "halfExtents": [2, 0.5, 1] },
                      { "type": "box", "halfExtents": [0.1, 0.3, 1], "position": [2.1, 0, 0], "material": "ice" },
                      { "type": "box", "halfExtents": [1, 0.5, 1], "position": [3.5, 0, 0], "isTrigger": true,
                        "layer": 8, "mask": 4 } ] } } ] })";
    const Scene s = parseScene(text);
    const ShapeDef& body = s.bodies[0].shape.shapes[0];
    const ShapeDef& bumper = s.bodies[0].shape.shapes[1];
    const ShapeDef& sensor = s.bodies[0].shape.shapes[2];
    EXPECT_FALSE(body.overridesSurface());
    EXPECT_EQ(bumper.material, "ice");
    EXPECT_FALSE(bumper.isTrigger || bumper.layer || bumper.mask);
    EXPECT_EQ(sensor.isTrigger, true);
    EXPECT_EQ(sensor.layer, 8u);
    EXPECT_EQ(sensor.mask, 4u);
    EXPECT_FALSE(sensor.material.has_value());
    const std::string written = sceneToJson(s);
    const Scene back = parseScene(written);
    expectSameScene(s, back);
    EXPECT_EQ(sceneToJson(back), written);
    // Only the sensor child writes a filter; the bumper writes its material and nothing else.
    EXPECT_NE(written.find("\"material\": \"ice\""), std::string::npos) << written;
    EXPECT_NE(written.find("\"layer\": 8"), std::string::npos) << written;
    EXPECT_EQ(written.find("\"layer\": 8"), written.rfind("\"layer\": 8")) << written;
}

TEST(SceneJson, ChildSurfaceErrorsNamePathValueAndRule) {
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "sphere", "radius": 0.5, "material": "ice"}]}})"),
                     {"bodies[0].shape.shapes[0].material: must name a material defined in \"materials\""});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "sphere", "radius": 0.5, "isTrigger": 1}]}})"),
                     {"bodies[0].shape.shapes[0].isTrigger"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "sphere", "radius": 0.5, "mask": -1}]}})"),
                     {"bodies[0].shape.shapes[0].mask: must be an unsigned 32-bit integer"});
    for (const char* key : {"material", "isTrigger", "layer", "mask"})
        expectParseError(withBody(std::string(R"({"name": "b", "shape": {"type": "sphere", "radius": 0.5, ")") + key +
                                  R"(": 1}})"),
                         {std::string("bodies[0].shape.") + key + ": allowed only on the children of a compound shape"});
}

TEST(SceneJson, ContactFieldErrorsNamePathValueAndRule) {
    // Compound children report their own path, from the loader and from validate() alike.
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "box", "halfExtents": [0.5, 0.5, 0.5]}, {"type": "sphere", "radius": -1}]}})"),
                     {"bodies[0].shape.shapes[1].radius: must be > 0, got -1"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "sphere", "radius": 0.5, "position": [0, "x", 0]}]}})"),
                     {"bodies[0].shape.shapes[0].position: must be an array of 3 numbers"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "sphere", "radius": 0.5, "density": 0}]}})"),
                     {"bodies[0].shape.shapes[0].density: must be > 0, got 0"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "sphere", "halfExtents": [1, 1, 1]}]}})"),
                     {"bodies[0].shape.shapes[0].halfExtents: unknown key for a sphere shape",
                      "type, radius, position, orientation, density"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": [
                                    {"type": "compound", "shapes": [{"type": "sphere", "radius": 0.5}]}]}})"),
                     {"bodies[0].shape.shapes[0].type", "compound children must be sphere, box, capsule or convex"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": []}})"),
                     {"bodies[0].shape.shapes: must hold at least one child shape"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "compound", "shapes": {}}})"),
                     {"bodies[0].shape.shapes: must be an array of child shape objects"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "sphere", "density": 10}})"),
                     {"bodies[0].shape.density: allowed only on the children of a compound shape"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "sphere", "radius": 0.5, "orientation": [2, 0, 0, 0]}})"),
                     {"bodies[0].shape.orientation", "unit quaternion"});

    expectParseError(withBody(R"({"name": "b", "shape": {"type": "convex", "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}})"),
                     {"bodies[0].shape.points: must hold at least 4 points that are not all in one plane, got 4 points"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "convex", "points": [[0, 0, 0], [1, 0]]}})"),
                     {"bodies[0].shape.points[1]: must be an array of 3 numbers, got [1,0]"});
    expectParseError(withBody(R"({"name": "b", "shape": {"type": "convex", "points": 4}})"),
                     {"bodies[0].shape.points: must be an array of [x, y, z] points, got 4"});

    const std::string square = R"("vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]])";
    expectParseError(withBody(R"({"name": "t", "type": "static", "shape": {"type": "mesh", )" + square +
                              R"(, "indices": [0, -1, 2]}})"),
                     {"bodies[0].shape.indices[1]: must be a non-negative integer (a vertex index) in [0, 4294967295], got -1"});
    expectParseError(withBody(R"({"name": "t", "type": "static", "shape": {"type": "mesh", )" + square +
                              R"(, "indices": [0, 1.5, 2]}})"),
                     {"bodies[0].shape.indices[1]", "got 1.5"});
    expectParseError(withBody(R"({"name": "t", "type": "static", "shape": {"type": "mesh", )" + square +
                              R"(, "indices": [0, 1, 3]}})"),
                     {"bodies[0].shape.indices[2]: must be < the number of vertices (3), got 3"});
    expectParseError(withBody(R"({"name": "t", "type": "static", "shape": {"type": "mesh", )" + square +
                              R"(, "indices": [0, 1]}})"),
                     {"bodies[0].shape.indices: must be a non-empty multiple of 3"});
    expectParseError(withBody(R"({"name": "t", "shape": {"type": "mesh", )" + square + R"(, "indices": [0, 1, 2]}})"),
                     {"bodies[0].shape.type", "only on static bodies"});

    expectParseError(withBody(R"({"name": "b", "isTrigger": 1, "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].isTrigger: must be true or false, got 1"});
    expectParseError(withBody(R"({"name": "b", "allowSleep": "no", "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].allowSleep: must be true or false, got \"no\""});
    expectParseError(withBody(R"({"name": "b", "layer": 4294967296, "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].layer: must be an unsigned 32-bit integer in [0, 4294967295], got 4294967296"});
    expectParseError(withBody(R"({"name": "b", "mask": -1, "shape": {"type": "sphere", "radius": 0.5}})"),
                     {"bodies[0].mask: must be an unsigned 32-bit integer", "got -1"});

    expectParseError(R"({"settings": {"contactHertz": 0}})", {"settings.contactHertz: must be > 0, got 0"});
    expectParseError(R"({"settings": {"baumgarte": 1.5}})", {"settings.baumgarte: must be in [0, 1], got 1.5"});
    // Below the interval in the same words as above it (one rule for every [0, 1] field).
    expectParseError(R"({"settings": {"baumgarte": -0.5}})", {"settings.baumgarte: must be in [0, 1], got -0.5"});
    expectParseError(R"({"materials": {"m": {"restitution": -0.5}}})", {"materials.m.restitution: must be in [0, 1], got -0.5"});
    expectParseError(R"({"settings": {"linearSlop": "tiny"}})", {"settings.linearSlop: must be a number, got \"tiny\""});
    expectParseError(R"({"settings": {"timeToSleep": -1}})", {"settings.timeToSleep: must be >= 0, got -1"});
    // A speed ceiling past 1e6 m/s let a body leave the world within one substep (ODE aborted).
    expectParseError(R"({"settings": {"maxSpeed": 1e20}})", {"settings.maxSpeed: must be <= 1e+06 m/s (anyphys::kMaxSpeedCeiling), got 1e+20"});
    expectParseError(R"({"settings": {"sleepVelocity": 1}})", {"settings.sleepVelocity: unknown key", "sleepLinearVelocity"});
}

namespace {

// A scene file's body with `shape` (JSON text) as its only shape.
std::string bodyWithShape(const std::string& shape) {
    return R"({"bodies": [{"name": "b", "type": "static", "shape": )" + shape + "}]}";
}

}  // namespace

// Every size a shape type needs is a required key: a box without halfExtents is a Parse error
// naming the key, never a 1 m cube.
TEST(SceneJson, ShapeSizesAreRequiredKeys) {
    const std::pair<const char*, const char*> cases[] = {
        {R"({"type": "sphere"})", "bodies[0].shape.radius"},
        {R"({"type": "box"})", "bodies[0].shape.halfExtents"},
        {R"({"type": "capsule", "radius": 0.2})", "bodies[0].shape.halfHeight"},
        {R"({"type": "capsule", "halfHeight": 0.2})", "bodies[0].shape.radius"},
        {R"({"type": "convex"})", "bodies[0].shape.points"},
        {R"({"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0]]})", "bodies[0].shape.indices"},
        {R"({"type": "compound"})", "bodies[0].shape.shapes"},
        {R"({"type": "compound", "shapes": [{"type": "box"}]})", "bodies[0].shape.shapes[0].halfExtents"},
    };
    for (const auto& [shape, field] : cases) {
        try {
            parseScene(bodyWithShape(shape));
            ADD_FAILURE() << shape << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Parse) << e.what();
            EXPECT_EQ(e.field(), field) << e.what();
            EXPECT_NE(std::string(e.what()).find("no default"), std::string::npos) << e.what();
        }
    }
    // A plane has no size: its offset defaults to 0 and its normal to up (+Y), as a ground means.
    EXPECT_EQ(parseScene(bodyWithShape(R"({"type": "plane", "normal": [0, 1, 0]})")).bodies[0].shape.offset, 0.0);
    EXPECT_EQ(parseScene(bodyWithShape(R"({"type": "plane", "offset": 1})")).bodies[0].shape.normal, Vec3(0, 1, 0));
}

// "userData" is any JSON value, kept as text and saved back as it came; an unsigned integer is
// also the def's userData, which reaches Body::userData through createSceneObjects.
TEST(SceneJson, UserDataIsKeptAndSavedBack) {
    const Scene s = parseScene(R"({
      "bodies": [{"name": "crate", "shape": {"type": "sphere", "radius": 1}, "userData": {"sound": "clank", "hp": [3, 4]}},
                 {"name": "id", "shape": {"type": "sphere", "radius": 1}, "position": [3, 0, 0], "userData": 18446744073709551615},
                 {"name": "plain", "shape": {"type": "sphere", "radius": 1}, "position": [6, 0, 0]}],
      "joints": [{"name": "j", "type": "ball", "bodyA": "crate", "bodyB": "id", "anchor": [1.5, 0, 0], "userData": "rope"}]})");
    EXPECT_EQ(s.bodyUserData.at("crate"), R"({"hp":[3,4],"sound":"clank"})");
    EXPECT_EQ(s.bodies[0].userData, 0u);
    EXPECT_EQ(s.bodies[1].userData, 18446744073709551615ull);
    EXPECT_EQ(s.bodyUserData.count("plain"), 0u);
    EXPECT_EQ(s.joints[0].userData, "\"rope\"");
    const std::string text = sceneToJson(s);
    const Scene back = parseScene(text);
    EXPECT_EQ(back.bodyUserData, s.bodyUserData);
    EXPECT_EQ(back.bodies[1].userData, s.bodies[1].userData);
    EXPECT_EQ(back.joints[0].userData, "\"rope\"");
    EXPECT_EQ(sceneToJson(back), text);

    Scene fromCode;  // a def's userData set in code is saved as a number
    BodyDef b;
    b.name = "x";
    b.shape = ShapeDef::sphere(1);
    b.userData = 5;
    fromCode.bodies.push_back(b);
    EXPECT_EQ(parseScene(sceneToJson(fromCode)).bodies[0].userData, 5u);
}
