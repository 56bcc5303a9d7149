// Files in and out: glTF/GLB scenes, the built-in scenes, OpenEXR and PNG images.
// Every writer is atomic: the picture goes to a temporary file in the destination folder and
// is renamed into place, so a file is either complete or absent.
#pragma once

#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Log.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern {

class FrameView;  // lantern/Renderer.h

// --- Scenes ---------------------------------------------------------------------------------

/// The default of LoadOptions::maxBytes (--max-size): 2 GiB. A load's parsed JSON counts against
/// it, and a 1,000,000-node chain holds about 1 GB while tinygltf builds its model.
inline constexpr std::uint64_t kDefaultMaxBytes = std::uint64_t(2) << 30;

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
};

/// Loads a .gltf or .glb file (external buffers and images may not leave the file's folder),
/// validates it completely and returns the scene. Errors name the file, object and problem.
LANTERN_API Result<Scene> loadGltf(const std::filesystem::path& path,
                                   const LoadOptions& options = {});

/// The names accepted by builtinScene(), e.g. "spheres", "teapots".
LANTERN_API std::vector<std::string> builtinSceneNames();

/// A built-in scene by name (without the "builtin:" prefix).
LANTERN_API Result<Scene> builtinScene(std::string_view name);

/// Loads "builtin:NAME" or a glTF/GLB path.
LANTERN_API Result<Scene> loadScene(std::string_view pathOrBuiltin,
                                    const LoadOptions& options = {});

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

/// Writes R, G, B, A (and Z, N.X, N.Y, N.Z when the image has those AOVs; Z and N always as
/// 32-bit float) plus the image's metadata as string attributes.
LANTERN_API Result<void> writeExr(const std::filesystem::path& path, const Image& image,
                                  const ExrOptions& options = {});

/// Reads an EXR written by Lantern or any other tool: R, G, B, A (A = 1 when absent) and the
/// Z / N.X N.Y N.Z planes when present.
LANTERN_API Result<Image> readExr(const std::filesystem::path& path);

/// Writes an 8-bit sRGB PNG (colour un-premultiplied, clamped to [0,1], sRGB-encoded).
LANTERN_API Result<void> writePng(const std::filesystem::path& path, const Image& image);

/// The same from a frame left where the renderer put it (Renderer::renderView): the 8-bit rows
/// are made straight from the device's memory, with no float copy of the picture. Usage when
/// the view is no longer valid.
LANTERN_API Result<void> writePng(const std::filesystem::path& path, const FrameView& view);

/// A PNG written band by band (Renderer::renderBands): each band's rows are converted and
/// compressed as they come, so no 8-bit copy of the whole picture is held. The file is made
/// as writePng makes it, complete at finish() or not at all: a stream that fails or is dropped
/// unfinished leaves nothing at the path. Move-only.
class LANTERN_API PngStream {
public:
    /// Checks that the folder is writable and starts the file (a temporary beside `path`).
    static Result<PngStream> create(const std::filesystem::path& path, int width, int height);
    PngStream();
    PngStream(PngStream&&) noexcept;
    PngStream& operator=(PngStream&&) noexcept;
    ~PngStream();
    /// Appends the rows of `band`, whose width is the picture's (Usage when it is not, when it
    /// has more rows than are left, or when the view is no longer valid).
    Result<void> write(const FrameView& band);
    /// After the last row: ends the file and moves it to the path (Usage before the last row).
    Result<void> finish();

    struct Impl;

private:
    std::unique_ptr<Impl> m_impl;
};

/// Writes .exr or .png by extension (anything else is an InvalidInput error).
LANTERN_API Result<void> writeImage(const std::filesystem::path& path, const Image& image,
                                    const ExrOptions& exrOptions = {});

} // namespace lantern
