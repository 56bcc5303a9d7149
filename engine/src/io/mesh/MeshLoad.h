// MeshLoad.h: the mesh formats' loaders (io/SceneLoad.cpp's format table calls them): OBJ with
// its MTL libraries (tinyobjloader), PLY, STL and OFF (Lantern's own readers). Each fills the
// one scene model: a root with a node per object, a mesh per node, materials and textures.
// The *Bytes entries load bytes as if read from `path` (whose folder an OBJ's MTL libraries and
// textures come from), for the fuzzers and the tests.
#pragma once

#include <lantern/FileOptions.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <filesystem>
#include <vector>

namespace lantern::mesh {

Result<Scene> loadObj(const std::filesystem::path& path, const LoadOptions& options);
Result<Scene> loadPly(const std::filesystem::path& path, const LoadOptions& options);
Result<Scene> loadStl(const std::filesystem::path& path, const LoadOptions& options);
Result<Scene> loadOff(const std::filesystem::path& path, const LoadOptions& options);

Result<Scene> loadObjBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                           const LoadOptions& options);
Result<Scene> loadPlyBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                           const LoadOptions& options);
Result<Scene> loadStlBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                           const LoadOptions& options);
Result<Scene> loadOffBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                           const LoadOptions& options);

/// True when the first bytes of a file look like a binary STL of `size` bytes: 84 + 50 x the
/// count at byte 80. (A binary STL may start with "solid" too; the size decides.)
bool looksLikeBinaryStl(const unsigned char* head, std::size_t headSize, std::uint64_t size);

} // namespace lantern::mesh
