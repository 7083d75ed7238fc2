// anyphys_demos NAME: the AgentPhysics thesis' other demos on any backend, the same code for
// every engine: volumes, materials, joints, dynamics, simultaneous. Each prints what it measured
// against what physics says; --out writes the trajectories in the `anyphys run` CSV format.
#include <cmath>
#include <cstdio>

#include "thesis_demos.hpp"

namespace anyphys::demo {

BodyDef groundPlane() {
    BodyDef g;
    g.name = "ground";
    g.type = BodyType::Static;
    g.shape = ShapeDef::plane(Vec3::UnitY(), 0.0);
    return g;
}

void printCheck(const std::string& what, double measured, double expected, const std::string& unit) {
    const double error = expected != 0.0 ? (measured - expected) / std::abs(expected) : measured;
    std::printf("  %-36s %.4g %s (expected %.4g, %+.1f %%)\n", (what + ":").c_str(), measured, unit.c_str(), expected, 100.0 * error);
}

}  // namespace anyphys::demo

int main(int argc, char** argv) {
    using namespace anyphys::demo;
    DemoMenu menu({
        {"volumes", "compound bodies: several collision volumes per body"},
        {"materials", "ice, wood and rubber side by side: sliding distances and rebounds"},
        {"joints", "every joint type the backend has, with limits and motors"},
        {"dynamics", "forces, torques, impulses and a spin about the intermediate axis"},
        {"simultaneous", "the same scene in one world per backend, stepped together"},
    });
    DemoOptions o;
    std::vector<std::string> backends;
    CLI::App app{"anyphys_demos: the thesis' demos on any backend", "anyphys_demos"};
    addCommonOptions(app, o, 4.0);
    menu.addTo(app);
    app.add_option("--backends", backends, "simultaneous: comma-separated backends (default: every built one)")->delimiter(',');
    return runMain(app, argc, argv, [&]() -> int {
        if (menu.listedOrChecked()) return 0;
        validate(o);
        const std::string& name = menu.chosen();
        if (name == "volumes") return runVolumes(o);
        if (name == "materials") return runMaterials(o);
        if (name == "joints") return runJoints(o);
        if (name == "dynamics") return runDynamics(o);
        if (backends.empty())
            for (const auto& info : anyphys::availableBackends()) backends.push_back(info.name);
        for (const std::string& b : backends) anyphys::backendInfo(b);  // an unknown name lists the known ones
        return runSimultaneous(o, backends);
    });
}
