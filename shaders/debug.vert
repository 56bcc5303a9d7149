// debug.vert: the viewer's display overlays, drawn over the shaded scene with the scene's
// frame block and push constants:
//   (default)       wireframe: the primitive's triangles rasterised as lines (polygon mode
//                   LINE), positions only
//   LANTERN_NORMALS normals: one instance per vertex (position and normal stepped per
//                   instance), two vertices each: the vertex and the tip of its unit eye-space
//                   normal scaled by draw.normalMatrix[0].w (eye units; the w is otherwise unused)
#version 460
#extension GL_GOOGLE_include_directive : require
#include "lighting.glsl"

layout(location = LANTERN_LOC_POSITION) in vec3 inPosition;
#ifdef LANTERN_NORMALS
layout(location = LANTERN_LOC_NORMAL) in vec3 inNormal;
#endif

layout(location = 0) out vec3 vColor;

void main() {
    vec4 eye = draw.viewFromModel * vec4(inPosition, 1.0);
#ifdef LANTERN_NORMALS
    vec3 n = safeNormalize(drawNormalMatrix() * inNormal);
    eye.xyz += float(gl_VertexIndex) * draw.normalMatrix[0].w * n;
    vColor = vec3(0.1, 0.75, 1.0);
#else
    vColor = vec3(1.0, 0.55, 0.1);
#endif
    gl_Position = frame.clipFromView * eye;
}
