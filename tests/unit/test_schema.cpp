// The field table (anyphys/schema) against what it describes: the defs' defaults, the scene
// loader and writer, validation's messages, the backends' parameter lists and the doc.
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "anyphys/backends.hpp"
#include "anyphys/containers/scene.hpp"
#include "anyphys/error.hpp"
#include "anyphys/fields/schema_markdown.hpp"
#include "anyphys/schema/markdown.hpp"
#include "anyphys/schema/parameters.hpp"
#include "anyphys/validation.hpp"

using namespace anyphys;
using schema::Check;
using schema::Field;
using schema::Type;
using schema::Value;

namespace {

// Equal values, NaN equal to NaN (a shape's unset sizes).
bool same(const Value& a, const Value& b) {
    if (a.index() != b.index()) return false;
    const auto eq = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
    if (const auto* x = std::get_if<double>(&a)) return eq(*x, std::get<double>(b));
    if (const auto* x = std::get_if<Vec3>(&a)) {
        const Vec3& y = std::get<Vec3>(b);
        return eq(x->x(), y.x()) && eq(x->y(), y.y()) && eq(x->z(), y.z());
    }
    if (const auto* x = std::get_if<Quat>(&a)) return x->coeffs() == std::get<Quat>(b).coeffs();
    if (const auto* x = std::get_if<int>(&a)) return *x == std::get<int>(b);
    if (const auto* x = std::get_if<std::uint32_t>(&a)) return *x == std::get<std::uint32_t>(b);
    if (const auto* x = std::get_if<bool>(&a)) return *x == std::get<bool>(b);
    if (const auto* x = std::get_if<std::string>(&a)) return *x == std::get<std::string>(b);
    return true;
}

template <class Def>
void expectDefaults(const std::vector<Field<Def>>& rows) {
    const Def def{};
    for (const auto& f : rows) {
        if (!f.get) continue;
        EXPECT_TRUE(same(f.get(def), f.value)) << f.path << ": the table's default differs from the struct's";
    }
}

// A valid value other than the default, for every row code can write.
template <class Def>
Value sample(const Field<Def>& f) {
    switch (f.type) {
        case Type::Number: {
            const double* d = std::get_if<double>(&f.value);
            if (!d || std::isnan(*d)) return 0.375;
            return *d == 0 ? 0.375 : *d * 0.5;
        }
        case Type::Count: {
            const int* n = std::get_if<int>(&f.value);
            return n ? *n + 1 : 3;
        }
        case Type::Bits: return std::uint32_t{6};
        case Type::Vec3:
            if (f.check == Check::Magnitude) return Vec3(0.5, -7, 0);
            return Vec3(0.5, 0.25, 0.75);
        case Type::Quat: return Quat(0.6, 0, 0.8, 0);
        case Type::Bool: {
            const bool* b = std::get_if<bool>(&f.value);
            return !(b && *b);
        }
        case Type::Enum: {
            const std::string names = f.allowed();
            const std::string first = names.substr(0, names.find(','));
            const std::string* current = std::get_if<std::string>(&f.value);
            if (current && *current == first) return names.substr(first.size() + 2, names.find(',', first.size() + 2) - first.size() - 2);
            return first;
        }
        case Type::String: return std::string("native_x");
        case Type::Object: break;
    }
    return {};
}

// A value the row's check refuses (nullopt: not expressible in JSON, e.g. a non-finite one).
template <class Def>
std::optional<Value> invalid(const Field<Def>& f) {
    const bool vec = f.type == Type::Vec3;
    const auto number = [&](double x) -> Value { return vec ? Value(Vec3(0.5, x, 0.5)) : Value(x); };
    switch (f.check) {
        case Check::Positive:
        case Check::NonNegative:
        case Check::Length:
        case Check::LengthOrZero: return number(-1);
        case Check::UnitInterval: return number(2);
        case Check::Within: return number(2 * f.bound);
        case Check::Coordinate: return number(2 * kMaxCoordinate);
        case Check::Magnitude: return Vec3(0, -2 * f.bound, 0);
        case Check::PositiveAtMost: return 2 * f.bound;
        case Check::TimeStep: return 1e-12;  // below kMinTimeStep: a step that rounds to 0 in substeps
        case Check::CountIn: return static_cast<int>(f.bound) + 1;
        case Check::UnitQuaternion: return Quat(2, 0, 0, 0);
        case Check::Direction: return Vec3(0, 0, 0);
        case Check::NonEmpty: return std::string();
        case Check::Threshold: return number(-1);
        default: return std::nullopt;
    }
}

// Expects the loader to refuse `scene`, where row `f` holds `bad`, in the words the row's own check
// gives for that value at `path` (the key's path in messages).
template <class Def>
void expectRefusedInTheRowsWords(const Field<Def>& f, const Value& bad, const Scene& scene, const std::string& path) {
    std::string expected;
    try {
        schema::checkValue(f, bad, path);
    } catch (const Error& e) {
        expected = e.what();
    }
    ASSERT_FALSE(expected.empty()) << f.path << ": the check accepts the value meant to be refused";
    try {
        parseScene(sceneToJson(scene));
        ADD_FAILURE() << f.path << ": the loader accepted a value the table refuses";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), expected) << f.path;
    }
}

