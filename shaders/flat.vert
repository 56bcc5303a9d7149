// flat.vert: per-triangle flat shading's vertex stage. The draw has no vertex buffers; its
// index list, written by the pre-pass (flatlight.comp), names vertex t for triangle t's first
// corner and vertex count + v for the mesh's vertex v as a second or third corner
// (meshVertex in flatjob.glsl), so a shared corner is shaded once and the triangles the pass
// skipped shade nothing. Each vertex pulls its position from the draw's FlatJob exactly as
// the pre-pass did, and vertex t hands the fragment stage triangle t's record (flat.glsl) as
// a flat varying. The record is not read by gl_PrimitiveID: on llvmpipe a fragment shader
// that reads it makes every draw go through a primitive assembler that de-indexes the mesh on
// the CPU (docs/performance.md). gl_Position is computed exactly as the pre-pass computes it
// for its culling.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "uniforms.glsl"
#include "flatjob.glsl"

layout(location = 5) centroid out vec2 vTexcoord;
layout(location = 6) centroid out vec3 vEyePosition;
layout(location = 8) out vec2 vTexcoordCentre;  // at the pixel centre, for derivatives
layout(location = 10) centroid out vec2 vTexcoord1;  // the second set (emissive map)
layout(location = 11) out vec2 vTexcoord1Centre;
layout(location = 9) flat out uint vTriangle;   // the triangle's record

void main() {
    const FlatJob j = jobs[draw.flatJob];
    const uint vertex = uint(gl_VertexIndex);
    const uint v = meshVertex(j, vertex);
    // Texture coordinates only where the fragment stage samples (on constants).
    vec2 uv = vec2(0.0);
    const bool sampled = SC_TEXTURE || (SC_MAPS & LANTERN_MAP_EMISSIVE) != 0u;
    if (sampled && j.texcoords != LANTERN_DEFORM_NONE) {
        const uint o = j.texcoords + 2u * v;
        uv = uintBitsToFloat(uvec2(geometry.words[o], geometry.words[o + 1u]));
    }
    vec2 uv1 = vec2(0.0);
    if ((SC_MAPS & LANTERN_MAP_SECOND_SETS) != 0u && j.texcoords1 != LANTERN_DEFORM_NONE) {
        const uint o = j.texcoords1 + 2u * v;
        uv1 = uintBitsToFloat(uvec2(geometry.words[o], geometry.words[o + 1u]));
    }
    vec4 eye = draw.viewFromModel * vec4(position(j, v), 1.0);
    vTexcoord1 = uv1;
    vTexcoord1Centre = uv1;
    vTexcoord = uv;
    vTexcoordCentre = uv;
    vEyePosition = eye.xyz;
    vTriangle = j.flatBase + vertex;  // read only where the vertex provokes (vertex < count)
    gl_Position = frame.clipFromView * eye;
}
