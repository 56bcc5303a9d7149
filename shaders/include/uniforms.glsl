// uniforms.glsl: the shader side of Lantern's GPU data. Mirrored in C++ by
// engine/src/gpu/GpuLayouts.h (static_asserted, and checked against this SPIR-V by a test).
// All positions and directions are in eye space (camera-relative, composed in double on the CPU).
#ifndef LANTERN_UNIFORMS_GLSL
#define LANTERN_UNIFORMS_GLSL

#include "lantern_shared.h"
#include "specialization.glsl"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_FRAME, std140) uniform FrameBlock {
    mat4 clipFromView;    // Vulkan clip space (y down, depth 0..1, reversed or not)
    vec4 globalAmbient;   // rgb: GL_LIGHT_MODEL_AMBIENT
    uint lightCount;
    uint viewIndex;
    float pointSize;      // gl_PointSize of point draws (pixels)
    uint shadowMaps;      // shadow maps per view (shadows.glsl)
    vec4 shadowParams;    // x: a map texel in uv (1 / resolution), y: PCF kernel, z: normal offset (texels)
} frame;

struct LightData {
    vec4 position;       // xyz eye space; w = 1 positional, w = 0 directional (xyz towards light)
    vec4 ambient;        // rgb
    vec4 diffuse;        // rgb
    vec4 specular;       // rgb
    vec4 spotDirection;  // xyz unit axis (eye space); w = 1 - cos(cutoff) for GL spots
    vec4 attenuation;    // kc, kl, kq (GL); w = 1/range (glTF; 0 = unlimited)
    vec4 spot;           // x = GL exponent; y = cos(outer), z = 1/(cos(inner) - cos(outer)) (glTF)
    uvec4 info;          // x = LANTERN_LIGHT_*, y = LANTERN_FALLOFF_*
};

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_LIGHTS, std430) readonly buffer LightBlock {
    LightData lights[];
};
// The same lights, bound as a uniform buffer. llvmpipe reads a uniform buffer at an index that
// differs between lanes (a light loop's counter) with one gather, a storage buffer one lane at
// a time (docs/performance.md).
layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_LIGHTS_UNIFORM, std140) uniform LightUniforms {
    LightData uniformLights[LANTERN_UNIFORM_LIGHTS];
};
// Field f of light i, from the buffer the variant reads (SC_LIGHTS_UNIFORM, resolved at
// pipeline creation: the other read is removed).
#define LIGHT(i, f) (SC_LIGHTS_UNIFORM ? uniformLights[i].f : lights[i].f)

struct MaterialSideData {
    vec4 ambient;   // rgb
    vec4 diffuse;   // rgba (a = opacity)
    vec4 specular;  // rgb; w = shininess
    vec4 emission;  // rgb
};

struct MaterialData {
    MaterialSideData front;
    MaterialSideData back;  // equal to front when the material has no back
    vec4 params;            // x = alpha cutoff
    vec4 uvRow0;            // KHR_texture_transform: u' = dot(uvRow0.xyz, vec3(u, v, 1))
    vec4 uvRow1;            //                        v' = dot(uvRow1.xyz, vec3(u, v, 1))
    vec4 pbrBase;           // the metallic-roughness factors' base colour
    vec4 pbrParams;         // metallic, roughness, normal scale, occlusion strength
    vec4 mapUv[8];          // uv rows of the metallic-roughness, normal, occlusion, emissive maps
};

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_MATERIALS, std430) readonly buffer MaterialBlock {
    MaterialData materials[];
};

layout(set = LANTERN_SET_TEXTURE, binding = LANTERN_BINDING_BASE_COLOR) uniform sampler2D baseColorTexture;
layout(set = LANTERN_SET_TEXTURE, binding = LANTERN_BINDING_METALLIC_ROUGHNESS) uniform sampler2D metallicRoughnessTexture;
layout(set = LANTERN_SET_TEXTURE, binding = LANTERN_BINDING_NORMAL) uniform sampler2D normalTexture;
layout(set = LANTERN_SET_TEXTURE, binding = LANTERN_BINDING_OCCLUSION) uniform sampler2D occlusionTexture;
layout(set = LANTERN_SET_TEXTURE, binding = LANTERN_BINDING_EMISSIVE) uniform sampler2D emissiveTexture;


