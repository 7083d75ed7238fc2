// Runs the fuzz targets' inputs without libFuzzer (any compiler): every file of the seed corpus
// and every past crash under tests/fuzz/corpus/<target>/, so the normal test suite replays them.
// Usage: anyphys_fuzz_replay <scene_json|api_calls> FILE_OR_DIR...
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int fuzzSceneJson(const std::uint8_t* data, std::size_t size);
extern "C" int fuzzApiCalls(const std::uint8_t* data, std::size_t size);

namespace {

int replay(int (*target)(const std::uint8_t*, std::size_t), const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    target(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s <scene_json|api_calls> FILE_OR_DIR...\n", argv[0]);
        return 2;
    }
    const std::string name = argv[1];
    auto* target = name == "scene_json" ? &fuzzSceneJson : name == "api_calls" ? &fuzzApiCalls : nullptr;
    if (!target) {
        std::fprintf(stderr, "unknown fuzz target %s\n", argv[1]);
        return 2;
    }
    int count = 0;
    for (int i = 2; i < argc; ++i) {
        const std::filesystem::path p = argv[i];
        if (std::filesystem::is_directory(p)) {
            std::vector<std::filesystem::path> files;
            for (const auto& e : std::filesystem::directory_iterator(p)) files.push_back(e.path());
            std::sort(files.begin(), files.end());
            for (const auto& f : files) count += replay(target, f);
        } else {
            count += replay(target, p);
        }
    }
    if (count == 0) {
        std::fprintf(stderr, "no inputs found\n");
        return 1;
    }
    std::printf("%s: %d inputs replayed, none crashed\n", name.c_str(), count);
    return 0;
}
