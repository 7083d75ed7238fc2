#include "anyphys/scene_objects.hpp"

#include <map>

#include "anyphys/error.hpp"

namespace anyphys {

Body SceneObjects::body(const std::string& name) const {
    for (const Body& b : bodies)
        if (b.name() == name) return b;
    throw Error("no body named \"" + name + "\" in the scene");
}

Joint SceneObjects::joint(const std::string& name) const {
    for (const Joint& j : joints)
        if (j.name() == name) return j;
    throw Error("no joint named \"" + name + "\" in the scene");
}

SceneObjects createSceneObjects(World& world, const Scene& scene) {
    SceneObjects made;
    made.bodies.reserve(scene.bodies.size());
    std::map<std::string, Body> byName;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        try {
            made.bodies.push_back(world.createBody(scene.bodies[i]));
        } catch (const Error& e) {
            // The World names the BodyDef field; say which scene body it was.
            throw e.within("bodies[" + std::to_string(i) + "] \"" + scene.bodies[i].name + "\"");
        }
        byName.emplace(scene.bodies[i].name, made.bodies.back());
    }
    made.joints.reserve(scene.joints.size());
    for (std::size_t i = 0; i < scene.joints.size(); ++i) {
        const SceneJoint& sj = scene.joints[i];
        const std::string where = "joints[" + std::to_string(i) + "]" + (sj.def.name.empty() ? "" : " \"" + sj.def.name + "\"");
        const auto find = [&](const std::string& name, const char* field) {
            const auto it = byName.find(name);
            if (it == byName.end()) throw Error(where + ": " + field + " \"" + name + "\" names no body of the scene");
            return it->second;
        };
        JointDef def = sj.def;
        def.bodyA = sj.bodyA.empty() ? Body() : find(sj.bodyA, "bodyA");
        def.bodyB = find(sj.bodyB, "bodyB");
        try {
            made.joints.push_back(world.createJoint(def));
        } catch (const Error& e) {
            throw e.within(where);
        }
    }
    for (std::size_t i = 0; i < scene.fields.size(); ++i) {
        try {
            world.addField(scene.fields[i]);
        } catch (const Error& e) {
            throw Error("fields[" + std::to_string(i) + "]: " + e.what());
        }
    }
    for (std::size_t i = 0; i < scene.fluids.size(); ++i) {
        try {
            world.addFluid(scene.fluids[i]);
        } catch (const Error& e) {
            throw e.within("fluids[" + std::to_string(i) + "]");
        }
    }
    for (std::size_t i = 0; i < scene.cloths.size(); ++i) {
        try {
            world.addCloth(scene.cloths[i]);
        } catch (const Error& e) {
            throw e.within("cloths[" + std::to_string(i) + "]");
        }
    }
    return made;
}

Error asSceneFileError(const Error& error, const std::string& file) {
    std::string field = error.field();
    std::string message = error.what();
    const auto rename = [&](const std::string& from, const std::string& to) {
        field = to + field.substr(from.size());
        if (message.rfind(from, 0) == 0) message = to + message.substr(from.size());
    };
    if (field.rfind("WorldSettings", 0) == 0) rename("WorldSettings", "settings");
    else if (field == "backend") rename("backend", "settings.backend");
    return Error(error.kind(), field, file + ": " + message);
}

}  // namespace anyphys
