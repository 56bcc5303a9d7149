// pervertex.frag: combines the colours lit in the vertex stage (pervertex.vert) with the
// base-colour texture and the emissive map; LANTERN_FLAT takes them unchanged from one vertex
// (flat interpolation).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "output.glsl"
#include "maps.glsl"

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
layout(location = 8) in vec2 vTexcoordCentre;

void main() {
    SurfaceUv u = SurfaceUv(vTexcoord, vec2(0.0), vec2(0.0));
    if (SC_TEXTURE || (SC_MAPS & LANTERN_MAP_EMISSIVE) != 0u) {  // on constants: uniform flow
        u.dx = dFdx(vTexcoordCentre);
        u.dy = dFdy(vTexcoordCentre);
    }
    bool back = SC_TWO_SIDED && !gl_FrontFacing;
    vec3 base = back ? vBackBase : vFrontBase;
    vec3 textured = back ? vBackTextured : vFrontTextured;
    float alpha = back ? vAlpha.y : vAlpha.x;
    vec4 texel = SC_TEXTURE ? baseColorTexel(u, draw.materialIndex) : vec4(1.0);
    alpha *= texel.a;
    if (SC_ALPHA_MASK && alpha < materials[draw.materialIndex].params.x) discard;
    vec3 c = base + texel.rgb * textured;
    // The emissive map per fragment (the emission is not lit, so this is exact); the other
    // maps need a per-fragment normal or material (phong only: docs/gl-differences.md).
    if ((materialMaps(draw.materialIndex) & LANTERN_MAP_EMISSIVE) != 0u) {
        MaterialData material = materials[draw.materialIndex];
        c = max(c + mappedEmissionChange(back ? material.back : material.front, u), 0.0);
    }
    writeOutputs(c, alpha, vNormal, vEyePosition);
}
