// FileOptions.h: how files are read and written: a load's bounds and folders, an EXR's
// encoding. The entry points that take them are in lantern/Io.h.
#pragma once

#include <lantern/Export.h>
#include <lantern/Log.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern {

// --- Scenes ---------------------------------------------------------------------------------

/// The default of LoadOptions::maxBytes (--max-size): 2 GiB. A load's parsed JSON counts against
/// it, and a 1,000,000-node chain holds about 1 GB while tinygltf builds its model.
inline constexpr std::uint64_t kDefaultMaxBytes = std::uint64_t(2) << 30;

/// Which of the file's axes points up (--up). Lantern's world is +Y up, as glTF's and OBJ's
/// usually are; CAD files, most STL and many PLY scans are +Z up. Z: the loaded scene is
/// turned -90 degrees about X (its +Z becomes +Y, its +Y becomes -Z) by a node above each of
/// its root nodes, whatever the format.
enum class UpAxis { Y, Z };

LANTERN_API const char* toString(UpAxis up) noexcept;  ///< "y", "z"
LANTERN_API std::optional<UpAxis> parseUpAxis(std::string_view text) noexcept;

struct LoadOptions {
    /// Largest accepted file, buffer or image, in bytes (--max-size), and the most memory one
    /// load may hold for what the file decides: the parsed JSON and the models built from it,
    /// buffers, decoded accessors and images. Each is charged before it is allocated; a file
    /// that would go beyond is refused with the object named.
    std::uint64_t maxBytes = kDefaultMaxBytes;
    LogSink log;  ///< warnings about things skipped or repaired
    /// Folders besides the scene's own that external buffers and images may come from
    /// (--allow-folder): a URI may then contain ".." and a symbolic link may lead there. Each
    /// file is still resolved to its real path and refused unless that lies inside one of them.
    std::vector<std::filesystem::path> allowedFolders;
    /// KHR_materials_variants: the variant whose materials the primitives take (--variant);
    /// empty: the file's own. A name the file does not have is refused, listing its variants.
    std::string variant;
    UpAxis up = UpAxis::Y;  ///< the file's up axis (--up)
};

// --- Images ---------------------------------------------------------------------------------

enum class ExrCompression { None, Rle, Zips, Zip, Piz, Pxr24, B44, B44a, Dwaa, Dwab };

LANTERN_API const char* toString(ExrCompression compression) noexcept;  ///< "none", "zip", ...
LANTERN_API std::optional<ExrCompression> parseExrCompression(std::string_view text) noexcept;

struct ExrOptions {
    bool half = false;  ///< 16-bit half RGBA (values beyond +-65504 clamp to +-65504)
    ExrCompression compression = ExrCompression::Zip;
    /// zlib level of the zip and zips compressions, 1 (fastest) to 9 (smallest). Lantern's 2
    /// writes a 1080p frame about 1.8x as fast as OpenEXR's default 4, for a file about 7%
    /// larger (docs/performance.md); every reader decodes any level.
    int zipLevel = 2;
    /// Threads that compress one file's blocks of lines at once (OpenEXR's thread pool, shared
    /// by the process): 0, one per core; 1, this thread alone.
    int threads = 0;
    /// Set to the number of values clamped to the half range, when `half` is on.
    std::uint64_t* clampedCount = nullptr;
};

} // namespace lantern
