// What the image writers and readers share with `lantern compare`: the bytes a PNG holds for an
// Image (so that a render compared with a PNG reference is quantised exactly as
// `lantern render -o x.png` writes it), and the reading of an EXR's data window.
#pragma once

#include <lantern/Image.h>
#include <lantern/Result.h>

#include <glm/mat4x4.hpp>

#include <cstddef>
#include <optional>
#include <filesystem>
#include <utility>
#include <vector>

namespace lantern::io {

/// Refuses (InvalidInput, naming `path`) an image without pixels, with a wrong pixel count,
/// or whose AOV planes or Cryptomatte layers do not match its size.
Result<void> checkImage(const Image& image, const std::filesystem::path& path);

/// 8-bit RGBA, un-premultiplied, clamped to [0,1], sRGB-encoded (non-finite values read as 0).
std::vector<unsigned char> pngPixels(const Image& image);

/// How a PNG's rows are compressed. Lantern writes for speed: zlib level 2 and the
/// Up filter on every row encode a 1080p render 2.5 times faster than libpng's default (level
/// 6, every filter tried per row; `everyFilter`) for a file 1.7 times larger
/// (lantern_microbench --benchmark_filter=BM_WritePng; docs/performance.md).
struct PngEncoding {
    int zlibLevel = 2;
    bool everyFilter = false;
};

/// The PNG file's bytes for `image` (pngPixels, then libpng).
Result<std::vector<unsigned char>> encodePng(const Image& image, const PngEncoding& encoding);

/// The standard EXR camera attributes of a picture: worldToCamera (OpenEXR's left-handed camera
/// space, looking down +Z) and worldToNDC ((0,0) top-left to (1,1) bottom-right), as the file
/// stores them, in float. Nothing when either would hold a value that is not finite in float
/// (a camera 1e300 from the origin): such a matrix is left out of the header, never written
/// as Inf or NaN.
struct ExrCameraMatrices {
    glm::mat4 worldToCamera{1.0f}, worldToNdc{1.0f};
};
std::optional<ExrCameraMatrices> exrCameraMatrices(const CameraMetadata& camera);

/// An EXR data window, corners inclusive (Imath::Box2i's min and max, without OpenEXR's headers).
struct ExrWindow {
    int minX = 0, minY = 0, maxX = -1, maxY = -1;
};


/// The base pointer OpenEXR wants for a slice whose pixel at the window's minimum corner is
/// `first`: OpenEXR addresses pixel (x, y) at base + x * xStride + y * yStride.
inline char* exrSliceBase(float* first, const ExrWindow& window, std::size_t xStride,
                          std::size_t yStride) {
    return reinterpret_cast<char*>(first) - (std::ptrdiff_t(window.minX) * std::ptrdiff_t(xStride) +
                                             std::ptrdiff_t(window.minY) * std::ptrdiff_t(yStride));
}

} // namespace lantern::io
