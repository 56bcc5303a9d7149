// mesh.vert: phong shading's vertex stage: transforms to eye and clip space and passes the
// interpolants on; lighting happens per fragment (phong.frag).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "instance.glsl"

layout(location = LANTERN_LOC_POSITION) in vec3 inPosition;
layout(location = LANTERN_LOC_NORMAL) in vec3 inNormal;
layout(location = LANTERN_LOC_COLOR) in vec4 inColor;
layout(location = LANTERN_LOC_TEXCOORD) in vec2 inTexcoord;
layout(location = LANTERN_LOC_TANGENT) in vec4 inTangent;  // zero: none
layout(location = LANTERN_LOC_TEXCOORD1) in vec2 inTexcoord1;

layout(location = 0) out vec3 vEyePosition;
layout(location = 1) out vec3 vNormal;
layout(location = 2) out vec4 vColor;
layout(location = 3) out vec2 vTexcoord;
layout(location = 4) out vec3 vEyeCentre;      // the same two at the pixel centre, for
layout(location = 5) out vec2 vTexcoordCentre; // derivatives (phong.frag)
layout(location = 6) out vec4 vTangent;        // eye space, w the bitangent's sign; zero: none
layout(location = 7) out vec2 vTexcoord1;      // the second set, and its copy for derivatives
layout(location = 8) out vec2 vTexcoord1Centre;

void main() {
    const mat4 viewFromModel = vertexViewFromModel();
    vec4 eye = viewFromModel * vec4(inPosition, 1.0);
    vEyePosition = eye.xyz;
    vNormal = vertexNormalMatrix() * inNormal;
    vColor = inColor;
    vTexcoord = inTexcoord;
    vEyeCentre = eye.xyz;
    vTexcoordCentre = inTexcoord;
    // Only the variants whose maps read it (a constant zero elsewhere, dropped).
    vTexcoord1 = (SC_MAPS & LANTERN_MAP_SECOND_SETS) != 0u ? inTexcoord1 : vec2(0.0);
    vTexcoord1Centre = vTexcoord1;
    vTangent = (SC_MAPS & LANTERN_MAP_NORMAL) != 0u
                   ? vec4(mat3(viewFromModel) * inTangent.xyz, inTangent.w)
                   : vec4(0.0);
    gl_Position = frame.clipFromView * eye;
    gl_PointSize = frame.pointSize;
}
