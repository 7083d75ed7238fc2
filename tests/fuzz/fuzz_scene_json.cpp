// libFuzzer target: the scene loader on arbitrary text (docs/reliability.md).
// Every input either loads or is refused with an anyphys::Error; anything else aborts. A scene
// that loads must save and load back to the same text (sceneToJson's documented round trip), and
// is then created in a world of one built backend (picked by the input) and stepped a few times.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "fuzz_support.hpp"

namespace {

using namespace anyphys;

// Keeps each input cheap: bigger scenes are only loaded and saved, not simulated.
constexpr std::size_t kMaxSimulatedBodies = 24;
constexpr int kMaxSweepsPerStep = 256;  // substeps x iterations
constexpr int kSteps = 4;

void simulate(Scene scene, std::size_t pick) {
    const auto& all = fuzz::backends();
    scene.settings.backend = all[pick % all.size()].name;
    scene.settings.workers = 1;  // threads are tests/threads' business
    if (scene.bodies.size() > kMaxSimulatedBodies || scene.joints.size() > kMaxSimulatedBodies) return;
    const long sweeps = long(scene.settings.substeps.value_or(4)) * scene.settings.iterations.value_or(10);
    if (sweeps > kMaxSweepsPerStep) return;
    fuzz::refusedOrDone([&] {
        World world(scene.settings, scene.materials);
        world.setWarningHandler([](const std::string&) {});
        createSceneObjects(world, scene);
        for (const FieldDef& f : scene.fields) world.addField(f);
        for (int i = 0; i < kSteps; ++i) world.step();
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    Scene scene;
    if (!fuzz::refusedOrDone([&] { scene = parseScene(text); })) return 0;
    std::string saved;
    Scene again;
    fuzz::refusedOrDone([&] {
        saved = sceneToJson(scene);
        again = parseScene(saved);
    });
    if (saved.empty() || sceneToJson(again) != saved) {
        std::fprintf(stderr, "fuzz: a loaded scene does not survive save + load:\n%s\n", saved.c_str());
        std::abort();
    }
    simulate(std::move(scene), std::hash<std::string>{}(text));
    return 0;
}
