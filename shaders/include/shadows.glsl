// shadows.glsl: how much of a light reaches a point, from the frame's shadow maps (rendered by
// gpu/Shadows.cpp, planned by frame/Shadows.cpp). Each map holds the nearest depths a light
// sees in its own clip space with reversed Z; the point is moved along its normal by a few
// texels (normal offset) and compared with the map: 1 lit, 0 shadowed, in between at edges
// (the device's 2 x 2 filter, PCF over kernel x kernel comparisons, or PCSS). A point light has
// six maps (cube faces), a directional light one per cascade; the point takes the first map
// whose square holds it. Read with zero gradients,
// so the same code serves the fragment, vertex and compute stages (phong, gouraud, flat).
#ifndef LANTERN_SHADOWS_GLSL
#define LANTERN_SHADOWS_GLSL

#include "lantern_shared.h"
#include "specialization.glsl"
#include "uniforms.glsl"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_SHADOW_MAP) uniform sampler2DArrayShadow shadowMap;
// The same maps' depths, nearest texel, for PCSS's blocker search.
layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_SHADOW_DEPTH) uniform sampler2DArray shadowDepth;

struct ShadowData {
    mat4 clipFromView;  // the map's clip space from this view's eye space
    vec4 params;        // x: a texel's world size (per unit distance when y = 1), y: perspective,
                        // z: the margin (clip units) kept from the edge, w: PCSS's light size
    vec4 depth;         // depth to distance: perspective x / depth, orthographic (depth - y) / x
};

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_SHADOWS, std430) readonly buffer ShadowBlock {
    ShadowData shadows[];
};

// One comparison of `depth` with map `layer` at uv (reversed Z: lit where depth >= the map's).
float shadowCompare(vec2 uv, float layer, float depth) {
    return textureGrad(shadowMap, vec4(uv, layer, depth), vec2(0.0), vec2(0.0));
}

// kernel x kernel comparisons spread evenly over a square `radius` texels from uv each way.
float shadowPcf(vec2 uv, float layer, float depth, float radius) {
    const int side = int(frame.shadowParams.y);
    const float step = side > 1 ? 2.0 * radius / float(side - 1) : 0.0;
    const vec2 corner = uv - vec2(side > 1 ? radius : 0.0) * frame.shadowParams.x;
    float sum = 0.0;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            sum += shadowCompare(corner + vec2(x, y) * step * frame.shadowParams.x, layer, depth);
    return sum / float(side * side);
}

// Distance from the map's eye plane of a map depth (reversed Z).
float shadowDistance(ShadowData s, float depth) {
    return s.params.y > 0.5 ? s.depth.x / max(depth, 1e-30) : (depth - s.depth.y) / s.depth.x;
}

// The penumbra (texels, each way) a light of size params.w casts at distance dr behind a
// blocker at db: similar triangles through the light's disc (perspective: radius, world
// units; orthographic: the tangent of its angular radius).
float shadowPenumbra(ShadowData s, float dr, float db) {
    return s.params.y > 0.5 ? s.params.w * (dr - db) / (max(db, 1e-30) * s.params.x * dr)
                            : s.params.w * (dr - db) / s.params.x;
}

// Percentage closer soft shadows (Fernando 2005): the blockers' mean distance over the region
// from which a blocker could hide part of the light (the penumbra a blocker halfway would
// cast, at most LANTERN_PCSS_MAX_TEXELS), then PCF over the penumbra they cast.
#define LANTERN_PCSS_MAX_TEXELS 32.0
float shadowSoft(ShadowData s, vec2 uv, float layer, float depth) {
    const float dr = shadowDistance(s, depth);
    const float search = clamp(shadowPenumbra(s, dr, 0.5 * dr), 1.0, LANTERN_PCSS_MAX_TEXELS);
    const int side = max(int(frame.shadowParams.y), 2);
    const float step = 2.0 * search / float(side - 1) * frame.shadowParams.x;
    const vec2 corner = uv - vec2(search * frame.shadowParams.x);
    float blockers = 0.0, sum = 0.0;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const float z = textureLod(shadowDepth, vec3(corner + vec2(x, y) * step, layer), 0.0).r;
            if (z > depth) {  // nearer the light than the point (reversed Z)
                blockers += 1.0;
                sum += shadowDistance(s, z);
            }
        }
    if (blockers == 0.0) return 1.0;
    const float radius = clamp(shadowPenumbra(s, dr, sum / blockers), 0.5, LANTERN_PCSS_MAX_TEXELS);
    return shadowPcf(uv, layer, depth, radius);
}

float shadowFiltered(ShadowData s, vec2 uv, float layer, float depth) {
    if (SC_SHADOWS == LANTERN_SHADOW_PCSS) return shadowSoft(s, uv, layer, depth);
    if (SC_SHADOWS != LANTERN_SHADOW_PCF) return shadowCompare(uv, layer, depth);
    return shadowPcf(uv, layer, depth, float(int(frame.shadowParams.y) / 2));
}

// The share of a light that reaches eye-space point V with unit normal n, from its `count`
// maps starting at `first` (a cube's faces, or cascades nearest first); `lightPosition`: the
// light's eye-space position (positional). A map serves a point inside it by more than its
// margin; a point outside every map is lit.
float shadowVisibility(uint first, uint count, vec3 V, vec3 n, vec3 lightPosition) {
    for (uint k = 0u; k < count; ++k) {
        const uint layer = first + k;
        ShadowData s = shadows[frame.viewIndex * frame.shadowMaps + layer];
        const float distance = s.params.y > 0.5 ? length(V - lightPosition) : 1.0;
        const vec3 p = V + n * (frame.shadowParams.z * s.params.x * distance);
        const vec4 c = s.clipFromView * vec4(p, 1.0);
        const float inside = c.w * (1.0 - s.params.z);
        if (!(c.w > 0.0) || abs(c.x) > inside || abs(c.y) > inside) continue;  // another map's
        const vec3 ndc = c.xyz / c.w;
        return shadowFiltered(s, ndc.xy * 0.5 + 0.5, float(layer), ndc.z);
    }
    return 1.0;  // outside every map
}

#endif