// A scene with one body of a shape that has the shape row `f` (a compound's child for children's rows).
Scene sceneFor(const Field<ShapeDef>& f) {
    Scene scene;
    BodyDef b;
    b.name = "b";
    if (f.childOnly) {
        b.shape = ShapeDef::compound({ShapeDef::sphere(0.5)});
    } else if (f.types & schema::bit(ShapeType::Plane) && !(f.types & schema::bit(ShapeType::Sphere))) {
        b.type = BodyType::Static;
        b.shape = ShapeDef::plane(Vec3::UnitY(), 0);
    } else if (f.types & schema::bit(ShapeType::Capsule) && !(f.types & schema::bit(ShapeType::Sphere))) {
        b.shape = ShapeDef::capsule(0.5, 1);
    } else if (f.types & schema::bit(ShapeType::Box) && !(f.types & schema::bit(ShapeType::Sphere))) {
        b.shape = ShapeDef::box(Vec3(1, 1, 1));
    } else {
        b.shape = ShapeDef::sphere(0.5);
    }
    scene.bodies.push_back(b);
    return scene;
}
ShapeDef& shapeOf(Scene& scene, const Field<ShapeDef>& f) {
    return f.childOnly ? scene.bodies[0].shape.shapes[0] : scene.bodies[0].shape;
}
std::string shapePath(const Field<ShapeDef>& f) { return f.childOnly ? "bodies[0].shape.shapes[0]" : "bodies[0].shape"; }

Scene sceneFor(const Field<BodyDef>&) {
    Scene scene;
    BodyDef b;
    b.name = "b";
    b.shape = ShapeDef::sphere(0.5);
    scene.bodies.push_back(b);
    return scene;
}

// Calls `each(row, scene, where, path)` with a fresh scene per row: `where(scene)` is the row's
// def in that scene (or in one read back from it), `path` its path in messages.
template <class Each>
void forEachRow(Each each) {
    for (const auto& f : schema::settingsFields()) {
        Scene scene;
        each(f, scene, [](Scene& s) -> WorldSettings& { return s.settings; }, std::string("settings"));
    }
    for (const auto& f : schema::bodyFields()) {
        Scene scene = sceneFor(f);
        each(f, scene, [](Scene& s) -> BodyDef& { return s.bodies.at(0); }, std::string("bodies[0]"));
    }
    for (const auto& f : schema::shapeFields()) {
        Scene scene = sceneFor(f);
        each(f, scene, [&f](Scene& s) -> ShapeDef& { return shapeOf(s, f); }, shapePath(f));
    }
}

}  // namespace

TEST(Schema, DefaultsAreTheDefsDefaults) {
    expectDefaults(schema::settingsFields());
    expectDefaults(schema::bodyFields());
    expectDefaults(schema::shapeFields());
    expectDefaults(schema::materialFields());
    expectDefaults(schema::jointDefFields());
    expectDefaults(schema::jointLimitsFields());
    expectDefaults(schema::jointMotorFields());
    expectDefaults(schema::jointSpringFields());
    expectDefaults(schema::fieldDefFields());
    expectDefaults(schema::fieldSurfaceFields());
    expectDefaults(schema::fluidDefFields());
    expectDefaults(schema::fluidBoxFields());
    expectDefaults(schema::clothDefFields());
}

TEST(Schema, KeysAreUniqueAndPathsEndInTheirKey) {
    const auto check = [](const auto& rows) {
        std::set<std::pair<std::string_view, std::uint32_t>> seen;
        for (const auto& f : rows) {
            EXPECT_TRUE(seen.emplace(f.key, f.childOnly ? 1u : 0u).second) << f.path << ": key described twice";
            // Not `"." + std::string(f.key)`: g++ 12 at -O3 reports a false overflow (-Werror) on it.
            const std::string_view path = f.path;
            EXPECT_TRUE(path.size() > f.key.size() && path.ends_with(f.key) &&
                        path[path.size() - f.key.size() - 1] == '.')
                << f.path;
            EXPECT_TRUE(f.ownCode || (f.get && f.set)) << f.path << ": neither accessors nor own code";
            if (f.type == Type::Enum) {
                EXPECT_TRUE(f.allowed != nullptr) << f.path << ": an enum without its names";
            }
        }
    };
    check(schema::settingsFields());
    check(schema::bodyFields());
    check(schema::shapeFields());
    check(schema::materialFields());
    check(schema::jointDefFields());
    check(schema::jointLimitsFields());
    check(schema::jointMotorFields());
    check(schema::jointSpringFields());
    check(schema::fieldDefFields());
    check(schema::fieldSurfaceFields());
    check(schema::fluidDefFields());
    check(schema::fluidBoxFields());
    check(schema::clothDefFields());
}

