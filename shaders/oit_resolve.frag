// oit_resolve.frag: exact transparency's composite (docs/transparency.md). Drawn over the
// whole target after the scene pass (gpu/Transparency.cpp): each pixel's list of blended
// fragments (shaders/include/oit.glsl) taken nearest first, ties broken by the fragments'
// contents so the order never depends on the order the GPU stored them, and composited front
// to back. The result is premultiplied and the pipeline blends it ONE, ONE_MINUS_SRC_ALPHA over
// the opaque picture: C = sum_i T_i a_i c_i + T_n C_behind, with T_i = prod_{j<i} (1 - a_j),
// as the reference ray caster composites (lantern/Reference.h). With MSAA each sample
// composites the fragments that cover it and the pixel takes the samples' mean (over the
// resolved opaque picture: exact wherever that picture is one surface across the pixel). A pixel
// with more than LANTERN_OIT_MAX_LAYERS fragments keeps its nearest ones and is counted.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "lantern_shared.h"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_FRAGMENT_LISTS, std430) buffer FragmentLists {
    uint words[];
} lists;

layout(location = 0) out vec4 outColor;

// A fragment's place in the composite: its depth as a key that grows with distance, then its
// colour, alpha and coverage bits (so the order never depends on the order the fragments were
// stored in; identical fragments are interchangeable).
struct Fragment {
    float key;
    uvec4 rgba;
    uint mask;
};

Fragment fragmentAt(uint at, bool greater) {
    const float z = uintBitsToFloat(lists.words[at + 1u]);
    return Fragment(greater ? -z : z,
                    uvec4(lists.words[at + 2u], lists.words[at + 3u], lists.words[at + 4u], lists.words[at + 5u]),
                    lists.words[at + 6u]);
}

// -1, 0 or 1 as `a` goes before, with or after `b`.
int order(Fragment a, Fragment b) {
    if (a.key != b.key) return a.key < b.key ? -1 : 1;
    for (int k = 0; k < 4; ++k)
        if (a.rgba[k] != b.rgba[k]) return a.rgba[k] < b.rgba[k] ? -1 : 1;
    if (a.mask != b.mask) return a.mask < b.mask ? -1 : 1;
    return 0;
}

// The front-to-back composite of the fragments of the list at `head` that cover a sample of
// `samples`, nearest first: each step finds the nearest fragment after the last one taken
// (with how many identical copies it has) by walking the list again. No array: llvmpipe
// keeps a per-invocation array in memory, which measured 5x slower than these walks.
vec4 compositeList(uint head, uint samples, bool greater, inout bool truncated) {
    const uint nodes = lists.words[LANTERN_OIT_NODES];
    const uint capacity = lists.words[LANTERN_OIT_CAPACITY];
    vec3 c = vec3(0.0);
    float transmitted = 1.0;
    Fragment last = Fragment(0.0, uvec4(0u), 0u);
    bool any = false;
    uint layers = 0u;
    while (true) {
        Fragment best = Fragment(0.0, uvec4(0u), 0u);
        uint copies = 0u;
        uint visited = 0u;
        for (uint node = head; node != LANTERN_OIT_END && visited < capacity; ++visited) {
            const uint at = nodes + node * LANTERN_OIT_NODE_WORDS;
            node = lists.words[at];
            const Fragment f = fragmentAt(at, greater);
            if ((f.mask & samples) == 0u) continue;
            if (any && order(f, last) <= 0) continue;
            const int o = copies == 0u ? -1 : order(f, best);
            if (o < 0) {
                best = f;
                copies = 1u;
            } else if (o == 0) {
                ++copies;
            }
        }
        if (copies == 0u) break;
        if (layers >= LANTERN_OIT_MAX_LAYERS) {
            truncated = true;
            break;
        }
        const vec3 colour = uintBitsToFloat(best.rgba.rgb);
        const float alpha = uintBitsToFloat(best.rgba.a);
        for (uint k = 0u; k < copies; ++k) {
            c += transmitted * alpha * colour;
            transmitted *= 1.0 - alpha;
        }
        layers += copies;
        last = best;
        any = true;
    }
    return vec4(c, 1.0 - transmitted);
}

void main() {
    const uint width = lists.words[LANTERN_OIT_WIDTH];
    const uint head = lists.words[LANTERN_OIT_HEADER_WORDS + uint(gl_FragCoord.y) * width + uint(gl_FragCoord.x)];
    if (head == LANTERN_OIT_END) discard;
    const bool greater = lists.words[LANTERN_OIT_NEARER_GREATER] != 0u;
    // Each sample composites the fragments that cover it (one sample: all of them).
    const uint samples = max(lists.words[LANTERN_OIT_SAMPLES], 1u);
    bool truncated = false;
    vec4 sum = vec4(0.0);
    for (uint s = 0u; s < samples; ++s)
        sum += compositeList(head, samples == 1u ? 0xFFFFFFFFu : 1u << s, greater, truncated);
    if (truncated) atomicAdd(lists.words[LANTERN_OIT_TRUNCATED], 1u);
    outColor = sum / float(samples);
}
