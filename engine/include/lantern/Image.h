// Image: a rendered picture in memory: linear RGBA float pixels plus optional AOV planes.
#pragma once

#include <glm/mat4x4.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lantern {

/// Which extra planes (arbitrary output values) a render produces.
struct AovSet {
    bool depth = false;   ///< Z: eye-space distance from the eye to the surface (FLT_MAX: nothing)
    bool normal = false;  ///< N.X, N.Y, N.Z: unit eye-space normal of the visible side (0: nothing)
    bool any() const { return depth || normal; }
};

/// The camera a picture was rendered with (double precision, Lantern's conventions): written to
/// EXR as the standard worldToCamera and worldToNDC attributes (and exact text copies).
struct CameraMetadata {
    glm::dmat4 viewFromWorld{1.0};  ///< right-handed eye space, camera looking down -Z
    glm::dmat4 clipFromView{1.0};   ///< Vulkan clip space (y down, depth 0..1)
    bool reversedDepth = true;      ///< clipFromView maps near to 1 (DepthMode::ReversedZ)
    bool wholeImage = true;         ///< the camera's view covers the whole image (one view)
};

/// A picture: width x height pixels, top row first, each pixel RGBA as 32-bit floats in
/// linear light, colour premultiplied by alpha (the OpenEXR convention). Values are HDR:
/// not clamped, but always finite (Lantern guarantees no NaN or Inf reaches an Image).
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;    ///< 4 * width * height floats
    std::vector<float> depth;   ///< width * height floats when the depth AOV was asked for
    std::vector<float> normal;  ///< 3 * width * height floats when the normal AOV was asked for
    /// Key/value metadata written as EXR string attributes (camera matrices, frame, time...).
    std::vector<std::pair<std::string, std::string>> metadata;
    std::optional<CameraMetadata> camera;  ///< the first view's camera, when rendered
    double framesPerSecond = 0.0;          ///< > 0: written as EXR's framesPerSecond

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * std::size_t(h) * 4, 0.0f) {}

    std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }
    float* pixel(int x, int y) { return rgba.data() + (std::size_t(y) * width + x) * 4; }
    const float* pixel(int x, int y) const {
        return rgba.data() + (std::size_t(y) * width + x) * 4;
    }
};

} // namespace lantern
