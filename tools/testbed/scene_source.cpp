#include "scene_source.hpp"

#include "anyphys/containers/assembly.hpp"

namespace anyphys::testbed {
namespace {

bool isFileName(const std::string& name) {
    return name.find('/') != std::string::npos ||
           (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0);
}

const CatalogueScene* findCatalogue(const std::string& name) {
    for (const CatalogueScene& c : sceneCatalogue())
        if (c.name == name) return &c;
    return nullptr;
}

// An assembly as its own scene: a ground plane and one copy standing on it, at default settings.
SceneSource assemblyScene(const std::string& name) {
    SceneSource s;
    s.name = name;
    s.description = "the built-in assembly '" + name + "' standing on the ground";
    const Scene& assembly = builtinAssembly(name);
    s.scene.settings.planar = assembly.settings.planar;
    BodyDef ground;
    ground.name = "ground";
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::plane(Vec3::UnitY(), 0.0);
    s.scene.bodies.push_back(ground);
    appendInstance(s.scene, assembly, Transform{Vec3(0, 0.01, 0), Quat::Identity()}, "");
    return s;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (const CatalogueScene& c : sceneCatalogue()) names.push_back(c.name);
    for (const std::string& a : builtinAssemblyNames()) names.push_back(a);
    return names;
}

SceneSource loadSceneSource(const std::string& nameOrFile) {
    if (const CatalogueScene* c = findCatalogue(nameOrFile)) {
        SceneSource s;
        s.name = c->name;
        s.description = c->description;
        s.scene = c->scene;
        s.check = c->check;
        return s;
    }
    if (isBuiltinAssembly(nameOrFile)) return assemblyScene(nameOrFile);
    if (isFileName(nameOrFile)) {
        SceneSource s;
        s.name = nameOrFile;
        s.description = "scene file " + nameOrFile;
        s.file = nameOrFile;
        s.scene = loadScene(nameOrFile);
        return s;
    }
    std::string known;
    for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
    throw Error("--scene: no built-in scene or assembly '" + nameOrFile + "' (a file needs a '/' or .json); known: " +
                known);
}

SceneSource sceneForBackend(const SceneSource& source, const Capabilities& caps) {
    if (caps.dimensions == 3 || source.scene.settings.planar) return source;
    const std::string variant = source.name + "_planar";
    if (findCatalogue(variant) || isBuiltinAssembly(variant)) return loadSceneSource(variant);
    throw Error("scene '" + source.name + "' is not planar and has no planar variant; this engine simulates planar worlds only");
}

}  // namespace anyphys::testbed
