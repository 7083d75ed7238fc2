// Helpers shared by the subcommands.
#include "cli.hpp"

#include <fstream>
#include <map>

namespace anyphys::cli {

std::string join(const std::vector<std::string>& items, std::string_view separator) {
    std::string out;
    for (const std::string& item : items) {
        if (!out.empty()) out += separator;
        out += item;
    }
    return out;
}

Integrator parseIntegrator(const std::string& option, const std::string& name) {
    if (auto integrator = fromString<Integrator>(name)) return *integrator;
    throw Error::invalid(option, "\"" + name + "\"", "must be one of " + allowedNames<Integrator>());
}

std::vector<Body> createSceneBodies(World& world, const Scene& scene) {
    std::vector<Body> bodies;
    bodies.reserve(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        try {
            bodies.push_back(world.createBody(scene.bodies[i]));
        } catch (const Error& e) {
            // The World names the BodyDef field; say which scene body it was.
            throw Error("bodies[" + std::to_string(i) + "] \"" + scene.bodies[i].name + "\": " + e.what());
        }
    }
    return bodies;
}

std::vector<Joint> createSceneJoints(World& world, const Scene& scene, const std::vector<Body>& bodies) {
    std::map<std::string, Body> byName;
    for (std::size_t i = 0; i < bodies.size(); ++i) byName.emplace(scene.bodies[i].name, bodies[i]);
    std::vector<Joint> joints;
    joints.reserve(scene.joints.size());
    for (std::size_t i = 0; i < scene.joints.size(); ++i) {
        const SceneJoint& sj = scene.joints[i];
        JointDef def = sj.def;
        def.bodyA = sj.bodyA.empty() ? Body() : byName.at(sj.bodyA);  // the loader checked the names
        def.bodyB = byName.at(sj.bodyB);
        try {
            joints.push_back(world.createJoint(def));
        } catch (const Error& e) {
            throw Error("joints[" + std::to_string(i) + "]" + (def.name.empty() ? "" : " \"" + def.name + "\"") +
                        ": " + e.what());
        }
    }
    return joints;
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(path + ": cannot open for writing");
    out << text;
    out.close();
    if (!out) throw Error(path + ": write failed");
}

}  // namespace anyphys::cli
