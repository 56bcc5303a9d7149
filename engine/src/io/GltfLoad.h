// GltfLoad.h: the loader's in-memory entry point, for the fuzzer and tests: the bytes of a
// .gltf or .glb file as if read from `path` (whose folder external URIs resolve against).
#pragma once

#include <lantern/Io.h>

#include <filesystem>
#include <vector>

namespace lantern::gltf {

Result<Scene> loadGltfBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                            const LoadOptions& options);

} // namespace lantern::gltf
