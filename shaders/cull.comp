// cull.comp: the cluster-culling pre-pass (gpu/Clusters.h). One invocation per draw (the
// first of its records; the others return): for each of its instances in order, the level of
// detail, then each cluster of that level in order, kept when its bounding sphere reaches into
// the view's clip volume and its normal cone does not wholly face away. Kept neighbours make
// one indirect draw (their index ranges follow on); the draws go out compacted, in order, with
// their count, so the draw call rasterises the kept triangles in the order of the whole draw.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "lantern_shared.h"

layout(local_size_x = LANTERN_CULL_GROUP) in;

// Mirrored by gpu::ClusterData, CullLevel, CullRecord and CullView (gpu/Clusters.h).
struct Cluster {
    vec4 sphere;  // centre, radius (model space)
    vec4 apex;    // the normal cone's apex
    vec4 axis;    // its axis, cutoff (1: no cone)
    uvec4 range;  // first index, index count
};
struct Level {
    float error;
    uint firstCluster;
    uint clusterCount;
    uint padding;
};
struct Record {
    mat4 viewFromModel;
    vec4 normalMatrix[3];
    vec4 sphere;
    uint view;
    uint flags;
    uint firstCommand;
    uint slots;
    uint firstInstance;
    uint levelCount;
    uint lodCommand;
    uint drawRecords;  // on a draw's first record: its records (instances); 0 on the others
    float scale;
    uint indexBase;  // level 0's first index in the buffer its draws bind
    uint lodSlots;   // the coarser levels' commands (level 1's cluster count)
    uint countIndex; // the draw's two counts: counts[1 + 2 countIndex] (full), [2 + 2 countIndex]
    Level levels[LANTERN_CULL_MAX_LEVELS];
};
struct View {
    vec4 planes[6];
    vec4 projection;  // pixels per unit, perspective, cone test allowed, level-of-detail bound
};

layout(std430, set = 0, binding = LANTERN_BINDING_CULL_CLUSTERS) readonly buffer Clusters {
    Cluster clusters[];
};
layout(std430, set = 0, binding = LANTERN_BINDING_CULL_RECORDS) readonly buffer Records {
    Record records[];
};
layout(std430, set = 0, binding = LANTERN_BINDING_CULL_COMMANDS) writeonly buffer Commands {
    uint commands[];  // VkDrawIndexedIndirectCommand: 5 words each
};
layout(std430, set = 0, binding = LANTERN_BINDING_CULL_COUNTS) buffer Counts {
    uint counts[];  // [0]: triangles kept; then per draw its full and coarser lists' draw counts
};
layout(std430, set = 0, binding = LANTERN_BINDING_CULL_VIEWS) readonly buffer Views {
    View views[];
};

layout(push_constant) uniform CullPush {
    uint records;
} push;

// A back-facing cone must clear the rasteriser's decision by this much (the cosine of the
// angle between the view ray and the cone): snapping the corners to the sub-pixel grid cannot
// turn a triangle whose plane the eye sees at such an angle (about a degree) front-facing,
// unless it is far below a pixel.
const float kConeMargin = 0.02;

// The coarsest level whose error, projected at the nearest depth of the mesh's bounds, stays
// under the bound; level 0 when the eye is within them.
uint chooseLevel(Record r, View v) {
    if (r.levelCount <= 1u || !(v.projection.w > 0.0)) return 0u;
    float pixelsPerUnit = v.projection.x * r.scale;
    if (v.projection.y != 0.0) {
        const vec3 c = (r.viewFromModel * vec4(r.sphere.xyz, 1.0)).xyz;
        const float depth = -c.z - r.sphere.w * r.scale;
        if (!(depth > 0.0)) return 0u;
        pixelsPerUnit /= depth;
    }
    uint level = 0u;
    for (uint l = 1u; l < r.levelCount; ++l)
        if (r.levels[l].error * pixelsPerUnit <= v.projection.w) level = l;
    return level;
}

bool visible(Record r, View v, Cluster k) {
    const vec3 c = (r.viewFromModel * vec4(k.sphere.xyz, 1.0)).xyz;
    const float radius = k.sphere.w * r.scale * 1.0001 + 1e-5 * length(c);
    for (int p = 0; p < 6; ++p) {
        const vec4 plane = v.planes[p];
        if (dot(plane.xyz, c) + plane.w < -radius * length(plane.xyz)) return false;
    }
    if ((r.flags & LANTERN_CULL_CONE) == 0u || v.projection.z == 0.0 || k.axis.w >= 1.0) return true;
    const vec3 apex = (r.viewFromModel * vec4(k.apex.xyz, 1.0)).xyz;
    const vec3 axis = mat3(r.normalMatrix[0].xyz, r.normalMatrix[1].xyz, r.normalMatrix[2].xyz) * k.axis.xyz;
    const float la = length(apex), lx = length(axis);
    if (!(la > 0.0 && lx > 0.0)) return true;
    return dot(apex, axis) < (k.axis.w + kConeMargin) * la * lx;
}

void write(uint at, uint indexCount, uint firstIndex, uint firstInstance) {
    commands[5u * at] = indexCount;
    commands[5u * at + 1u] = 1u;
    commands[5u * at + 2u] = firstIndex;
    commands[5u * at + 3u] = 0u;
    commands[5u * at + 4u] = firstInstance;
}

void main() {
    const uint first = gl_GlobalInvocationID.x;
    if (first >= push.records || records[first].drawRecords == 0u) return;
    const uint drawRecords = records[first].drawRecords;
    uint full = 0u, coarse = 0u, kept = 0u;
    for (uint k = 0u; k < drawRecords; ++k) {
        const Record r = records[first + k];
        const View v = views[r.view];
        const uint level = chooseLevel(r, v);
        const Level l = r.levels[level];
        const uint base = level == 0u ? r.indexBase : 0u;
        uint runFirst = 0u, runCount = 0u;
        for (uint c = 0u; c <= l.clusterCount; ++c) {
            const bool end = c == l.clusterCount;
            Cluster cluster;
            if (!end) cluster = clusters[l.firstCluster + c];
            if (!end && visible(r, v, cluster)) {
                if (runCount == 0u) runFirst = cluster.range.x;
                runCount += cluster.range.y;
                continue;
            }
            if (runCount == 0u) continue;
            if (level == 0u) write(r.firstCommand + full++, runCount, runFirst + base, r.firstInstance);
            else write(r.lodCommand + coarse++, runCount, runFirst, r.firstInstance);
            kept += runCount / 3u;
            runCount = 0u;
        }
    }
    const uint countIndex = records[first].countIndex;
    counts[1u + 2u * countIndex] = full;
    counts[2u + 2u * countIndex] = coarse;
    atomicAdd(counts[0], kept);
}
