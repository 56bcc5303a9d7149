// flatlight.comp: flat shading lit once per triangle, before the draws. One invocation per
// triangle of one draw (a FlatJob, flatjob.glsl) transforms its corners as flat.vert does,
// skips it when the rasteriser will certainly not draw it (outside the view volume, or
// back-facing in a draw that culls back faces), and otherwise evaluates the equation once per lit side at the centroid
// with the face normal and the mean vertex colour (the rule of the per-corner path in
// pervertex.vert, LANTERN_FLAT_CENTROID), writing the triangle's record (flat.glsl). The
// specialisation constants are the draw's, so the same terms are compiled in.
#version 460
#extension GL_GOOGLE_include_directive : require
#define LANTERN_DRAW_FROM_JOB
#include "lighting.glsl"
#define LANTERN_FLAT_ACCESS writeonly
#include "flat.glsl"
#define LANTERN_FLAT_INDEX_WRITER
#include "flatjob.glsl"
#include "guard.glsl"

layout(local_size_x = LANTERN_FLAT_GROUP) in;

layout(push_constant) uniform FlatPush {
    uint job;
} push;

vec4 vertexColor(FlatJob j, uint v) {
    const uint o = j.colors + 4u * v;
    return uintBitsToFloat(uvec4(geometry.words[o], geometry.words[o + 1u], geometry.words[o + 2u],
                                 geometry.words[o + 3u]));
}

// All three corners beyond one plane of Vulkan's clip volume (-w <= x, y <= w, 0 <= z <= w):
// every point of the triangle is, so nothing of it is rasterised (exact in homogeneous space,
// whatever the signs of w).
bool outsideView(vec4 c0, vec4 c1, vec4 c2) {
    if (c0.x > c0.w && c1.x > c1.w && c2.x > c2.w) return true;
    if (c0.x < -c0.w && c1.x < -c1.w && c2.x < -c2.w) return true;
    if (c0.y > c0.w && c1.y > c1.w && c2.y > c2.w) return true;
    if (c0.y < -c0.w && c1.y < -c1.w && c2.y < -c2.w) return true;
    if (c0.z < 0.0 && c1.z < 0.0 && c2.z < 0.0) return true;
    return c0.z > c0.w && c1.z > c1.w && c2.z > c2.w;
}

// Back-facing with a margin the rasteriser cannot cross: twice the signed area in pixels
// beyond 1/64 pixel times the perimeter (snapping to the sub-pixel grid moves each corner by
// at most 1/512 pixel, which changes the area by less than that). A triangle that crosses the
// eye plane is kept. Vulkan's a = -(shoelace area) in framebuffer coordinates (y down), and a
// positive a is front-facing under VK_FRONT_FACE_COUNTER_CLOCKWISE.
bool certainlyBack(FlatJob j, vec4 c0, vec4 c1, vec4 c2) {
    if ((j.cull & LANTERN_FLAT_CULL_BACK) == 0u) return false;
    if (!(c0.w > 0.0 && c1.w > 0.0 && c2.w > 0.0)) return false;
    const vec2 s0 = c0.xy / c0.w * j.viewport.xy, s1 = c1.xy / c1.w * j.viewport.xy,
               s2 = c2.xy / c2.w * j.viewport.xy;
    const vec2 e1 = s1 - s0, e2 = s2 - s0;
    float shoelace = e1.x * e2.y - e1.y * e2.x;
    if ((j.cull & LANTERN_FLAT_FRONT_CLOCKWISE) != 0u) shoelace = -shoelace;
    const float perimeter = length(e1) + length(e2) + length(s2 - s1);
    return shoelace > perimeter * (1.0 / 64.0);
}

void writeSide(uint at, LightSums sums, MaterialSideData side, vec4 colour) {
    vec3 ambientM, diffuseM, base, textured;
    float alpha;
    materialColours(side, colour, ambientM, diffuseM, alpha);
    splitLit(sums, ambientM, diffuseM, base, textured);
    guardLit(base, textured, alpha);
    flatColors[at] = vec4(base, alpha);
    if (SC_TEXTURE) flatColors[at + 1u] = vec4(textured, 0.0);
}

void main() {
    const FlatJob j = jobs[push.job];
    const uint t = gl_GlobalInvocationID.x;
    if (t >= j.count) return;
    draw = DrawData(j.viewFromModel, j.normalMatrix, j.materialIndex, j.drawIndex, j.flags,
                    push.job);
    uint v[3];
    vec3 p[3];
    vec4 clip[3];
    for (uint c = 0u; c < 3u; ++c) {
        v[c] = cornerVertex(j, t, c);
        p[c] = position(j, v[c]);
        clip[c] = frame.clipFromView * (draw.viewFromModel * vec4(p[c], 1.0));
    }
    // The draw's index list (flatjob.glsl): a skipped triangle draws nothing and makes no
    // vertex of it shaded.
    const uint list = 3u * (j.flatBase + t);
    if (outsideView(clip[0], clip[1], clip[2]) || certainlyBack(j, clip[0], clip[1], clip[2])) {
        flatIndices[list] = flatIndices[list + 1u] = flatIndices[list + 2u] = j.count;
        return;
    }
    flatIndices[list] = t;
    flatIndices[list + 1u] = j.count + v[1];
    flatIndices[list + 2u] = j.count + v[2];

    const vec3 middle = (p[0] + p[1] + p[2]) / 3.0;
    const vec3 shadePoint = (draw.viewFromModel * vec4(middle, 1.0)).xyz;
    const vec3 face = safeNormalize(cross(p[1] - p[0], p[2] - p[0]));
    const vec3 n = safeNormalize(drawNormalMatrix() * face);
    vec4 colour = vec4(1.0);
    if (j.colors != LANTERN_DEFORM_NONE)
        colour = (vertexColor(j, v[0]) + vertexColor(j, v[1]) + vertexColor(j, v[2])) / 3.0;

    const uint triangle = j.flatBase + t;
    const uint at = triangle * flatRecordVectors();
    MaterialData material = materials[draw.materialIndex];
    writeSide(at, evaluateLighting(shadePoint, n, material.front), material.front, colour);
    if (SC_TWO_SIDED)
        writeSide(at + flatVectorsPerSide(), evaluateLighting(shadePoint, -n, material.back),
                  material.back, colour);
    if (j.writeNormals != 0u) flatNormals[triangle] = vec4(n, 0.0);
}