// Every row code can write round-trips through a scene file with a value other than its default
// (so the loader accepts its key and the writer writes it).
TEST(Schema, EveryRowRoundTripsANonDefaultValue) {
    forEachRow([](const auto& f, Scene& scene, auto where, const std::string& path) {
        if (!f.set) return;
        const Value value = sample(f);
        ASSERT_TRUE(f.set(where(scene), value)) << f.path;
        Scene back;
        ASSERT_NO_THROW(back = parseScene(sceneToJson(scene))) << f.path << " at " << path;
        EXPECT_TRUE(same(f.get(where(back)), value)) << f.path << ": not read back";
    });
    for (const auto& f : schema::materialFields()) {
        Scene scene;
        Material m;
        ASSERT_TRUE(f.set(m, sample(f)));
        scene.materials.add("m", m);
        const Scene back = parseScene(sceneToJson(scene));
        EXPECT_TRUE(same(f.get(back.materials.get("m")), sample(f))) << f.path;
    }
}

// A scene with a joint of the first type that uses JointDef row `f`, between two dynamic bodies;
// a distance joint's anchors 1 m apart.
Scene jointSceneFor(const Field<JointDef>& f) {
    Scene scene;
    for (const char* name : {"a", "b"}) {
        BodyDef b;
        b.name = name;
        b.shape = ShapeDef::sphere(0.5);
        scene.bodies.push_back(b);
    }
    SceneJoint j;
    j.bodyA = "a";
    j.bodyB = "b";
    for (const auto& [type, name] : EnumNames<JointType>::values)
        if (f.types & schema::bit(type)) {
            j.def.type = type;
            break;
        }
    j.def.anchorB = Vec3(0, 1, 0);
    scene.joints.push_back(j);
    return scene;
}

// A value other than the default that the joint rules between fields accept.
Value jointSample(const Field<JointDef>& f) {
    if (f.key == "minLength") return 0.25;
    if (f.key == "maxLength") return 4.0;
    if (f.key == "spinAxis") return Vec3(0, 1, 0);  // perpendicular to the default axis
    if (f.key == "breakForce" || f.key == "breakTorque") return 100.0;
    return sample(f);
}

// Every JointDef row code can write round-trips through a scene file on a type that uses it, and a
// value its check refuses is refused by the loader in the row's words.
TEST(Schema, EveryJointRowRoundTripsAndIsRefusedInItsWords) {
    std::size_t refused = 0;
    for (const auto& f : schema::jointDefFields()) {
        if (!f.set) continue;
        Scene scene = jointSceneFor(f);
        const Value value = jointSample(f);
        ASSERT_TRUE(f.set(scene.joints[0].def, value)) << f.path;
        Scene back;
        ASSERT_NO_THROW(back = parseScene(sceneToJson(scene))) << f.path;
        EXPECT_TRUE(same(f.get(back.joints.at(0).def), value)) << f.path << ": not read back";

        const auto bad = invalid(f);
        if (!bad) continue;
        Scene wrong = jointSceneFor(f);
        ASSERT_TRUE(f.set(wrong.joints[0].def, *bad));
        expectRefusedInTheRowsWords(f, *bad, wrong, "joints[0]." + std::string(f.key));
        ++refused;
    }
    EXPECT_EQ(refused, 8u);  // anchor, anchorA, anchorB, length, minLength, maxLength, breakForce, breakTorque
}

