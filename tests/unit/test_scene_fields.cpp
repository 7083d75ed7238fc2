// Scene files with force fields: parsing, defaults, round trip and errors naming the path.
#include <gtest/gtest.h>

#include <string>

#include "anyphys/containers/scene.hpp"
#include "anyphys/error.hpp"

namespace anyphys {
namespace {

const char* kFields = R"({
  "bodies": [ { "name": "ball", "shape": { "type": "sphere", "radius": 0.5 }, "dragCoefficient": 0.3 } ],
  "fields": [
    { "type": "buoyancy", "fluidDensity": 1000, "surface": { "normal": [0, 1, 0], "offset": 0 }, "linearDrag": 1.0, "angularDrag": 0.5 },
    { "type": "drag", "airDensity": 1.2 },
    { "type": "wind", "velocity": [6, 0, 0], "airDensity": 1.2 },
    { "type": "explosion", "center": [0, 0, 0], "time": 1.0, "impulse": 500, "radius": 5 } ] })";

std::string errorOf(const std::string& text) {
    try {
        parseScene(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(SceneFields, ParsesTheIssueExample) {
    const Scene scene = parseScene(kFields);
    ASSERT_EQ(scene.fields.size(), 4u);
    EXPECT_EQ(scene.fields[0].type, FieldType::Buoyancy);
    EXPECT_EQ(scene.fields[0].fluidDensity, 1000.0);
    EXPECT_EQ(scene.fields[0].surfaceNormal, Vec3(0, 1, 0));
    EXPECT_EQ(scene.fields[0].linearDrag, 1.0);
    EXPECT_EQ(scene.fields[0].angularDrag, 0.5);
    EXPECT_EQ(scene.fields[1].type, FieldType::Drag);
    EXPECT_EQ(scene.fields[1].airDensity, 1.2);
    EXPECT_EQ(scene.fields[2].velocity, Vec3(6, 0, 0));
    EXPECT_EQ(scene.fields[3].type, FieldType::Explosion);
    EXPECT_EQ(scene.fields[3].time, 1.0);
    EXPECT_EQ(scene.fields[3].impulse, 500.0);
    EXPECT_EQ(scene.fields[3].radius, 5.0);
    ASSERT_TRUE(scene.bodies[0].dragCoefficient);
    EXPECT_EQ(*scene.bodies[0].dragCoefficient, 0.3);
}

TEST(SceneFields, RoundTrip) {
    const Scene scene = parseScene(kFields);
    const std::string text = sceneToJson(scene);
    const Scene again = parseScene(text);
    EXPECT_EQ(sceneToJson(again), text);
    ASSERT_EQ(again.fields.size(), 4u);
    EXPECT_EQ(again.fields[3].center, scene.fields[3].center);
    EXPECT_EQ(*again.bodies[0].dragCoefficient, 0.3);
    // A scene without fields writes no "fields" key (files written before fields stay identical).
    EXPECT_EQ(sceneToJson(parseScene("{}")).find("fields"), std::string::npos);
}

TEST(SceneFields, ErrorsNamePathValueAndRule) {
    EXPECT_EQ(errorOf(R"({"fields": [{"type": "drag"}, {"type": "drag"}, {"type": "explosion", "radius": -1}]})"),
              "fields[2].radius: must be > 0, got -1");
    EXPECT_EQ(errorOf(R"({"fields": [{"type": "gravity"}]})"),
              "fields[0].type: must be one of buoyancy, drag, wind, explosion, got \"gravity\"");
    EXPECT_NE(errorOf(R"({"fields": [{"type": "drag", "velocity": [1, 0, 0]}]})").find("fields[0].velocity: unknown key for a drag field"),
              std::string::npos);
    EXPECT_EQ(errorOf(R"({"fields": [{"type": "buoyancy", "surface": {"normal": [0, 2, 0]}}]})"),
              "fields[0].surface.normal: must be a unit vector (norm 1 within 1e-6), got [0, 2, 0]");
    EXPECT_EQ(errorOf(R"({"fields": [{"type": "wind", "airDensity": 0}]})"), "fields[0].airDensity: must be > 0, got 0");
    EXPECT_EQ(errorOf(R"({"fields": {"type": "drag"}})").substr(0, 8), "fields: ");
    EXPECT_EQ(errorOf(R"({"settings": {"planar": true}, "fields": [{"type": "wind", "velocity": [1, 0, 1]}]})"),
              "fields[0].velocity: must lie in the XY plane (z = 0) in a planar world, got [1, 0, 1]");
    EXPECT_EQ(errorOf(R"({"bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.5}, "dragCoefficient": -1}]})"),
              "bodies[0].dragCoefficient: must be >= 0, got -1");
}

// ---- fluids and cloths ---------------------------------------------------------------------------

