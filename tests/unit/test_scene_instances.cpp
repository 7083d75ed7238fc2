// Assemblies: instances in scene files (nesting, renaming, moving, the rules on which files may be
// loaded) and the built-in assemblies.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "anyphys/containers/assembly.hpp"
#include "anyphys/error.hpp"

namespace anyphys {
namespace {

namespace fs = std::filesystem;

// A fresh folder with files written into it.
class Folder {
public:
    Folder() : root_(fs::temp_directory_path() / ("anyphys_instances_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                                                  ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
        fs::remove_all(root_);
        fs::create_directories(root_);
    }
    ~Folder() { fs::remove_all(root_); }
    std::string write(const std::string& name, const std::string& text) const {
        const fs::path p = root_ / name;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
        return p.string();
    }
    const fs::path& root() const { return root_; }

private:
    fs::path root_;
};

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

constexpr const char* kArm = R"({
  "materials": {"steel": {"friction": 0.4, "restitution": 0.1, "density": 7800}},
  "bodies": [{"name": "upper", "position": [0, -0.5, 0], "linearVelocity": [1, 0, 0],
              "shape": {"type": "sphere", "radius": 0.1}, "material": "steel"},
             {"name": "lower", "position": [0, -1.5, 0], "shape": {"type": "sphere", "radius": 0.1}}],
  "joints": [{"name": "shoulder", "type": "hinge", "bodyB": "upper", "anchor": [0, 0, 0], "axis": [0, 0, 1]},
             {"name": "elbow", "type": "hinge", "bodyA": "upper", "bodyB": "lower", "anchor": [0, -1, 0], "axis": [0, 0, 1]}]
})";

TEST(SceneInstances, PlacesRenamesAndMovesACopy) {
    Folder folder;
    folder.write("parts/arm.json", kArm);
    // Turned a quarter about +Y (so +Z becomes +X) and moved to (10, 2, 0).
    const std::string main = folder.write("main.json", R"({
      "instances": [{"scene": "parts/arm.json", "position": [10, 2, 0], "orientation": [0.7071067811865476, 0, 0.7071067811865476, 0],
                     "prefix": "left/"}],
      "joints": [{"type": "ball", "bodyB": "left/lower", "anchor": [10, 0.5, 0]}]})");
    const Scene s = loadScene(main);
    ASSERT_EQ(s.bodies.size(), 2u);
    EXPECT_EQ(s.bodies[0].name, "left/upper");
    EXPECT_TRUE(s.bodies[0].position.isApprox(Vec3(10, 1.5, 0), 1e-12));
    EXPECT_TRUE(s.bodies[0].linearVelocity.isApprox(Vec3(0, 0, -1), 1e-12));  // +X turned about +Y: -Z
    EXPECT_TRUE(s.materials.contains("steel"));
    ASSERT_EQ(s.joints.size(), 3u);  // the instance's two, then the scene's own
    EXPECT_EQ(s.joints[0].def.name, "left/shoulder");
    EXPECT_EQ(s.joints[0].bodyA, "");
    EXPECT_EQ(s.joints[1].bodyA, "left/upper");
    EXPECT_TRUE(s.joints[1].def.anchor.isApprox(Vec3(10, 1, 0), 1e-12));
    EXPECT_TRUE(s.joints[1].def.axis.isApprox(Vec3(1, 0, 0), 1e-12));
    EXPECT_EQ(s.joints[2].bodyB, "left/lower");
}

TEST(SceneInstances, NestAndRenameAtEveryLevel) {
    Folder folder;
    folder.write("parts/arm.json", kArm);
    folder.write("parts/pair.json", R"({"instances": [
        {"scene": "arm.json", "position": [-1, 0, 0], "prefix": "a/"},
        {"scene": "arm.json", "position": [1, 0, 0], "prefix": "b/"}]})");
    const Scene s = loadScene(folder.write("main.json", R"({"instances": [
        {"scene": "parts/pair.json", "position": [0, 5, 0], "prefix": "p1/"},
        {"scene": "parts/pair.json", "position": [0, 9, 0], "prefix": "p2/"}]})"));
    ASSERT_EQ(s.bodies.size(), 8u);
    EXPECT_EQ(s.bodies[0].name, "p1/a/upper");
    EXPECT_TRUE(s.bodies[0].position.isApprox(Vec3(-1, 4.5, 0), 1e-12));
    EXPECT_EQ(s.bodies[7].name, "p2/b/lower");
    EXPECT_EQ(s.joints[3].bodyA, "p1/b/upper");
}

