// flat.vert: per-triangle flat shading's vertex stage: the indexed mesh's positions to clip
// space and its texture coordinates on; the colours were lit once per triangle before the
// draw (flatlight.comp) and are read per fragment by primitive id (pervertex.frag,
// LANTERN_FLAT_PRIMITIVE). gl_Position is computed exactly as the pre-pass computes it for
// its culling.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "uniforms.glsl"

layout(location = LANTERN_LOC_POSITION) in vec3 inPosition;
layout(location = LANTERN_LOC_TEXCOORD) in vec2 inTexcoord;

layout(location = 5) centroid out vec2 vTexcoord;
layout(location = 6) centroid out vec3 vEyePosition;
layout(location = 8) out vec2 vTexcoordCentre;  // at the pixel centre, for derivatives

void main() {
    vec4 eye = draw.viewFromModel * vec4(inPosition, 1.0);
    vTexcoord = inTexcoord;
    vTexcoordCentre = inTexcoord;
    vEyePosition = eye.xyz;
    gl_Position = frame.clipFromView * eye;
}
