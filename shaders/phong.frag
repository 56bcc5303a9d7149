// phong.frag: phong shading: the equation per fragment with the interpolated normal,
// renormalised. `centroid` keeps MSAA from extrapolating interpolants outside the triangle.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "output.glsl"

layout(location = 0) centroid in vec3 vEyePosition;
layout(location = 1) centroid in vec3 vNormal;
layout(location = 2) centroid in vec4 vColor;
layout(location = 3) centroid in vec2 vTexcoord;

void main() {
    MaterialData material = materials[draw.materialIndex];
    bool back = SC_TWO_SIDED && !gl_FrontFacing;
    MaterialSideData side = back ? material.back : material.front;
    vec3 n = safeNormalize(vNormal);
    vec3 ambientM, diffuseM;
    float alpha;
    materialColours(side, vColor, ambientM, diffuseM, alpha);
    vec4 texel = SC_TEXTURE ? texture(baseColorTexture, baseColorUv(vTexcoord, draw.materialIndex)) : vec4(1.0);
    alpha *= texel.a;
    if (SC_ALPHA_MASK && alpha < material.params.x) discard;
    LightSums sums = evaluateLighting(vEyePosition, back ? -n : n, side);
    vec3 base, textured;
    splitColour(sums, ambientM, diffuseM, base, textured);
    writeOutputs(base + texel.rgb * textured, alpha, n, vEyePosition);
}
