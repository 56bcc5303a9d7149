// clear.frag: writes the values a LOAD_OP_CLEAR would (gpu/ClearDraw.h): the frame's clear
// colour, pushed as the first 16 bytes of the push constants, and, in the AOV variant, the
// AOV planes' background (gpu/Recorder.cpp: normal 0 and depth FLT_MAX; no draw, no
// primitive; uv 0 and range FLT_MAX).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "lantern_shared.h"

layout(push_constant) uniform ClearBlock {
    vec4 color;
} clearBlock;

layout(location = LANTERN_OUT_COLOR) out vec4 outColor;
#ifdef LANTERN_AOV
layout(location = LANTERN_OUT_NORMAL_DEPTH) out uvec4 outNormalDepth;
layout(location = LANTERN_OUT_ID) out uvec2 outId;
layout(location = LANTERN_OUT_SURFACE) out uvec4 outSurface;
#endif

void main() {
    outColor = clearBlock.color;
#ifdef LANTERN_AOV
    outNormalDepth = uvec4(0u, 0u, 0u, LANTERN_FLT_MAX_BITS);
    outId = uvec2(0u);
    outSurface = uvec4(0u, 0u, LANTERN_FLT_MAX_BITS, 0u);
#endif
}
