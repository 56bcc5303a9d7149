// Files in and out: glTF/GLB scenes, the built-in scenes, OpenEXR and PNG images.
// Every writer is atomic: the picture goes to a temporary file in the destination folder and
// is renamed into place, so a file is either complete or absent.
#pragma once

#include <lantern/Compare.h>
#include <lantern/Export.h>
#include <lantern/FileOptions.h>
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

/// Loads a .gltf or .glb file (external buffers and images may not leave the file's folder),
/// validates it completely and returns the scene. Errors name the file, object and problem.
LANTERN_API Result<Scene> loadGltf(const std::filesystem::path& path,
                                   const LoadOptions& options = {});

/// The names accepted by builtinScene(), e.g. "spheres", "teapots".
LANTERN_API std::vector<std::string> builtinSceneNames();

/// A built-in scene by name (without the "builtin:" prefix).
LANTERN_API Result<Scene> builtinScene(std::string_view name);

/// Loads "builtin:NAME" or a scene file of any format Lantern reads: glTF (.gltf, .glb), OBJ
/// with its MTL libraries, PLY, STL, OFF (docs/scene-format-support.md). The format is chosen by
/// the file's extension, or when that names none of them, by its first bytes.
LANTERN_API Result<Scene> loadScene(std::string_view pathOrBuiltin,
                                    const LoadOptions& options = {});

/// The extensions of the scene files loadScene reads, lower case with the dot (".gltf", ".obj").
LANTERN_API std::vector<std::string> sceneFileExtensions();

// --- Images ---------------------------------------------------------------------------------

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

// --- Images compared (lantern/Compare.h) ------------------------------------------------------

/// Reads an .exr (every channel, as 32-bit float) or a .png (8 or 16 bits, values / max, sRGB
/// encoded). Errors name the file and the problem.
LANTERN_API Result<CompareImage> readCompareImage(const std::filesystem::path& path);

/// A rendered Image as `lantern render` would have written it: Linear (R, G, B, A and the AOV
/// planes, as in an EXR) or Srgb (R, G, B, A quantised to 8 bits exactly as writePng does).
LANTERN_API CompareImage toCompareImage(const Image& image, PixelEncoding encoding,
                                        std::string source = "render");

/// readCompareImage both, then compareImages.
LANTERN_API Result<CompareReport> compareFiles(const std::filesystem::path& reference,
                                               const std::filesystem::path& test,
                                               const CompareOptions& options = {});

} // namespace lantern
