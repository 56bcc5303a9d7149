// libFuzzer target: arbitrary bytes as a .gltf or .glb file through the loader, then, for
// what loads, everything a render does before the GPU (scene validation, poses, bounds, the
// frame plan with its cameras, lights and draws). Crashes, hangs, sanitizer reports and
// uncaught exceptions are findings; refusals are the expected outcome for most inputs.
#include "io/GltfLoad.h"
#include "frame/Frame.h"

#include <lantern/Scene.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace {

// An empty folder for the nominal input path: external URIs in an input resolve against it
// and find nothing, so the fuzzer never reads files of the machine.
const std::filesystem::path& emptyFolder() {
    static const std::filesystem::path folder = [] {
        auto dir = std::filesystem::temp_directory_path() / ("lantern-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir);
        return dir;
    }();
    return folder;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lantern;
    LoadOptions options;
    options.maxBytes = std::uint64_t(4) << 20;
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    auto scene = gltf::loadGltfBytes(std::vector<unsigned char>(data, data + size),
                                     emptyFolder() / (glb ? "input.glb" : "input.gltf"), options);
    if (!scene) return 0;
    (void)summarize(*scene);
    RenderOptions render;
    render.width = 64;
    render.height = 48;
    for (double time : {0.0, 0.5, 1e6}) {
        for (int root = 0; root < int(scene->roots.size()) && root < 4; ++root) {
            render.root = root;
            (void)frame::buildFrame(*scene, render, time);
        }
    }
    return 0;
}
