// guard.glsl: the output guard. The stages that make a frame's lit colours outside the
// fragment stage (pervertex.vert's guarded variants, flatlight.comp) check them there, where
// there are far fewer of them than pixels, and set a word in the frame's arena when one is
// NaN, Inf, above LANTERN_GUARD_BOUND or has an alpha outside [0, 1]; the host clears the word
// before the frame and reads it after, and checks the picture itself only when it is set
// (gpu/Readback.cpp). Not in the fragment stage: on llvmpipe a fragment shader that stores to
// memory made the teapot grid up to 1.5x slower even with early fragment tests.
#ifndef LANTERN_GUARD_GLSL
#define LANTERN_GUARD_GLSL

#include "specialization.glsl"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_GUARD, std430) writeonly buffer GuardBlock {
    uint guardTripped;
};

// On the bits, one unsigned comparison per channel: a NaN, an Inf or a magnitude above the
// bound has a larger magnitude pattern than the bound's; a negative alpha (the sign bit) or
// one above 1 (or NaN) a larger pattern than 1.0's. Opaque variants write alpha 1 whatever it
// is, so their alpha is not checked.
void guardLit(vec3 base, vec3 textured, float alpha) {
    const uint bound = floatBitsToUint(float(LANTERN_GUARD_BOUND));
    const uvec3 magnitude = uvec3(0x7fffffffu);
    const bool parts = any(greaterThan(floatBitsToUint(base) & magnitude, uvec3(bound))) ||
                       any(greaterThan(floatBitsToUint(textured) & magnitude, uvec3(bound)));
    const bool opacity = !SC_OPAQUE && floatBitsToUint(alpha) > floatBitsToUint(1.0);
    if (parts || opacity) guardTripped = 1u;
}

#endif
