// anyphys_effects NAME: the special effects of docs/fields.md on any backend, the same code for
// every engine: boat (buoyancy waves), dambreak (fluid and crates), flag (cloth in wind),
// explosion (a stack blown apart). Each prints what it measured; --out writes the bodies'
// trajectories in the `anyphys run` CSV format.
#include "effects_demos.hpp"

namespace anyphys::demo {

Body staticBlock(World& world, const std::string& name, const Vec3& lo, const Vec3& hi) {
    BodyDef def;
    def.name = name;
    def.type = BodyType::Static;
    def.shape = ShapeDef::box(0.5 * (hi - lo));
    def.position = 0.5 * (lo + hi);
    return world.createBody(def);
}

}  // namespace anyphys::demo

int main(int argc, char** argv) {
    using namespace anyphys::demo;
    DemoMenu menu({
        {"boat", "a boat riding waves of a buoyancy field"},
        {"dambreak", "a water column collapses and carries crates (position-based fluid)"},
        {"flag", "a cloth flag on a pole in the wind"},
        {"explosion", "an explosion at the foot of a stack of crates"},
    });
    DemoOptions o;
    CLI::App app{"anyphys_effects: buoyancy, fluid, cloth and explosion demos on any backend", "anyphys_effects"};
    addCommonOptions(app, o, 3.0);
    menu.addTo(app);
    return runMain(app, argc, argv, [&]() -> int {
        if (menu.listedOrChecked()) return 0;
        validate(o);
        const std::string& name = menu.chosen();
        if (name == "boat") return runBoat(o);
        if (name == "dambreak") return runDamBreak(o);
        if (name == "flag") return runFlag(o);
        return runExplosion(o);
    });
}
