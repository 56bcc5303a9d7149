// phong.frag: phong shading: the equation per fragment with the interpolated normal,
// renormalised, and the material's maps (maps.glsl). `centroid` keeps MSAA from extrapolating
// interpolants outside the triangle; derivatives come from pixel-centre copies (SurfaceUv).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "output.glsl"
#include "maps.glsl"

layout(location = 0) centroid in vec3 vEyePosition;
layout(location = 1) centroid in vec3 vNormal;
layout(location = 2) centroid in vec4 vColor;
layout(location = 3) centroid in vec2 vTexcoord;
layout(location = 4) in vec3 vEyeCentre;
layout(location = 5) in vec2 vTexcoordCentre;
layout(location = 6) centroid in vec4 vTangent;
layout(location = 7) centroid in vec2 vTexcoord1;
layout(location = 8) in vec2 vTexcoord1Centre;

void main() {
    // Derivatives only in the variants that sample (the branches are on constants, so control
    // flow stays uniform): an untextured scene pays nothing for them.
    SurfaceUv u = SurfaceUv(vTexcoord, vec2(0.0), vec2(0.0));
    if (SC_TEXTURE || SC_MAPS != 0u) {
        u.dx = dFdx(vTexcoordCentre);
        u.dy = dFdy(vTexcoordCentre);
    }
    MapUv mu = MapUv(u, SurfaceUv(vTexcoord1, vec2(0.0), vec2(0.0)));
    if ((SC_MAPS & LANTERN_MAP_SECOND_SETS) != 0u) {
        mu.second.dx = dFdx(vTexcoord1Centre);
        mu.second.dy = dFdy(vTexcoord1Centre);
    }
    vec3 dp1 = vec3(0.0), dp2 = vec3(0.0);
    if ((SC_MAPS & LANTERN_MAP_NORMAL) != 0u) {
        dp1 = dFdx(vEyeCentre);
        dp2 = dFdy(vEyeCentre);
    }
    MaterialData material = materials[draw.materialIndex];
    const uint maps = materialMaps(draw.materialIndex);
    bool back = SC_TWO_SIDED && !gl_FrontFacing;
    MaterialSideData side = back ? material.back : material.front;
    if ((maps & LANTERN_MAP_METALLIC_ROUGHNESS) != 0u) side = mappedPbrSide(side, material, mu);
    vec3 n = safeNormalize(vNormal);
    if ((maps & LANTERN_MAP_NORMAL) != 0u) n = mappedNormal(n, vTangent, dp1, dp2, mu, material);
    vec3 ambientM, diffuseM;
    float alpha;
    materialColours(side, vColor, ambientM, diffuseM, alpha);
    vec4 texel = SC_TEXTURE ? baseColorTexel(u, draw.materialIndex) : vec4(1.0);
    alpha *= texel.a;
    if (SC_ALPHA_MASK && alpha < material.params.x) discard;
    LightSums sums = evaluateLighting(vEyePosition, back ? -n : n, side);
    if ((maps & LANTERN_MAP_OCCLUSION) != 0u) sums.ambient *= mappedOcclusion(mu, material);
    if ((maps & LANTERN_MAP_EMISSIVE) != 0u) sums.emissiveSpecular += mappedEmissionChange(side, mu);
    vec3 base, textured;
    splitColour(sums, ambientM, diffuseM, base, textured);
    writeOutputs(base + texel.rgb * textured, alpha, n, vEyePosition, vTexcoord);
}
