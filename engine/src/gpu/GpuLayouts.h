// GpuLayouts.h: C++ mirrors of the blocks in shaders/include/uniforms.glsl (std140 FrameBlock,
// std430 LightBlock and MaterialBlock, the push-constant DrawBlock). Every member is a 16-byte
// vector or a scalar run, so the layouts are the same in both languages; the static_asserts
// pin sizes and offsets, and tests/unit/GpuLayoutsTest.cpp checks them against the SPIR-V.
#pragma once

#include "lantern_shared.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace lantern::gpu {

struct alignas(16) Vec4 {
    float x = 0, y = 0, z = 0, w = 0;
};
struct alignas(16) UVec4 {
    std::uint32_t x = 0, y = 0, z = 0, w = 0;
};
struct alignas(16) Mat4 {
    float m[16] = {};  // column-major, as GLSL's mat4
};

// std140, set 0 binding 0; one per view (dynamic offset).
struct FrameBlock {
    Mat4 clipFromView;
    Vec4 globalAmbient;
    std::uint32_t lightCount = 0;
    std::uint32_t viewIndex = 0;
    float pointSize = 1.0f;  ///< gl_PointSize of point draws
    std::uint32_t shadowMaps = 0;  ///< shadow maps per view
    Vec4 shadowParams;  ///< x: a map texel in uv, y: PCF kernel, z: normal offset (texels)
};
static_assert(sizeof(FrameBlock) == 112);
static_assert(offsetof(FrameBlock, shadowMaps) == 92);
static_assert(offsetof(FrameBlock, shadowParams) == 96);
static_assert(offsetof(FrameBlock, clipFromView) == 0);
static_assert(offsetof(FrameBlock, globalAmbient) == 64);
static_assert(offsetof(FrameBlock, lightCount) == 80);
static_assert(offsetof(FrameBlock, viewIndex) == 84);

// std430 array element, set 0 binding 1.
struct LightData {
    Vec4 position;
    Vec4 ambient;
    Vec4 diffuse;
    Vec4 specular;
    Vec4 spotDirection;
    Vec4 attenuation;
    Vec4 spot;
    UVec4 info;
};
static_assert(sizeof(LightData) == 128);
static_assert(offsetof(LightData, position) == 0);
static_assert(offsetof(LightData, spotDirection) == 64);
static_assert(offsetof(LightData, attenuation) == 80);
static_assert(offsetof(LightData, spot) == 96);
static_assert(offsetof(LightData, info) == 112);

/// The frame set's dynamic offsets, in binding order: the view's FrameBlock, its lights as a
/// storage buffer, the same lights as a uniform buffer (LANTERN_BINDING_LIGHTS_UNIFORM).
using FrameSetOffsets = std::array<std::uint32_t, 3>;
inline FrameSetOffsets frameSetOffsets(std::uint64_t frame, std::uint64_t lights) {
    return {std::uint32_t(frame), std::uint32_t(lights), std::uint32_t(lights)};
}

struct MaterialSideData {
    Vec4 ambient;
    Vec4 diffuse;
    Vec4 specular;  // w = shininess
    Vec4 emission;
};
static_assert(sizeof(MaterialSideData) == 64);

// std430 array element, set 0 binding 2.
struct MaterialData {
    MaterialSideData front;
    MaterialSideData back;
    Vec4 params;  // x = alpha cutoff
    Vec4 uvRow0;  // KHR_texture_transform: u' = dot(uvRow0.xyz, (u, v, 1))
    Vec4 uvRow1;  //                        v' = dot(uvRow1.xyz, (u, v, 1))
    Vec4 pbrBase;   // PbrFactors::baseColor (metallic-roughness map)
    Vec4 pbrParams; // metallic, roughness, normal scale, occlusion strength
    Vec4 mapUv[8];  // uv rows of the metallic-roughness, normal, occlusion and emissive maps
};
static_assert(sizeof(MaterialData) == 336);
static_assert(offsetof(MaterialData, back) == 64);
static_assert(offsetof(MaterialData, params) == 128);
static_assert(offsetof(MaterialData, uvRow0) == 144);
static_assert(offsetof(MaterialData, uvRow1) == 160);
static_assert(offsetof(MaterialData, pbrBase) == 176);
static_assert(offsetof(MaterialData, mapUv) == 208);

