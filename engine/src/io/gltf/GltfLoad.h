// GltfLoad.h: the loader's in-memory entry point, for the fuzzer and tests: the bytes of a
// .gltf or .glb file as if read from `path` (whose folder external URIs resolve against).
#pragma once

#include <lantern/FileOptions.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <filesystem>
#include <vector>

namespace lantern::gltf {

/// Loads a .gltf or .glb file (io/SceneLoad.cpp calls it, and turns what it throws into an
/// error): external buffers and images may not leave the file's folder; validated completely.
Result<Scene> loadGltf(const std::filesystem::path& path, const LoadOptions& options);

Result<Scene> loadGltfBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                            const LoadOptions& options);

} // namespace lantern::gltf
