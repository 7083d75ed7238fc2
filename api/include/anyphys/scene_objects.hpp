#pragma once
// A scene's bodies and joints created in a world: what game code holds on to after loading a
// scene file or an assembly (a ragdoll, a car), found by the names the scene gave them.
#include <string>
#include <vector>

#include "anyphys/body.hpp"
#include "anyphys/containers/scene.hpp"
#include "anyphys/error.hpp"
#include "anyphys/joint.hpp"
#include "anyphys/world.hpp"

namespace anyphys {

/// The handles createSceneObjects made, in scene order.
struct SceneObjects {
    std::vector<Body> bodies;
    std::vector<Joint> joints;

    /// The body of that name. Throws anyphys::Error naming it if the scene had none.
    Body body(const std::string& name) const;
    /// The joint of that name. Throws anyphys::Error naming it if the scene had none.
    Joint joint(const std::string& name) const;
};

/// Creates `scene`'s bodies, then its joints, in `world` (made with the scene's settings and
/// materials, or compatible ones). An error names the scene entry ("bodies[2] \"ball\": ...",
/// "joints[1] \"knee\": ..."); what was created before it stays in the world.
SceneObjects createSceneObjects(World& world, const Scene& scene);

/// An error the world raised while making a scene file's world or objects, as the file names
/// things: the file first (as its parse errors have it), and a setting by its JSON path
/// ("settings.backend" where the API says "WorldSettings.backend" or "backend"). Tools that open
/// scene files report errors through this, so a user reads the names of the file they wrote.
Error asSceneFileError(const Error& error, const std::string& file);

}  // namespace anyphys
