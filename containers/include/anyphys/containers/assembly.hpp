#pragma once
// Assemblies: scenes placed into other scenes, moved, turned and renamed (a ragdoll, a car, a
// chain). In scene files through "instances"; from C++ by loading an assembly once and calling
// appendInstance as often as needed. Built-in assemblies are named without ".json".
#include <cstddef>
#include <string>
#include <vector>

#include "anyphys/containers/scene.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

/// How scene files may pull in others. Scene files are untrusted input: by default an instance
/// may only load files under the including file's folder, or a built-in assembly.
struct SceneLoadOptions {
    /// Folder that relative instance paths start from. loadScene sets it to the file's folder;
    /// parseScene without it resolves built-in assemblies only.
    std::string folder;
    /// Allow absolute paths and ".." leaving the including file's folder. Default false.
    bool allowOutsideFolder = false;
    /// Deepest nesting of instances (a scene with instances is depth 1). Default 8.
    int maxDepth = 8;
    /// Most bodies a scene may hold with all its instances expanded. Default 100 000.
    std::size_t maxBodies = 100000;
};

/// Copies `assembly`'s bodies and joints into `target`: positions, orientations, velocities,
/// anchors and axes moved by `pose`; body and joint names prefixed (`prefix + name`); the
/// assembly's materials added to the target's library (a name already there must mean the same
/// material). Its settings are not copied. Throws anyphys::Error naming what clashes (a body
/// name already used, a material with other values); the target is unchanged then.
void appendInstance(Scene& target, const Scene& assembly, const Transform& pose, const std::string& prefix);

/// The built-in assemblies: "ragdoll", "ragdoll_planar", "vehicle", "vehicle_planar"
/// (docs/assemblies.md gives their bodies, joints, dimensions and limits).
std::vector<std::string> builtinAssemblyNames();
bool isBuiltinAssembly(const std::string& name);
/// Throws anyphys::Error listing the known names for an unknown one.
const Scene& builtinAssembly(const std::string& name);

}  // namespace anyphys
