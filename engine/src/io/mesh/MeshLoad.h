// MeshLoad.h: the mesh formats' readers (io/SceneLoad.cpp's format table calls them through
// load<>): OBJ with its MTL libraries (tinyobjloader), PLY, STL and OFF (Lantern's own
// readers). Each fills the one scene model: a root with a node per object, a mesh per node,
// materials and textures. loadBytes reads bytes in memory as if read from a path (whose folder
// an OBJ's MTL libraries and textures come from), for the fuzzers and the tests.
#pragma once

#include "io/LoadDiagnostics.h"

#include <lantern/FileOptions.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace lantern::mesh {

/// How a format reads a file's bytes (already charged to the budget; a reader may change them
/// in place, and hand them back once read).
using BytesReader = Result<Scene> (*)(std::vector<unsigned char>& bytes,
                                      const LoadOptions& options, const io::Diagnostics& diag);

Result<Scene> readObj(std::vector<unsigned char>& bytes, const LoadOptions& options,
                      const io::Diagnostics& diag);
Result<Scene> readPly(std::vector<unsigned char>& bytes, const LoadOptions& options,
                      const io::Diagnostics& diag);
Result<Scene> readStl(std::vector<unsigned char>& bytes, const LoadOptions& options,
                      const io::Diagnostics& diag);
Result<Scene> readOff(std::vector<unsigned char>& bytes, const LoadOptions& options,
                      const io::Diagnostics& diag);

/// Reads the scene file (a regular file of at most --max-size), charges it and hands it to
/// `reader`.
Result<Scene> loadFile(BytesReader reader, const std::filesystem::path& path,
                       const LoadOptions& options);
/// The same for bytes in memory as if read from `path`; what a reader throws becomes an error.
Result<Scene> loadBytes(BytesReader reader, std::vector<unsigned char> bytes,
                        const std::filesystem::path& path, const LoadOptions& options);

/// loadFile with its reader chosen: the shape of a loader in io/SceneLoad's format table.
template <BytesReader Reader>
Result<Scene> load(const std::filesystem::path& path, const LoadOptions& options) {
    return loadFile(Reader, path, options);
}

/// True when the first bytes of a file look like a binary STL of `size` bytes: 84 + 50 x the
/// count at byte 80. (A binary STL may start with "solid" too; the size decides.)
bool looksLikeBinaryStl(const unsigned char* head, std::size_t headSize, std::uint64_t size);

} // namespace lantern::mesh
