#pragma once
// What the testbed opens: a built-in catalogue scene, a built-in assembly standing on a ground
// plane (`ragdoll`, `vehicle`, their `_planar` versions), or a scene file. A 2D engine gets the
// scene's planar variant when the catalogue has one.
#include <optional>
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"

namespace anyphys::testbed {

struct SceneSource {
    std::string name;                ///< catalogue or assembly name, or the file path
    std::string description;         ///< one line
    std::string file;                ///< the scene file's path; empty for a built-in scene
    Scene scene;
    std::optional<SceneCheck> check; ///< the catalogue scene's own measure, if it has one
};

/// Every name `loadSceneSource` takes besides files: the catalogue's scenes, then the assemblies.
std::vector<std::string> builtinSceneNames();

/// The named built-in scene, or the scene file at that path (a name with '/' or ending in .json).
/// Throws anyphys::Error naming what is known otherwise.
SceneSource loadSceneSource(const std::string& nameOrFile);

/// The scene a backend runs: `source` itself, or, for an engine without 3D worlds and a scene
/// that is not planar, its built-in planar variant (name + "_planar"). Throws anyphys::Error
/// saying so when there is none.
SceneSource sceneForBackend(const SceneSource& source, const Capabilities& caps);

}  // namespace anyphys::testbed
