// pervertex.frag: combines the colours lit before the fragment stage with the base-colour
// texture and the emissive map. Gouraud interpolates them from the vertices (pervertex.vert);
// LANTERN_FLAT takes them unchanged from one vertex (flat interpolation); LANTERN_FLAT_PRIMITIVE
// reads them from the triangle's record, lit once per triangle by the pre-pass (flat.glsl), at
// the index the vertex stage passes (flat.vert).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "output.glsl"
#include "maps.glsl"

#ifdef LANTERN_FLAT_PRIMITIVE
#define LANTERN_FLAT_ACCESS readonly
#include "flat.glsl"
layout(location = 9) flat in uint vTriangle;
#else
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
layout(location = 7) LIT in vec3 vNormal;
#endif
layout(location = 5) centroid in vec2 vTexcoord;
#if !defined(LANTERN_FLAT_PRIMITIVE) || defined(LANTERN_AOV)
layout(location = 6) centroid in vec3 vEyePosition;
#endif
layout(location = 8) in vec2 vTexcoordCentre;
layout(location = 10) centroid in vec2 vTexcoord1;
layout(location = 11) in vec2 vTexcoord1Centre;

void main() {
    SurfaceUv u = SurfaceUv(vTexcoord, vec2(0.0), vec2(0.0));
    if (SC_TEXTURE || (SC_MAPS & LANTERN_MAP_EMISSIVE) != 0u) {  // on constants: uniform flow
        u.dx = dFdx(vTexcoordCentre);
        u.dy = dFdy(vTexcoordCentre);
    }
    MapUv mu = MapUv(u, SurfaceUv(vTexcoord1, vec2(0.0), vec2(0.0)));
    if ((SC_MAPS & LANTERN_MAP_SECOND_SETS) != 0u) {
        mu.second.dx = dFdx(vTexcoord1Centre);
        mu.second.dy = dFdy(vTexcoord1Centre);
    }
    bool back = SC_TWO_SIDED && !gl_FrontFacing;
#ifdef LANTERN_FLAT_PRIMITIVE
    const uint triangle = vTriangle;
    const uint at = triangle * flatRecordVectors() + (back ? flatVectorsPerSide() : 0u);
    const vec4 lit = flatColors[at];
    vec3 base = lit.rgb;
    vec3 textured = SC_TEXTURE ? flatColors[at + 1u].rgb : vec3(0.0);
    float alpha = lit.a;
#else
    vec3 base = back ? vBackBase : vFrontBase;
    // Without a texture the vertex stage summed the parts into `base` (pervertex.vert).
    vec3 textured = SC_TEXTURE ? (back ? vBackTextured : vFrontTextured) : vec3(0.0);
    float alpha = back ? vAlpha.y : vAlpha.x;
#endif
    vec4 texel = SC_TEXTURE ? baseColorTexel(u, draw.materialIndex) : vec4(1.0);
    alpha *= texel.a;
    if (SC_ALPHA_MASK && alpha < materials[draw.materialIndex].params.x) discard;
    vec3 c = base + texel.rgb * textured;
    // The emissive map per fragment (the emission is not lit, so this is exact); the other
    // maps need a per-fragment normal or material (phong only: docs/gl-differences.md).
    if ((materialMaps(draw.materialIndex) & LANTERN_MAP_EMISSIVE) != 0u) {
        MaterialData material = materials[draw.materialIndex];
        c = max(c + mappedEmissionChange(back ? material.back : material.front, mu), 0.0);
    }
#ifdef LANTERN_FLAT_PRIMITIVE
#ifdef LANTERN_AOV
    writeOutputs(c, alpha, flatNormals[triangle].xyz, vEyePosition, vTexcoord);
#else
    writeOutputs(c, alpha, vec3(0.0), vec3(0.0), vec2(0.0));
#endif
#else
    writeOutputs(c, alpha, vNormal, vEyePosition, vTexcoord);
#endif
}
