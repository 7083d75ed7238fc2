// Helpers shared by the subcommands.
#include "cli.hpp"

#include <fstream>

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

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(path + ": cannot open for writing");
    out << text;
    out.close();
    if (!out) throw Error(path + ": write failed");
}

}  // namespace anyphys::cli