TEST(SceneInstances, UntrustedPathsAreRefusedNamingTheJsonPath) {
    Folder folder;
    folder.write("arm.json", kArm);
    const auto load = [&](const std::string& scene) {
        return errorOf([&] { loadScene(folder.write("main.json", R"({"instances": [{"scene": ")" + scene + R"("}]})")); });
    };
    EXPECT_NE(load("../arm.json").find("instances[0].scene: leaves the including file's folder"), std::string::npos);
    EXPECT_NE(load((folder.root() / "arm.json").string()).find("absolute paths are refused"), std::string::npos);
    EXPECT_NE(load("missing.json").find("instances[0].scene:"), std::string::npos);
    EXPECT_NE(load("missing.json").find("cannot read scene file"), std::string::npos);
    // Allowed when the caller says so.
    SceneLoadOptions open;
    open.allowOutsideFolder = true;
    folder.write("sub/main.json", R"({"instances": [{"scene": "../arm.json", "prefix": "x/"}]})");
    EXPECT_EQ(loadScene((folder.root() / "sub/main.json").string(), open).bodies.size(), 2u);
    // Text has no folder: built-in assemblies only.
    EXPECT_NE(errorOf([] { parseScene(R"({"instances": [{"scene": "arm.json"}]})"); }).find("has no folder"),
              std::string::npos);
}

TEST(SceneInstances, CyclesDepthAndSizeHaveLimits) {
    Folder folder;
    folder.write("a.json", R"({"instances": [{"scene": "b.json", "prefix": "b/"}]})");
    folder.write("b.json", R"({"instances": [{"scene": "a.json", "prefix": "a/"}]})");
    const std::string cycle = errorOf([&] { loadScene((folder.root() / "a.json").string()); });
    EXPECT_NE(cycle.find("instances form a cycle: a.json -> b.json -> a.json"), std::string::npos) << cycle;

    folder.write("d0.json", kArm);
    for (int i = 1; i <= 4; ++i)
        folder.write("d" + std::to_string(i) + ".json",
                     R"({"instances": [{"scene": "d)" + std::to_string(i - 1) + R"(.json", "prefix": "x/"}]})");
    SceneLoadOptions shallow;
    shallow.maxDepth = 3;
    EXPECT_NO_THROW(loadScene((folder.root() / "d3.json").string(), shallow));
    EXPECT_NE(errorOf([&] { loadScene((folder.root() / "d4.json").string(), shallow); }).find("maxDepth (3)"),
              std::string::npos);

    SceneLoadOptions small;
    small.maxBodies = 3;
    folder.write("two.json", R"({"instances": [{"scene": "arm.json", "prefix": "a/"}, {"scene": "arm.json", "prefix": "b/"}]})");
    folder.write("arm.json", kArm);
    const std::string big = errorOf([&] { loadScene((folder.root() / "two.json").string(), small); });
    EXPECT_NE(big.find("instances[1]: would bring the scene to 4 bodies, more than SceneLoadOptions::maxBodies (3)"),
              std::string::npos)
        << big;
}

