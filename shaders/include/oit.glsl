// oit.glsl: order-independent transparency's fragment side (docs/transparency.md).
// LANTERN_OIT (exact): a blended fragment that passes the depth test against the opaque
// surfaces is stored in its pixel's list (a node appended with one atomic, linked in with
// another); shaders/oit_resolve.frag later sorts each list by depth and composites it. The
// depth test must come before the store, hence early fragment tests (the blended draws do not
// write depth, so testing early changes no result).
// LANTERN_WEIGHTED: the fragment adds its weighted colour into the sums and multiplies the
// revealage (McGuire and Bavoil 2013, "Weighted Blended Order-Independent Transparency",
// JCGT 2(2), their equation 10 weight); shaders/weighted_resolve.frag divides them out.
#ifndef LANTERN_OIT_GLSL
#define LANTERN_OIT_GLSL

#include "lantern_shared.h"

#ifdef LANTERN_OIT
layout(early_fragment_tests) in;

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_FRAGMENT_LISTS, std430) coherent buffer FragmentLists {
    uint words[];
} lists;

// c: linear colour, straight alpha. With MSAA the node keeps the samples the fragment covers,
// and the resolve composites each sample's own fragments (two triangles sharing a pixel each
// cover their samples once, as they blend in the sorted path).
void storeFragment(vec3 c, float alpha) {
    const uint node = atomicAdd(lists.words[LANTERN_OIT_COUNT], 1u);
    if (node >= lists.words[LANTERN_OIT_CAPACITY]) return;  // the host sees COUNT and renders again
    const uint head = LANTERN_OIT_HEADER_WORDS +
                      uint(gl_FragCoord.y) * lists.words[LANTERN_OIT_WIDTH] + uint(gl_FragCoord.x);
    const uint at = lists.words[LANTERN_OIT_NODES] + node * LANTERN_OIT_NODE_WORDS;
    lists.words[at + 1u] = floatBitsToUint(gl_FragCoord.z);
    lists.words[at + 2u] = floatBitsToUint(c.r);
    lists.words[at + 3u] = floatBitsToUint(c.g);
    lists.words[at + 4u] = floatBitsToUint(c.b);
    lists.words[at + 5u] = floatBitsToUint(alpha);
    lists.words[at + 6u] = lists.words[LANTERN_OIT_SAMPLES] > 1u ? uint(gl_SampleMaskIn[0]) : 1u;
    lists.words[at] = atomicExchange(lists.words[head], node);
}
#endif

#ifdef LANTERN_WEIGHTED
// The weight of a fragment at eye distance d (1 / gl_FragCoord.w: -z_eye in perspective, 1 in
// an orthographic view, where every layer weighs the same): McGuire and Bavoil's equation 10.
float weightedWeight(float alpha) {
    const float d = 1.0 / gl_FragCoord.w;
    const float a = d / 5.0, b = d / 200.0;
    return alpha * clamp(10.0 / (1e-5 + a * a + b * b * b * b * b * b), 1e-2, 3e3);
}
#endif

#endif
