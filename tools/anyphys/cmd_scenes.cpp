// `anyphys scenes [--json]` lists the built-in catalogue; `anyphys scene NAME` prints one as a
// scene file, so users can start their own from it.
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "anyphys/containers/scene_catalogue.hpp"
#include "cli.hpp"

namespace anyphys::cli {

Command addScenesCommand(CLI::App& parent) {
    auto json = std::make_shared<bool>(false);
    CLI::App* app = parent.add_subcommand("scenes", "List the built-in catalogue scenes");
    app->add_flag("--json", *json,
                  "Print JSON: name, description, duration (s), bodies, hasReference, check, compareByDefault, hardCase");
    return {app, [json] {
                const auto& catalogue = sceneCatalogue();
                if (*json) {
                    nlohmann::json list = nlohmann::json::array();
                    for (const CatalogueScene& c : catalogue) {
                        nlohmann::json check;  // null: the scene has no measure of its own
                        if (c.check)
                            check = {{"label", c.check->label},       {"unit", c.check->unit},
                                     {"expected", c.check->expected}, {"tolerance", c.check->tolerance},
                                     {"why", c.check->why}};
                        list.push_back({{"name", c.name},
                                        {"description", c.description},
                                        {"duration", c.duration},
                                        {"bodies", c.scene.bodies.size()},
                                        {"hasReference", static_cast<bool>(c.reference)},
                                        {"check", check},
                                        {"compareByDefault", c.compareByDefault},
                                        {"hardCase", c.hardCase}});
                    }
                    std::cout << nlohmann::json{{"scenes", list}}.dump(2) << '\n';
                    return 0;
                }
                std::size_t width = 4;
                for (const CatalogueScene& c : catalogue) width = std::max(width, c.name.size());
                std::printf("%-*s  %8s  %s\n", int(width), "name", "duration", "description");
                for (const CatalogueScene& c : catalogue)
                    std::printf("%-*s  %7gs  %s%s\n", int(width), c.name.c_str(), c.duration, c.description.c_str(),
                                c.hardCase ? " [hard case]" : c.compareByDefault ? "" : " [compare: only with --scenes]");
                return 0;
            }};
}

Command addSceneCommand(CLI::App& parent) {
    struct Options {
        std::string name;
        std::string out;
    };
    auto o = std::make_shared<Options>();
    CLI::App* app = parent.add_subcommand("scene", "Print a catalogue scene as a scene JSON file");
    app->add_option("NAME", o->name, "Catalogue scene name (see `anyphys scenes`)")->required();
    CLI::Option* out = app->add_option("--out", o->out, "Write to this file instead of stdout");
    return {app, [o, out] {
                const std::string json = sceneToJson(catalogueScene(o->name).scene);
                if (out->count())
                    writeFile(o->out, json.ends_with('\n') ? json : json + '\n');
                else
                    std::cout << json << (json.ends_with('\n') ? "" : "\n");
                return 0;
            }};
}

}  // namespace anyphys::cli