TEST(SceneInstances, ClashesAreRefusedAndLeaveTheSceneAsItWas) {
    Scene target = parseScene(kArm);
    const Scene arm = parseScene(kArm);
    const std::string same = errorOf([&] { appendInstance(target, arm, Transform{}, ""); });
    EXPECT_NE(same.find("body name \"upper\" is already used"), std::string::npos) << same;
    EXPECT_EQ(target.bodies.size(), 2u);
    Scene other = arm;
    other.materials.add("steel", Material{0.9, 0.0, 1000.0});
    const std::string material = errorOf([&] { appendInstance(target, other, Transform{}, "x/"); });
    EXPECT_NE(material.find("material \"steel\" has other values"), std::string::npos) << material;
    EXPECT_EQ(target.bodies.size(), 2u);
    appendInstance(target, arm, Transform{}, "x/");
    EXPECT_EQ(target.bodies.size(), 4u);
}

// A placed copy meets the rules of a body written in the file: what loads also saves and loads
// again (found by the scene fuzzer: an instance at 8.9e26 m loaded, and its saved file did not).
TEST(SceneInstances, PlacedBodiesMeetTheCoordinateCeiling) {
    const std::string far = errorOf([] {
        parseScene(R"({"instances": [{"scene": "ragdoll", "prefix": "r.", "position": [8.9e26, 2, 0]}]})");
    });
    EXPECT_NE(far.find("instances[0].position"), std::string::npos) << far;
    EXPECT_NE(far.find("1e+07"), std::string::npos) << far;
    // The instance's own position is within kMaxCoordinate (1e7 m), but the ragdoll's bodies
    // stand up to 1.7 m above it: the head is refused, by name.
    const std::string edge = errorOf([] {
        parseScene(R"({"instances": [{"scene": "ragdoll", "prefix": "r.", "position": [0, 9999999.5, 0]}]})");
    });
    EXPECT_NE(edge.find("instances[0] body \"r."), std::string::npos) << edge;
    EXPECT_NE(edge.find(".position"), std::string::npos) << edge;
    // Just inside, the whole ragdoll is accepted and survives save + load unchanged.
    const Scene inside = parseScene(R"({"instances": [{"scene": "ragdoll", "prefix": "r.", "position": [0, 9999990, 0]}]})");
    EXPECT_EQ(sceneToJson(parseScene(sceneToJson(inside))), sceneToJson(inside));
}

// The built-in assemblies are well-formed scenes: a 70 kg ragdoll of 11 bodies and 10 joints, a
// car of 5 bodies with 4 wheel joints, and their planar versions.
TEST(SceneInstances, BuiltinAssemblies) {
    EXPECT_EQ(builtinAssemblyNames(), (std::vector<std::string>{"ragdoll", "ragdoll_planar", "vehicle", "vehicle_planar"}));
    for (const std::string& name : builtinAssemblyNames()) {
        const Scene& s = builtinAssembly(name);
        // Round trip through JSON: every body and joint passes the scene file's rules.
        const Scene back = parseScene(sceneToJson(s));
        EXPECT_EQ(back.bodies.size(), s.bodies.size()) << name;
        EXPECT_EQ(back.joints.size(), s.joints.size()) << name;
    }
    const Scene& ragdoll = builtinAssembly("ragdoll");
    EXPECT_EQ(ragdoll.bodies.size(), 11u);
    EXPECT_EQ(ragdoll.joints.size(), 10u);
    double mass = 0.0;
    for (const BodyDef& b : ragdoll.bodies) mass += *b.mass;
    EXPECT_NEAR(mass, 70.0, 1e-9);
    EXPECT_EQ(builtinAssembly("vehicle").bodies.size(), 5u);
    EXPECT_EQ(builtinAssembly("vehicle_planar").joints.size(), 2u);
    EXPECT_NE(errorOf([] { builtinAssembly("robot"); }).find("ragdoll, ragdoll_planar"), std::string::npos);
    // Instanced from text by name.
    const Scene two = parseScene(R"({"instances": [{"scene": "ragdoll", "prefix": "a/"},
                                                   {"scene": "ragdoll", "position": [2, 0, 0], "prefix": "b/"}]})");
    EXPECT_EQ(two.bodies.size(), 22u);
    EXPECT_EQ(two.bodies[11].name, "b/pelvis");
}

}  // namespace
}  // namespace anyphys