// A fragment's texture coordinates: `uv` where the fragment is shaded (the centroid), `dx` and
// `dy` their screen derivatives taken from a copy interpolated at the pixel centre. Derivatives
// of centroid inputs are inaccurate where a 2x2 quad straddles a triangle edge (GLSL 4.60,
// 8.14.1): on lavapipe they picked coarse mip levels along every edge. Taken in main(), in
// uniform control flow.
struct SurfaceUv {
    vec2 uv;
    vec2 dx;
    vec2 dy;
};

// A derivative of (u, v) carried through the linear part of the transform (row0, row1).
vec2 transformedGradient(vec4 row0, vec4 row1, vec2 d) {
    return vec2(dot(row0.xy, d), dot(row1.xy, d));
}

// `s` read at (row0, row1) * (uv, 1), a KHR_texture_transform, with the derivatives carried
// through its linear part.
vec4 sampleTransformed(sampler2D s, vec4 row0, vec4 row1, SurfaceUv u) {
    vec2 st = vec2(dot(row0.xyz, vec3(u.uv, 1.0)), dot(row1.xyz, vec3(u.uv, 1.0)));
    return textureGrad(s, st, transformedGradient(row0, row1, u.dx),
                       transformedGradient(row0, row1, u.dy));
}

// The base-colour texture at the fragment.
vec4 baseColorTexel(SurfaceUv u, uint materialIndex) {
    return sampleTransformed(baseColorTexture, materials[materialIndex].uvRow0,
                             materials[materialIndex].uvRow1, u);
}

// The material's maps (LANTERN_MAP_*, with their second-set bits) that this variant compiles
// in.
uint materialMaps(uint materialIndex) {
    return SC_MAPS & uint(materials[materialIndex].params.y);
}

// The maps' texture coordinates: the primitive's set and its second (Primitive::texcoords1).
struct MapUv {
    SurfaceUv first;
    SurfaceUv second;
};

// The coordinates map `k` (0 metallic-roughness, 1 normal, 2 occlusion, 3 emissive) reads.
SurfaceUv mapSet(MapUv m, uint materialIndex, int k) {
    const uint bit = 1u << (LANTERN_MAP_SECOND_SET_SHIFT + uint(k));
    return (materialMaps(materialIndex) & bit) != 0u ? m.second : m.first;
}

// Map `k` at the fragment.
vec4 mapTexel(sampler2D s, MapUv m, uint materialIndex, int k) {
    return sampleTransformed(s, materials[materialIndex].mapUv[2 * k],
                             materials[materialIndex].mapUv[2 * k + 1], mapSet(m, materialIndex, k));
}

// Per draw: the 128 bytes every device guarantees. The flat-lighting pre-pass
// (flatlight.comp, LANTERN_DRAW_FROM_JOB) has no push-constant draw: it copies its job's draw
// into a variable of the same name, so the lighting functions below serve both.
#ifdef LANTERN_DRAW_FROM_JOB
struct DrawData {
    mat4 viewFromModel;
    vec4 normalMatrix[3];
    uint materialIndex;
    uint drawIndex;
    uint flags;
    uint flatJob;
};
DrawData draw;
#else
layout(push_constant, std430) uniform DrawBlock {
    mat4 viewFromModel;     // camera-relative, composed in double precision
    vec4 normalMatrix[3];   // columns of the normalised cofactor of viewFromModel's 3x3
    uint materialIndex;
    uint drawIndex;
    uint flags;
    uint flatJob;           // per-triangle flat: the draw's FlatJob (flatjob.glsl)
} draw;
#endif

#endif
