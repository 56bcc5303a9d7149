// libFuzzer target: arbitrary bytes as a .gltf or .glb file through the loader and the CPU
// side of a render (FuzzLoad.h). GltfStructureFuzz.cpp mutates documents as JSON instead.
#include "FuzzLoad.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    lantern::fuzz::loadAndPlan(data, size);
    return 0;
}
