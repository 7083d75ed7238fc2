#pragma once
// A scene: settings, materials, bodies and joints, as loaded from or saved to a JSON file.
#include <map>
#include <string>
#include <vector>

#include "anyphys/containers/material_library.hpp"
#include "anyphys/defs.hpp"
#include "anyphys/fields/field_def.hpp"
#include "anyphys/fields/particle_defs.hpp"
#include "anyphys/joint_def.hpp"
#include "anyphys/world_settings.hpp"

namespace anyphys {

/// A joint of a scene: its def (with null body handles) and its bodies by name.
struct SceneJoint {
    JointDef def;
    std::string bodyA;  ///< "" (written as omitted): the joint holds bodyB to the static world
    std::string bodyB;
    /// Its "userData" in the file, as JSON text (any value: {"sound": "clank"}); "" when absent.
    /// Saved back as it came. An unsigned integer is also def.userData.
    std::string userData;
};

struct Scene {
    WorldSettings settings;
    MaterialLibrary materials;
    std::vector<BodyDef> bodies;  ///< each with a unique, non-empty name
    std::vector<SceneJoint> joints;  ///< created after the bodies, in this order
    std::vector<FieldDef> fields;    ///< force fields (buoyancy, drag, wind, explosion), added in this order
    std::vector<FluidDef> fluids;    ///< fluid blocks, added in this order
    std::vector<ClothDef> cloths;    ///< cloth sheets, added in this order
    /// Each body's "userData" in the file, as JSON text, by body name (bodies without one are
    /// absent). Saved back as it came; an unsigned integer is also that BodyDef's userData.
    std::map<std::string, std::string> bodyUserData;
};


struct SceneLoadOptions;  // assembly.hpp: what instances may load

/// Parses scene JSON text. Throws anyphys::Error whose message names the JSON path, the value
/// and the rule, e.g. "bodies[3].shape.radius: must be > 0, got -1". Its "instances" may name
/// built-in assemblies only, unless `options.folder` says where files are.
Scene parseScene(const std::string& jsonText);
Scene parseScene(const std::string& jsonText, const SceneLoadOptions& options);
/// Reads and parses a scene file; the message of an error starts with the file name. Its
/// "instances" load files under its folder (see SceneLoadOptions), expanded into the scene.
Scene loadScene(const std::string& path);
Scene loadScene(const std::string& path, const SceneLoadOptions& options);
/// Serialises a scene; parseScene(sceneToJson(s)) reproduces s exactly (doubles round-trip).
std::string sceneToJson(const Scene& scene);
/// Writes sceneToJson(scene) to a file; throws anyphys::Error if it cannot.
void saveScene(const Scene& scene, const std::string& path);

}  // namespace anyphys
