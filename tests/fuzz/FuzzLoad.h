// FuzzLoad.h: what both glTF fuzz targets do with an input: load it as a .gltf or .glb file
// (external URIs resolve in an empty folder of this process, so nothing of the machine is
// read) and, for what loads, everything a render does before the GPU (scene validation,
// poses, bounds, the frame plan with its cameras, lights and draws). Crashes, hangs, sanitizer
// reports and uncaught exceptions are findings; refusals are the expected outcome.
#pragma once

#include "io/gltf/GltfLoad.h"
#include "frame/Frame.h"

#include <lantern/Scene.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace lantern::fuzz {

inline const std::filesystem::path& emptyFolder() {
    static const std::filesystem::path folder = [] {
        auto dir = std::filesystem::temp_directory_path() / ("lantern-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir);
        return dir;
    }();
    return folder;
}

inline void loadAndPlan(const std::uint8_t* data, std::size_t size) {
    LoadOptions options;
    options.maxBytes = std::uint64_t(4) << 20;
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    auto scene = gltf::loadGltfBytes(std::vector<unsigned char>(data, data + size),
                                     emptyFolder() / (glb ? "input.glb" : "input.gltf"), options);
    if (!scene) return;
    (void)summarize(*scene);
    RenderOptions render;
    render.width = 64;
    render.height = 48;
    for (double time : {0.0, 0.5, 1e6})
        for (int root = 0; root < int(scene->roots.size()) && root < 4; ++root) {
            render.root = root;
            (void)frame::buildFrame(*scene, render, time);
        }
}

} // namespace lantern::fuzz
