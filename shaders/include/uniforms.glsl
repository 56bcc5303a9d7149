// uniforms.glsl: the shader side of Lantern's GPU data. Mirrored in C++ by
// engine/src/gpu/GpuLayouts.h (static_asserted, and checked against this SPIR-V by a test).
// All positions and directions are in eye space (camera-relative, composed in double on the CPU).
#ifndef LANTERN_UNIFORMS_GLSL
#define LANTERN_UNIFORMS_GLSL

#include "lantern_shared.h"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_FRAME, std140) uniform FrameBlock {
    mat4 clipFromView;    // Vulkan clip space (y down, depth 0..1, reversed or not)
    vec4 globalAmbient;   // rgb: GL_LIGHT_MODEL_AMBIENT
    uint lightCount;
    uint viewIndex;
    float pointSize;      // gl_PointSize of point draws (pixels)
    uint pad1;
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
};

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_MATERIALS, std430) readonly buffer MaterialBlock {
    MaterialData materials[];
};

layout(set = LANTERN_SET_TEXTURE, binding = LANTERN_BINDING_BASE_COLOR) uniform sampler2D baseColorTexture;

// The base-colour texture's coordinates after the material's KHR_texture_transform.
vec2 baseColorUv(vec2 uv, uint materialIndex) {
    const vec3 h = vec3(uv, 1.0);
    return vec2(dot(materials[materialIndex].uvRow0.xyz, h), dot(materials[materialIndex].uvRow1.xyz, h));
}

// Per draw: 124 of the 128 bytes every device guarantees.
layout(push_constant, std430) uniform DrawBlock {
    mat4 viewFromModel;     // camera-relative, composed in double precision
    vec4 normalMatrix[3];   // columns of the normalised cofactor of viewFromModel's 3x3
    uint materialIndex;
    uint drawIndex;
    uint flags;
} draw;

#endif
