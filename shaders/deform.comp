// deform.comp: skinning and morph targets before the draws (the GPU twin of
// engine/src/scene/Deform.cpp, operation for operation). One invocation per vertex writes the
// deformed position and normal; in flat mode one per element writes its corners' position,
// face normal and centroid (the flat-shading streams). The lighting shaders read
// the results as ordinary vertex streams.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "lantern_shared.h"

layout(local_size_x = LANTERN_DEFORM_GROUP) in;

// The scene's deformation inputs (gpu/SceneBuffers.cpp), 32-bit words: float bits or uints.
layout(std430, set = 0, binding = LANTERN_BINDING_DEFORM_INPUT) readonly buffer DeformInput {
    uint words[];
} src;
// This frame's joint matrices (column-major mat4s) and morph weights.
layout(std430, set = 0, binding = LANTERN_BINDING_DEFORM_PARAMS) readonly buffer DeformParams {
    float values[];
} params;
layout(std430, set = 0, binding = LANTERN_BINDING_DEFORM_OUTPUT) writeonly buffer DeformOutput {
    float values[];
} dst;

// Offsets are in 32-bit words of their buffer; LANTERN_DEFORM_NONE: absent.
layout(push_constant) uniform DeformJob {
    uint count;         // vertices, or elements in flat mode
    uint flatMode;      // 0: per vertex; 3, 2, 1: flat-shading streams per triangle, line, point corner
    uint vertexCount;
    uint position;      // src: base positions (3 floats per vertex)
    uint normal;        // src: base normals
    uint joints;        // src: `influences` joint indices per vertex
    uint weights;       // src: `influences` weights per vertex
    uint influences;    // 0 (not skinned), 4 or 8
    uint targets;       // src: per target 3 * vertexCount position, then normal displacements
    uint targetCount;
    uint indices;       // src: the element list; LANTERN_DEFORM_NONE: vertices in order
    uint matrices;      // params: the skin's joint matrices
    uint morphWeights;  // params: one per target
    uint outPosition;   // dst
    uint outNormal;     // dst
    uint outCentroid;   // dst (flat mode)
} job;

vec3 load3(uint base, uint i) {
    const uint o = base + 3u * i;
    return vec3(uintBitsToFloat(src.words[o]), uintBitsToFloat(src.words[o + 1u]),
                uintBitsToFloat(src.words[o + 2u]));
}

void store3(uint base, uint i, vec3 v) {
    const uint o = base + 3u * i;
    dst.values[o] = v.x;
    dst.values[o + 1u] = v.y;
    dst.values[o + 2u] = v.z;
}

mat4 jointMatrix(uint j) {
    const uint o = job.matrices + 16u * j;
    return mat4(params.values[o], params.values[o + 1u], params.values[o + 2u], params.values[o + 3u],
                params.values[o + 4u], params.values[o + 5u], params.values[o + 6u], params.values[o + 7u],
                params.values[o + 8u], params.values[o + 9u], params.values[o + 10u], params.values[o + 11u],
                params.values[o + 12u], params.values[o + 13u], params.values[o + 14u], params.values[o + 15u]);
}

// Scaled by the largest component first (no overflow), zero stays zero (normalize(0) is NaN
// on lavapipe: numerics.md 3.1).
vec3 guardedNormalize(vec3 n) {
    const float big = max(abs(n.x), max(abs(n.y), abs(n.z)));
    if (!(big > 0.0) || isinf(big)) return vec3(0.0);
    const vec3 m = n / big;
    return m * inversesqrt(dot(m, m));
}

void deformVertex(uint v, out vec3 p, out vec3 n) {
    p = load3(job.position, v);
    n = load3(job.normal, v);
    for (uint t = 0u; t < job.targetCount; ++t) {
        const float w = params.values[job.morphWeights + t];
        if (w == 0.0) continue;
        const uint base = job.targets + t * 6u * job.vertexCount;
        p += w * load3(base, v);
        n += w * load3(base + 3u * job.vertexCount, v);
    }
    if (job.influences > 0u) {
        mat4 s = mat4(0.0);
        float sum = 0.0;
        for (uint k = 0u; k < job.influences; ++k) {
            const float w = uintBitsToFloat(src.words[job.weights + v * job.influences + k]);
            if (w == 0.0) continue;
            s += w * jointMatrix(src.words[job.joints + v * job.influences + k]);
            sum += w;
        }
        if (sum == 0.0) s = mat4(1.0);
        p = (s * vec4(p, 1.0)).xyz;
        const mat3 m = mat3(s);
        mat3 cof = mat3(cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1]));
        if (dot(m[0], cof[0]) < 0.0) cof = -cof;  // mirroring: keep normals outward
        n = cof * n;
    }
    n = guardedNormalize(n);
}

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= job.count) return;
    if (job.flatMode == 0u) {
        vec3 p, n;
        deformVertex(i, p, n);
        store3(job.outPosition, i, p);
        store3(job.outNormal, i, n);
        return;
    }
    // Triangles: the face normal of the deformed corners; lines and points: the normalised
    // mean of the deformed vertex normals (gpu/SceneBuffers.cpp, flatElement).
    const uint k = job.flatMode;
    vec3 p[3], n[3];
    vec3 sum = vec3(0.0), normals = vec3(0.0);
    for (uint c = 0u; c < k; ++c) {
        const uint v = job.indices == LANTERN_DEFORM_NONE ? k * i + c : src.words[job.indices + k * i + c];
        deformVertex(v, p[c], n[c]);
        sum += p[c];
        normals += n[c];
    }
    const vec3 face = guardedNormalize(k == 3u ? cross(p[1] - p[0], p[2] - p[0]) : normals);
    const vec3 middle = sum / float(k);
    for (uint c = 0u; c < k; ++c) {
        store3(job.outPosition, k * i + c, p[c]);
        store3(job.outNormal, k * i + c, face);
        store3(job.outCentroid, k * i + c, middle);
    }
}
