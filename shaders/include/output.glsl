// output.glsl: the fragment outputs shared by every fragment entry point: the colour and, in
// the AOV variants, the eye-space normal and depth, the draw/primitive ids and the surface
// plane (texture coordinates, range). AOVs are stored as integer bits, never blended or
// filtered. The surface plane has an attachment only when a frame asks for uv or range
// (otherwise its format is undefined in the pipeline and the writes are discarded).
#ifndef LANTERN_OUTPUT_GLSL
#define LANTERN_OUTPUT_GLSL

#include "lighting.glsl"
#include "oit.glsl"

#ifdef LANTERN_WEIGHTED
// The weighted pass's attachments: the weighted sums (premultiplied colour, alpha) and the
// revealage (the product of 1 - alpha, by the blend state). No AOV: they have passes of their own.
layout(location = 0) out vec4 outAccum;
layout(location = 1) out float outReveal;
#else
layout(location = LANTERN_OUT_COLOR) out vec4 outColor;
#endif
#ifdef LANTERN_AOV
layout(location = LANTERN_OUT_NORMAL_DEPTH) out uvec4 outNormalDepth;  // float bits: N.x, N.y, N.z, Z (= -z_eye)
layout(location = LANTERN_OUT_ID) out uvec2 outId;           // draw index + 1, gl_PrimitiveID
layout(location = LANTERN_OUT_SURFACE) out uvec4 outSurface;  // float bits: u, v, |eye|, 0
#endif

// c: linear colour; alpha: opacity; n: the surface normal before any two-sided flip;
// eyePosition: the eye-space point; uv: TEXCOORD_0 as the mesh holds it (0 without one).
void writeOutputs(vec3 c, float alpha, vec3 n, vec3 eyePosition, vec2 uv) {
    if (SC_CLAMP != LANTERN_CLAMP_NONE) c = clampVisible(c);
#if defined(LANTERN_WEIGHTED)
    const float w = weightedWeight(alpha);
    outAccum = vec4(c * alpha, alpha) * w;
    outReveal = alpha;
#elif defined(LANTERN_OIT)
    storeFragment(c, alpha);
    outColor = vec4(0.0);  // the pipeline writes no colour here (gpu/Pipelines.cpp)
#else
    outColor = vec4(c, SC_OPAQUE ? 1.0 : alpha);
#endif
#ifdef LANTERN_AOV
    vec3 visible = safeNormalize(n);
    if (!gl_FrontFacing) visible = -visible;
    outNormalDepth = uvec4(floatBitsToUint(visible), floatBitsToUint(-eyePosition.z));
    outId = uvec2(draw.drawIndex + 1u, uint(gl_PrimitiveID));
    outSurface = uvec4(floatBitsToUint(uv), floatBitsToUint(length(eyePosition)), 0u);
#endif
}

#endif
