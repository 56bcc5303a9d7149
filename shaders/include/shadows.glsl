// shadows.glsl: how much of a light reaches a point, from the frame's shadow maps (rendered by
// gpu/Shadows.cpp, planned by frame/Shadows.cpp). Each map holds the nearest depths a light
// sees in its own clip space with reversed Z; the point is moved along its normal by a few
// texels (normal offset) and compared with the map: 1 lit, 0 shadowed, in between at edges
// (the device's 2 x 2 filter, or PCF over kernel x kernel comparisons). A point light has six
// maps (cube faces); the point takes the face whose square holds it. Read with zero gradients,
// so the same code serves the fragment, vertex and compute stages (phong, gouraud, flat).
#ifndef LANTERN_SHADOWS_GLSL
#define LANTERN_SHADOWS_GLSL

#include "lantern_shared.h"
#include "specialization.glsl"
#include "uniforms.glsl"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_SHADOW_MAP) uniform sampler2DArrayShadow shadowMap;

struct ShadowData {
    mat4 clipFromView;  // the map's clip space from this view's eye space
    vec4 params;        // x: a texel's world size (per unit distance when y = 1), y: perspective
};

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_SHADOWS, std430) readonly buffer ShadowBlock {
    ShadowData shadows[];
};

// One comparison of `depth` with map `layer` at uv (reversed Z: lit where depth >= the map's).
float shadowCompare(vec2 uv, float layer, float depth) {
    return textureGrad(shadowMap, vec4(uv, layer, depth), vec2(0.0), vec2(0.0));
}

float shadowFiltered(vec2 uv, float layer, float depth) {
    if (SC_SHADOWS != LANTERN_SHADOW_PCF) return shadowCompare(uv, layer, depth);
    const int r = int(frame.shadowParams.y) / 2;
    const float texel = frame.shadowParams.x;
    float sum = 0.0;
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) sum += shadowCompare(uv + vec2(x, y) * texel, layer, depth);
    const float side = float(2 * r + 1);
    return sum / (side * side);
}

// The share of a light that reaches eye-space point V with unit normal n, from its `count`
// maps starting at `first`; `lightPosition`: the light's eye-space position (positional).
float shadowVisibility(uint first, uint count, vec3 V, vec3 n, vec3 lightPosition) {
    for (uint k = 0u; k < count; ++k) {
        const uint layer = first + k;
        ShadowData s = shadows[frame.viewIndex * frame.shadowMaps + layer];
        const float distance = s.params.y > 0.5 ? length(V - lightPosition) : 1.0;
        const vec3 p = V + n * (frame.shadowParams.z * s.params.x * distance);
        const vec4 c = s.clipFromView * vec4(p, 1.0);
        if (!(c.w > 0.0) || abs(c.x) > c.w || abs(c.y) > c.w) continue;  // another face's
        const vec3 ndc = c.xyz / c.w;
        return shadowFiltered(ndc.xy * 0.5 + 0.5, float(layer), ndc.z);
    }
    return 1.0;  // outside every map
}

#endif
