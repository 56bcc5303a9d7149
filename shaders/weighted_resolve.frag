// weighted_resolve.frag: weighted blended transparency's composite (docs/transparency.md,
// shaders/include/oit.glsl): the average colour of the pixel's blended fragments, weighted,
// covering 1 - revealage of what is behind. Premultiplied; the pipeline blends it ONE,
// ONE_MINUS_SRC_ALPHA over the opaque picture (gpu/Transparency.cpp).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "lantern_shared.h"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_WEIGHTED_ACCUM, rgba32f) uniform readonly image2D accumImage;
layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_WEIGHTED_REVEAL, r32f) uniform readonly image2D revealImage;

layout(location = 0) out vec4 outColor;

void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const float reveal = imageLoad(revealImage, p).r;
    if (reveal >= 1.0) discard;  // no blended fragment
    const vec4 accum = imageLoad(accumImage, p);
    // Float sums (not the half floats of the paper): no weight overflows them for colours
    // within the output guard's bound of 1e35 times a few layers; beyond that the host checks
    // the picture (a weighted frame is never taken as guarded, gpu/FrameRing.cpp).
    const vec3 average = accum.rgb / max(accum.a, 1e-30);
    const float covered = 1.0 - reveal;
    outColor = vec4(average * covered, covered);
}
