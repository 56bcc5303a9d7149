// MeshFuzz.cpp: the mesh formats' libFuzzer targets, one per format, built from this file with
// LANTERN_FUZZ_READER (mesh::readObj ...) and LANTERN_FUZZ_NAME ("input.obj" ...) defined
// (tests/fuzz/CMakeLists.txt). What each does with an input: load it as an OBJ, PLY, STL or
// OFF file in an empty folder of this process (an OBJ's input may carry an MTL library after a
// line "#MTL", written there as "m.mtl" so that `mtllib m.mtl` reads it), then everything a
// render does before the GPU (FuzzLoad.h). Crashes, hangs, sanitizer reports and uncaught
// exceptions are findings; refusals are the expected outcome.
#include "FuzzLoad.h"
#include "io/mesh/MeshLoad.h"

#include <fstream>
#include <string_view>

namespace lantern::fuzz {

inline void planScene(const Scene& scene) {
    (void)summarize(scene);
    RenderOptions render;
    render.width = 64;
    render.height = 48;
    (void)frame::buildFrame(scene, render, 0.0);
}

inline void loadMeshAndPlan(mesh::BytesReader reader, const char* name, const std::uint8_t* data,
                            std::size_t size) {
    std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::size_t mtl = text.find("\n#MTL\n");
    const std::filesystem::path folder = emptyFolder();
    if (mtl != std::string_view::npos) {
        std::ofstream(folder / "m.mtl", std::ios::binary) << text.substr(mtl + 6);
        text = text.substr(0, mtl + 1);
    } else {
        std::filesystem::remove(folder / "m.mtl");
    }
    LoadOptions options;
    options.maxBytes = std::uint64_t(64) << 20;
    auto scene = mesh::loadBytes(reader, std::vector<unsigned char>(text.begin(), text.end()),
                                 folder / name, options);
    if (scene) planScene(*scene);
}

} // namespace lantern::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    lantern::fuzz::loadMeshAndPlan(&lantern::mesh::LANTERN_FUZZ_READER, LANTERN_FUZZ_NAME, data, size);
    return 0;
}