// std430 array element, set 0 binding LANTERN_BINDING_SHADOWS: map k of view v at
// v * FrameBlock::shadowMaps + k (shaders/include/shadows.glsl).
struct ShadowData {
    Mat4 clipFromView;
    /// x: a texel's world size (per unit distance when y = 1), y: perspective, z: the margin
    /// (clip units) a lookup keeps from the map's edge, w: the light's size for PCSS (radius
    /// in world units when perspective, else the tangent of its angular radius)
    Vec4 params;
    /// Depth to distance from the map's eye plane: perspective, x / depth (x: the near
    /// plane); orthographic, (depth - y) / x.
    Vec4 depth;
};
static_assert(sizeof(ShadowData) == 96);
static_assert(offsetof(ShadowData, params) == 64);
static_assert(offsetof(ShadowData, depth) == 80);

// Push constants (std430): 124 bytes of the 128 every device guarantees.
struct DrawBlock {
    float viewFromModel[16];
    float normalMatrix[12];  // three vec4 columns (w unused)
    std::uint32_t materialIndex = 0;
    std::uint32_t drawIndex = 0;
    std::uint32_t flags = 0;  // bit 0: the primitive has vertex colours
    std::uint32_t flatJob = 0;  // per-triangle flat: the draw's FlatJob (set by gpu/)
};
static_assert(sizeof(DrawBlock) == 128);
static_assert(offsetof(DrawBlock, normalMatrix) == 64);
static_assert(offsetof(DrawBlock, materialIndex) == 112);
static_assert(offsetof(DrawBlock, drawIndex) == 116);
static_assert(offsetof(DrawBlock, flags) == 120);
static_assert(offsetof(DrawBlock, flatJob) == 124);

inline constexpr std::uint32_t kDrawFlagVertexColor = 1u;

// One instance of an instanced draw (shaders/include/instance.glsl): DrawBlock's transforms.
struct InstanceData {
    float viewFromModel[16];
    float normalMatrix[12];  // three vec4 columns (w unused)
};
static_assert(sizeof(InstanceData) == 112);
static_assert(offsetof(InstanceData, normalMatrix) == 64);

// Push constants of shaders/deform.comp: one deformation job (offsets in 32-bit words).
struct DeformJob {
    std::uint32_t count = 0, flatMode = 0, vertexCount = 0;
    std::uint32_t position = 0, normal = 0, joints = 0, weights = 0, influences = 0;
    std::uint32_t targets = 0, targetCount = 0, indices = LANTERN_DEFORM_NONE;
    std::uint32_t matrices = 0, morphWeights = 0;
    std::uint32_t outPosition = 0, outNormal = 0, outCentroid = 0;
};
static_assert(sizeof(DeformJob) == 64);
static_assert(offsetof(DeformJob, outCentroid) == 60);

// std430, set LANTERN_SET_FLAT binding LANTERN_BINDING_FLAT_JOBS (shaders/include/flatjob.glsl):
// one flat triangle draw lit once per triangle by flatlight.comp and drawn by flat.vert, which
// pulls its corners from the same words. The first members are its DrawBlock's; the offsets
// are 32-bit words of the geometry (or deformed) buffer.
struct FlatJob {
    float viewFromModel[16];
    float normalMatrix[12];
    std::uint32_t materialIndex = 0, drawIndex = 0, flags = 0, flatBase = 0;
    std::uint32_t count = 0;                     // triangles
    std::uint32_t indices = LANTERN_DEFORM_NONE; // the triangle list; NONE: vertices in order
    std::uint32_t positions = 0;
    std::uint32_t deformed = 0;                  // 1: positions are in the deformed buffer
    std::uint32_t colors = LANTERN_DEFORM_NONE;  // vertex colours (rgba); NONE: white
    std::uint32_t cull = 0;                      // LANTERN_FLAT_CULL_BACK | _FRONT_CLOCKWISE
    std::uint32_t writeNormals = 0;              // 1: the frame has AOVs
    std::uint32_t view = 0;
    Vec4 viewport;                               // x, y: half the view's size in pixels
    std::uint32_t texcoords = LANTERN_DEFORM_NONE;  // texture coordinates (uv); NONE: zero
    std::uint32_t texcoords1 = LANTERN_DEFORM_NONE; // the second set; NONE: zero
    std::uint32_t padding[2] = {};               // std430 rounds the struct to 16 bytes
};
static_assert(sizeof(FlatJob) == 192);
static_assert(offsetof(FlatJob, flatBase) == 124);
static_assert(offsetof(FlatJob, count) == 128);
static_assert(offsetof(FlatJob, view) == 156);
static_assert(offsetof(FlatJob, viewport) == 160);
static_assert(offsetof(FlatJob, texcoords) == 176);

} // namespace lantern::gpu
