// pervertex.frag: combines the colours lit in the vertex stage (pervertex.vert) with the
// base-colour texture; LANTERN_FLAT takes them unchanged from one vertex (flat interpolation).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "output.glsl"

#ifdef LANTERN_FLAT
#define LIT flat
#else
#define LIT centroid
#endif

layout(location = 0) LIT in vec3 vFrontBase;
layout(location = 1) LIT in vec3 vFrontTextured;
layout(location = 2) LIT in vec3 vBackBase;
layout(location = 3) LIT in vec3 vBackTextured;
layout(location = 4) LIT in vec2 vAlpha;
layout(location = 5) centroid in vec2 vTexcoord;
layout(location = 6) centroid in vec3 vEyePosition;
layout(location = 7) LIT in vec3 vNormal;

void main() {
    bool back = SC_TWO_SIDED && !gl_FrontFacing;
    vec3 base = back ? vBackBase : vFrontBase;
    vec3 textured = back ? vBackTextured : vFrontTextured;
    float alpha = back ? vAlpha.y : vAlpha.x;
    vec4 texel = SC_TEXTURE ? texture(baseColorTexture, baseColorUv(vTexcoord, draw.materialIndex)) : vec4(1.0);
    alpha *= texel.a;
    if (SC_ALPHA_MASK && alpha < materials[draw.materialIndex].params.x) discard;
    writeOutputs(base + texel.rgb * textured, alpha, vNormal, vEyePosition);
}
