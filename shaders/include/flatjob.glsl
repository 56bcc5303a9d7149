// flatjob.glsl: one flat triangle draw lit once per triangle (a FlatJob), and where its
// triangles' corners are. Read by the pre-pass that lights the triangles (flatlight.comp) and
// by the draw's vertex stage (flat.vert), which pulls the same corners by gl_VertexIndex, so
// the two compute each corner's position from the same words.
#ifndef LANTERN_FLATJOB_GLSL
#define LANTERN_FLATJOB_GLSL

#include "lantern_shared.h"

// The scene's geometry buffer (gpu/SceneBuffers.cpp) as 32-bit words, and this frame's deformed
// streams (deform.comp).
layout(std430, set = LANTERN_SET_FLAT, binding = LANTERN_BINDING_FLAT_GEOMETRY) readonly buffer FlatGeometry {
    uint words[];
} geometry;
layout(std430, set = LANTERN_SET_FLAT, binding = LANTERN_BINDING_FLAT_DEFORMED) readonly buffer FlatDeformed {
    float values[];
} deformed;

// Mirrored by gpu::FlatJob (gpu/GpuLayouts.h).
struct FlatJob {
    mat4 viewFromModel;
    vec4 normalMatrix[3];
    uint materialIndex;
    uint drawIndex;
    uint flags;
    uint flatBase;     // the draw's first triangle record (flat.glsl)
    uint count;        // triangles
    uint indices;      // words into geometry; LANTERN_DEFORM_NONE: vertices in order
    uint positions;    // words into geometry, or into deformed when `deformed` is 1
    uint deformed;
    uint colors;       // words into geometry (rgba per vertex); LANTERN_DEFORM_NONE: white
    uint cull;         // LANTERN_FLAT_CULL_BACK | LANTERN_FLAT_FRONT_CLOCKWISE
    uint writeNormals; // 1: the frame has AOVs, which read the face normal
    uint view;
    vec4 viewport;     // xy: half the view's size in pixels
    uint texcoords;    // words into geometry (uv per vertex); LANTERN_DEFORM_NONE: zero
    uint texcoords1;   // the second set, the same way
};
#ifdef LANTERN_FLAT_INDEX_WRITER
layout(std430, set = LANTERN_SET_FLAT, binding = LANTERN_BINDING_FLAT_INDICES) writeonly buffer FlatIndices {
    uint flatIndices[];
};
#endif
layout(std430, set = LANTERN_SET_FLAT, binding = LANTERN_BINDING_FLAT_JOBS) readonly buffer FlatJobs {
    FlatJob jobs[];
};

// The vertex at corner c (0..2) of triangle t.

uint cornerVertex(FlatJob j, uint t, uint c) {
    return j.indices == LANTERN_DEFORM_NONE ? 3u * t + c : geometry.words[j.indices + 3u * t + c];
}

// The draw's vertices (flat.vert): vertex t < count is triangle t's first corner, whose
// outputs the triangle takes (Vulkan's first vertex provokes); vertex count + v is the mesh's
// vertex v, shared by every triangle that has it as a second or third corner. The pass writes
// triangle t's indices (t, count + v1, count + v2), the same corners in the same order as the
// mesh's, so the rasteriser sees the same triangles; one it skips becomes (count, count,
// count), which draws nothing and leaves its corners unshaded.
uint meshVertex(FlatJob j, uint vertex) {
    return vertex < j.count ? cornerVertex(j, vertex, 0u) : vertex - j.count;
}

vec3 position(FlatJob j, uint v) {
    const uint o = j.positions + 3u * v;
    if (j.deformed != 0u)
        return vec3(deformed.values[o], deformed.values[o + 1u], deformed.values[o + 2u]);
    return vec3(uintBitsToFloat(geometry.words[o]), uintBitsToFloat(geometry.words[o + 1u]),
                uintBitsToFloat(geometry.words[o + 2u]));
}

#endif
