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

/// The value of an id plane where no surface was drawn (the background): no glTF index or
/// semantic id a scene can hold (semantic ids are limited to 0 .. 2^32 - 2).
inline constexpr std::uint32_t kNoId = 0xFFFFFFFFu;

/// Which extra planes (arbitrary output values) a render produces (docs/aovs.md). Every plane
/// holds one surface per pixel, never a blend: with MSAA only the colour is resolved, the AOVs
/// come from a single-sampled pass (the surface at the pixel centre).
struct AovSet {
    bool depth = false;   ///< Z: linear eye-space depth -z_eye (FLT_MAX: nothing)
    bool normal = false;  ///< N.X, N.Y, N.Z: unit eye-space normal of the visible side (0: nothing)
    bool range = false;   ///< range: Euclidean distance from the eye |p_eye| (FLT_MAX: nothing)
    bool worldNormal = false;  ///< Nw.X, Nw.Y, Nw.Z: the normal in world space (0: nothing)
    bool uv = false;      ///< uv.U, uv.V: TEXCOORD_0 as the mesh holds it (0 where absent)
    bool instance = false;   ///< id.instance: the glTF node index (kNoId: nothing)
    bool primitive = false;  ///< id.mesh, id.primitive: mesh index, primitive index in it
    bool material = false;   ///< id.material: glTF material index (material count: the default)
    bool semantic = false;   ///< id.semantic: the node's "semantic_id" extra (0: none, background)
    /// Cryptomatte layers (docs/aovs.md): CryptoObject (node names), CryptoMaterial (material
    /// names), each `cryptomatteLevels` ranks of (name hash, coverage) from a second render of
    /// the draw ids at `cryptomatteSamples` x `cryptomatteSamples` positions per pixel.
    bool cryptoObject = false;
    bool cryptoMaterial = false;
    int cryptomatteLevels = 4;   ///< ranks per pixel: even, 2 .. 16 (2 per EXR layer)
    int cryptomatteSamples = 4;  ///< samples per pixel along each axis: 1 .. 16

    /// Any plane read from the draw and primitive ids.
    bool anyId() const { return instance || primitive || material || semantic || worldNormal; }
    /// Any plane of the surface attachment (texture coordinates, range).
    bool anySurface() const { return range || uv; }
    bool any() const { return depth || normal || anySurface() || anyId(); }
    /// Any Cryptomatte layer (made by a render of its own, not by the AOV attachments).
    bool anyCryptomatte() const { return cryptoObject || cryptoMaterial; }
};

/// The camera a picture was rendered with (double precision, Lantern's conventions): written to
/// EXR as the standard worldToCamera and worldToNDC attributes (and exact text copies).
struct CameraMetadata {
    glm::dmat4 viewFromWorld{1.0};  ///< right-handed eye space, camera looking down -Z
    glm::dmat4 clipFromView{1.0};   ///< Vulkan clip space (y down, depth 0..1)
    bool reversedDepth = true;      ///< clipFromView maps near to 1 (DepthMode::ReversedZ)
    bool wholeImage = true;         ///< the camera's view covers the whole image (one view)
};

/// One Cryptomatte layer (the Cryptomatte specification 1.2.0): per pixel, `levels` ranks of
/// (id, coverage) sorted by coverage, most first; an id is the float whose bits are
/// cryptomatteId(murmurHash3_32(name)); unused ranks are (0, 0). The background has no id, so
/// the coverages of an edge pixel sum to the share of its samples that hit a surface.
struct CryptomatteLayer {
    std::string name;  ///< the EXR type name: "CryptoObject", "CryptoMaterial"
    int levels = 0;    ///< ranks per pixel (channels: name00.R/G/B/A, name01... two ranks each)
    std::vector<float> ranks;  ///< width * height * levels * 2: id0, coverage0, id1, ...
    /// Every name drawn and its id's bits (written as the manifest), sorted by name.
    std::vector<std::pair<std::string, std::uint32_t>> manifest;
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
    std::vector<float> range;        ///< width * height: distance from the eye (AovSet::range)
    std::vector<float> worldNormal;  ///< 3 * width * height: world-space normal
    std::vector<float> uv;           ///< 2 * width * height: TEXCOORD_0 (u, v)
    /// The id planes asked for, width * height each (AovSet; kNoId where nothing was drawn).
    std::vector<std::uint32_t> instance, mesh, primitive, material, semantic;
    std::vector<CryptomatteLayer> cryptomatte;  ///< AovSet::cryptoObject, cryptoMaterial
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
