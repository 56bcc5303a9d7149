// flat.glsl: the records of per-triangle flat shading, written once per triangle by the
// pre-pass (flatlight.comp) and read by the fragment stage (pervertex.frag,
// LANTERN_FLAT_PRIMITIVE) at the draw's first record plus the triangle's index, which the
// vertex stage passes as a flat varying (flat.vert). A record holds per side (the front, then
// the back when two-sided lighting is on) the lit colour (rgb, alpha) and, when the variant
// samples a base-colour texture, the part the texel scales (rgb); without one the two are
// summed, so an untextured triangle costs one vec4. The includer defines LANTERN_FLAT_ACCESS
// (readonly or writeonly).
#ifndef LANTERN_FLAT_GLSL
#define LANTERN_FLAT_GLSL

#include "uniforms.glsl"

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_FLAT_COLORS, std430)
LANTERN_FLAT_ACCESS buffer FlatColors {
    vec4 flatColors[];
};
// The eye-space face normal per triangle, for the normal AOV (written in frames with AOVs).
layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_FLAT_NORMALS, std430)
LANTERN_FLAT_ACCESS buffer FlatNormals {
    vec4 flatNormals[];
};

uint flatVectorsPerSide() { return SC_TEXTURE ? 2u : 1u; }
uint flatRecordVectors() { return flatVectorsPerSide() * (SC_TWO_SIDED ? 2u : 1u); }

#endif
