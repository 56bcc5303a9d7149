// pervertex.vert: the equation evaluated in the vertex stage, for three shading modes:
//   (default)             gouraud: at each vertex with its normal; colours interpolated
//   LANTERN_FLAT_CENTROID flat: at the element's centroid with its face normal (each vertex of
//                         the de-indexed triangle, line or point carries both), one colour
//                         per element (a line's normal is the mean of its vertex normals)
//   LANTERN_FLAT_PROVOKING GL_FLAT (--gl-compat): at each vertex, the provoking (last)
//                         vertex's colour fills the triangle
// Both faces are lit when two-sided lighting is on; the fragment stage picks by facing.
// LANTERN_GUARD: the variant that checks what it lit (guard.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "instance.glsl"
#ifdef LANTERN_GUARD
#include "guard.glsl"
#endif

#if defined(LANTERN_FLAT_CENTROID) || defined(LANTERN_FLAT_PROVOKING)
#define LIT flat
#else
#define LIT centroid
#endif

layout(location = LANTERN_LOC_POSITION) in vec3 inPosition;
layout(location = LANTERN_LOC_NORMAL) in vec3 inNormal;
layout(location = LANTERN_LOC_COLOR) in vec4 inColor;
layout(location = LANTERN_LOC_TEXCOORD) in vec2 inTexcoord;
layout(location = LANTERN_LOC_TEXCOORD1) in vec2 inTexcoord1;
#ifdef LANTERN_FLAT_CENTROID
layout(location = LANTERN_LOC_CENTROID) in vec3 inCentroid;
#endif

layout(location = 0) LIT out vec3 vFrontBase;
layout(location = 1) LIT out vec3 vFrontTextured;
layout(location = 2) LIT out vec3 vBackBase;
layout(location = 3) LIT out vec3 vBackTextured;
layout(location = 4) LIT out vec2 vAlpha;  // front, back
layout(location = 5) centroid out vec2 vTexcoord;
layout(location = 6) centroid out vec3 vEyePosition;
layout(location = 7) LIT out vec3 vNormal;
layout(location = 8) out vec2 vTexcoordCentre;  // at the pixel centre, for derivatives
layout(location = 10) centroid out vec2 vTexcoord1;  // the second set (emissive map)
layout(location = 11) out vec2 vTexcoord1Centre;

void main() {
    const mat4 viewFromModel = vertexViewFromModel();
    vec4 eye = viewFromModel * vec4(inPosition, 1.0);
#ifdef LANTERN_FLAT_CENTROID
    vec3 shadePoint = (viewFromModel * vec4(inCentroid, 1.0)).xyz;
#else
    vec3 shadePoint = eye.xyz;
#endif
    vec3 n = safeNormalize(vertexNormalMatrix() * inNormal);
    MaterialData material = materials[draw.materialIndex];

    vec3 ambientM, diffuseM;
    float alpha;
    materialColours(material.front, inColor, ambientM, diffuseM, alpha);
    LightSums sums = evaluateLighting(shadePoint, n, material.front);
    splitLit(sums, ambientM, diffuseM, vFrontBase, vFrontTextured);
    vAlpha.x = alpha;
    if (SC_TWO_SIDED) {
        materialColours(material.back, inColor, ambientM, diffuseM, alpha);
        sums = evaluateLighting(shadePoint, -n, material.back);
        splitLit(sums, ambientM, diffuseM, vBackBase, vBackTextured);
        vAlpha.y = alpha;
    } else {
        vBackBase = vFrontBase;
        vBackTextured = vFrontTextured;
        vAlpha.y = vAlpha.x;
    }
#ifdef LANTERN_GUARD
    guardLit(vFrontBase, vFrontTextured, vAlpha.x);
    if (SC_TWO_SIDED) guardLit(vBackBase, vBackTextured, vAlpha.y);
#endif
    vTexcoord = inTexcoord;
    vTexcoordCentre = inTexcoord;
    vTexcoord1 = (SC_MAPS & LANTERN_MAP_SECOND_SETS) != 0u ? inTexcoord1 : vec2(0.0);
    vTexcoord1Centre = vTexcoord1;
    vEyePosition = eye.xyz;
    vNormal = n;
    gl_Position = frame.clipFromView * eye;
    gl_PointSize = frame.pointSize;
}
