#pragma once
// A scene's bodies and joints created in a world: what game code holds on to after loading a
// scene file or an assembly (a ragdoll, a car), found by the names the scene gave them.
#include <string>
#include <vector>

#include "anyphys/body.hpp"
#include "anyphys/containers/scene.hpp"
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

}  // namespace anyphys