// Every row of fields, fluids and cloths that code can write round-trips through a scene file (a
// field of the first type that has the row), and a value its check refuses is refused by the
// loader in the row's words.
TEST(Schema, EveryFieldFluidAndClothRowRoundTripsAndIsRefusedInItsWords) {
    std::size_t refused = 0;
    // `make(f)`: a scene holding one def that has row f; `where(scene)`: that def.
    const auto run = [&refused](const auto& rows, auto make, auto where, const std::string& path, auto override) {
        for (const auto& f : rows) {
            if (!f.set) continue;
            Scene scene = make(f);
            const Value value = override(f).value_or(sample(f));
            ASSERT_TRUE(f.set(where(scene), value)) << f.path;
            Scene back;
            ASSERT_NO_THROW(back = parseScene(sceneToJson(scene))) << f.path;
            EXPECT_TRUE(same(f.get(where(back)), value)) << f.path << ": not read back";
            const auto bad = invalid(f);
            if (!bad) continue;
            Scene wrong = make(f);
            ASSERT_TRUE(f.set(where(wrong), *bad));
            expectRefusedInTheRowsWords(f, *bad, wrong, path + "." + std::string(f.key));
            ++refused;
        }
    };
    const auto none = [](const auto&) { return std::optional<Value>(); };
    run(schema::fieldDefFields(),
        [](const Field<FieldDef>& f) {
            Scene scene;
            FieldDef def;
            for (const auto& n : kFieldTypeNames)
                if (f.types & schema::bit(n.type)) {
                    def.type = n.type;
                    break;
                }
            scene.fields.push_back(def);
            return scene;
        },
        [](Scene& s) -> FieldDef& { return s.fields.at(0); }, "fields[0]", none);
    run(schema::fluidDefFields(), [](const auto&) {
            Scene scene;
            scene.fluids.push_back(FluidDef{});
            return scene;
        },
        [](Scene& s) -> FluidDef& { return s.fluids.at(0); }, "fluids[0]", none);
    run(schema::clothDefFields(), [](const auto&) {
            Scene scene;
            scene.cloths.push_back(ClothDef{});
            return scene;
        },
        [](Scene& s) -> ClothDef& { return s.cloths.at(0); }, "cloths[0]",
        [](const Field<ClothDef>& f) -> std::optional<Value> {
            // Unit and perpendicular to the other axis's default.
            if (f.key == "axisU" || f.key == "axisV") return Vec3(0, 0, 1);
            return std::nullopt;
        });
    // fluidDensity, linearDrag, angularDrag, airDensity, center, time, impulse, radius; spacing,
    // density, viscosity; corner, areaDensity, stiffness, bending, damping, thickness.
    EXPECT_EQ(refused, 17u);
}

// A value a row's check refuses is refused by the loader with the row's rule in the same words.
TEST(Schema, RefusedValuesGiveTheRowsRule) {
    std::size_t checked = 0;
    forEachRow([&checked](const auto& f, Scene& scene, auto where, const std::string& path) {
        const auto bad = invalid(f);
        if (!f.set || !bad) return;
        ASSERT_TRUE(f.set(where(scene), *bad));
        expectRefusedInTheRowsWords(f, *bad, scene, path + "." + std::string(f.key));
        ++checked;
    });
    EXPECT_GE(checked, 30u);
}

// Every parameter a backend lists for settings, bodies and materials is a row of the table, and
// every row the layer honours is listed on every backend (settings.planar where planar).
TEST(Schema, CapabilityParametersComeFromTheTable) {
    const auto described = schema::describedParameters();
    for (const BackendInfo& b : availableBackends()) {
        for (const std::string& p : b.capabilities.parameters) {
            EXPECT_TRUE(described.contains(p)) << b.name << " lists " << p << ", which no row describes";
        }
        for (const std::string& p : schema::layerParameters(b.capabilities))
            EXPECT_TRUE(b.capabilities.parameters.contains(p)) << b.name << " lacks the layer's " << p;
        EXPECT_EQ(b.capabilities.parameters.contains("settings.planar"), b.capabilities.planar) << b.name;
        EXPECT_TRUE(b.capabilities.parameters.contains("settings.maxSpeed")) << b.name;
    }
}

TEST(Schema, ValidationUsesTheRowsWords) {
    WorldSettings s;
    s.timeStep = 2;
    try {
        validate(s, "WorldSettings");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "WorldSettings.timeStep: must be <= 1 s (anyphys::kMaxTimeStep), got 2");
    }
    BodyDef b;
    b.shape = ShapeDef::box(Vec3(1, -1, 1));
    try {
        validate(b, "BodyDef");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "BodyDef.shape.halfExtents[1]: must be > 0, got -1");
    }
}

// docs/scene-format.md's key tables are the generated ones.
TEST(Schema, SceneFormatDocMatchesTheTable) {
    const std::string path = std::string(ANYPHYS_SOURCE_DIR) + "/docs/scene-format.md";
    std::ifstream in(path);
    ASSERT_TRUE(in) << "cannot read " << path;
    std::stringstream text;
    text << in.rdbuf();
    std::vector<std::string> missing;
    const std::string updated = schema::updateMarkdown(text.str(), missing, schema::allMarkdownTables());
    EXPECT_TRUE(missing.empty()) << path << " lacks the markers of " << missing.size() << " tables, e.g. "
                                 << (missing.empty() ? "" : missing[0]);
    EXPECT_TRUE(updated == text.str()) << "docs/scene-format.md's key tables differ from the field table "
                                          "(api/include/anyphys/schema/): run `build/bin/anyphys schema --update "
                                          "docs/scene-format.md` and commit the result";
}