const char* kParticles = R"({
  "fluids": [ { "name": "water", "box": { "min": [-1, 0, -1], "max": [1, 1, 1] },
                "spacing": 0.05, "density": 1000, "viscosity": 0.001 } ],
  "cloths": [ { "name": "flag", "corner": [0, 2, 0], "size": [2, 1], "resolution": [20, 10],
                "areaDensity": 0.2, "stiffness": 1e4, "damping": 0.1, "pinned": [[0, 0], [0, 10]] } ] })";

TEST(SceneParticles, ParsesTheIssueExample) {
    const Scene scene = parseScene(kParticles);
    ASSERT_EQ(scene.fluids.size(), 1u);
    EXPECT_EQ(scene.fluids[0].name, "water");
    EXPECT_EQ(scene.fluids[0].boxMin, Vec3(-1, 0, -1));
    EXPECT_EQ(scene.fluids[0].boxMax, Vec3(1, 1, 1));
    EXPECT_EQ(scene.fluids[0].spacing, 0.05);
    EXPECT_EQ(scene.fluids[0].viscosity, 0.001);
    ASSERT_EQ(scene.cloths.size(), 1u);
    const ClothDef& c = scene.cloths[0];
    EXPECT_EQ(c.corner, Vec3(0, 2, 0));
    EXPECT_EQ(c.size[0], 2.0);
    EXPECT_EQ(c.resolution[1], 10);
    EXPECT_EQ(c.stiffness, 1e4);
    ASSERT_EQ(c.pinned.size(), 2u);
    EXPECT_EQ(c.pinned[1][1], 10);
    EXPECT_EQ(c.axisV, Vec3(0, -1, 0));  // default: a hanging sheet
    const std::string text = sceneToJson(scene);
    EXPECT_EQ(sceneToJson(parseScene(text)), text);
    EXPECT_EQ(sceneToJson(parseScene("{}")).find("fluids"), std::string::npos);
    EXPECT_EQ(sceneToJson(parseScene("{}")).find("cloths"), std::string::npos);
}

TEST(SceneParticles, ErrorsNamePathValueAndRule) {
    EXPECT_EQ(errorOf(R"({"fluids": [{"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "spacing": 0}]})"),
              "fluids[0].spacing: must be > 0, got 0");
    EXPECT_EQ(errorOf(R"({"fluids": [{"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "viscosity": -1}]})"),
              "fluids[0].viscosity: must be >= 0, got -1");
    EXPECT_EQ(errorOf(R"({"fluids": [{"box": {"min": [0, 0, 0], "max": [1, 0, 1]}}]})"),
              "fluids[0].box.max: must exceed box.min [0, 0, 0] in every coordinate, got [1, 0, 1]");
    EXPECT_NE(errorOf(R"({"fluids": [{"spacing": 0.1}]})").find("fluids[0].box"), std::string::npos);
    EXPECT_NE(errorOf(R"({"fluids": [{"box": {"min": [0, 0, 0], "max": [100, 100, 100]}, "spacing": 0.01}]})")
                  .find("fluids[0].spacing: gives 1000000000000 particles in the box; at most 200000 are allowed"), std::string::npos);
    EXPECT_NE(errorOf(R"({"fluids": [{"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "colour": 1}]})").find("fluids[0].colour"),
              std::string::npos);
    EXPECT_EQ(errorOf(R"({"cloths": [{"pinned": [[0, 0], [21, 0]]}]})"),
              "cloths[0].pinned[1]: must name a node [i, j] with 0 <= i <= 20 and 0 <= j <= 10, got [21, 0]");
    EXPECT_EQ(errorOf(R"({"cloths": [{"stiffness": -5}]})"), "cloths[0].stiffness: must be > 0, got -5");
    EXPECT_EQ(errorOf(R"({"cloths": [{"resolution": [0, 3]}]})"), "cloths[0].resolution[0]: must be an integer in [1, 1000], got 0");
    EXPECT_NE(errorOf(R"({"cloths": [{"resolution": [2.5, 3]}]})").find("cloths[0].resolution"), std::string::npos);
    EXPECT_NE(errorOf(R"({"cloths": [{"axisV": [1, 0, 0]}]})").find("cloths[0].axisV: must be perpendicular"),
              std::string::npos);
    EXPECT_EQ(errorOf(R"({"settings": {"planar": true}, "cloths": [{"axisV": [0, 0, 1]}]})"),
              "cloths[0].axisV: must lie in the XY plane (z = 0) in a planar world: the sheet then moves in the plane, got [0, 0, 1]");
    EXPECT_EQ(errorOf(R"({"cloths": {"name": "x"}})").substr(0, 8), "cloths: ");
}

}  // namespace
}  // namespace anyphys
