// maps.glsl: glTF's material maps per fragment: the metallic-roughness mapping per texel (the
// twin of gltf::phongFromPbr in engine/src/io/GltfMaterials.cpp), the normal map in a tangent
// frame built from screen-space derivatives, occlusion and emission factors.
#ifndef LANTERN_MAPS_GLSL
#define LANTERN_MAPS_GLSL

#include "lighting.glsl"

// The classic side of a metallic-roughness material at metallic m and roughness r:
// f0 = mix(d, b, m) with d the dielectric F0 (0.04 unless KHR_materials_ior or _specular), w = r^2; diffuse = ambient = b (1 - m) + f0 w m;
// shininess = clamp(2 / w^2 - 2, 1, 1e4); specular = f0 (1 - w m) (s + 8) / 8.
MaterialSideData pbrSide(MaterialSideData side, vec4 base, float m, float r, float dielectricF0) {
    float w = r * r;
    vec3 f0 = mix(vec3(dielectricF0), base.rgb, m);
    vec3 diffuse = base.rgb * (1.0 - m) + f0 * (w * m);
    float r4 = w * w;
    float s = r4 > 0.0 ? clamp(2.0 / r4 - 2.0, LANTERN_PBR_MIN_SHININESS, LANTERN_PBR_MAX_SHININESS)
                       : LANTERN_PBR_MAX_SHININESS;
    side.ambient = vec4(diffuse, 0.0);
    side.diffuse = vec4(diffuse, base.a);
    side.specular = vec4(f0 * ((1.0 - w * m) * (s + 8.0) / 8.0), s);
    return side;
}

// The metallic-roughness map at the fragment: the material's factors times the texel's blue
// (metallic) and green (roughness).
MaterialSideData mappedPbrSide(MaterialSideData side, MaterialData material, MapUv u) {
    vec4 texel = mapTexel(metallicRoughnessTexture, u, draw.materialIndex, 0);
    return pbrSide(side, material.pbrBase, material.pbrParams.x * texel.b,
                   material.pbrParams.y * texel.g, material.params.z);
}

// The normal map applied to the unit normal n. With the vertex's tangent (eye space, w the
// bitangent's sign; glTF TANGENT), the frame is T = the tangent made orthogonal to n and
// B = cross(n, T) w (as glTF and MikkTSpace define it). Without one (zero), with dp1, dp2 the
// screen derivatives of the eye-space position: the tangent frame from those and the map's coordinates' derivatives
// (Schüler's cotangent frame, "Normal mapping without precomputed tangents", 2013), T along
// +u and B along -v (glTF's +Y is up in the image); t and b below point the other way because
// Lantern's framebuffer y runs down the eye's y (clipFromView flips it), which reverses the
// frame's handedness. The texel's X and Y are scaled by the material's normal scale. Where no
// frame can be built (the map's coordinates do not change across the pixel) n is kept.
vec3 mappedNormal(vec3 n, vec4 tangent, vec3 dp1, vec3 dp2, MapUv u, MaterialData material) {
    vec3 m = mapTexel(normalTexture, u, draw.materialIndex, 1).xyz * 2.0 - 1.0;
    m.xy *= material.pbrParams.z;
    vec3 given = tangent.xyz - n * dot(n, tangent.xyz);
    float length2 = dot(given, given);
    if (length2 > 0.0 && !isinf(length2)) {
        vec3 t = given * inversesqrt(length2);
        vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
        vec3 mapped = safeNormalize(mat3(t, b, n) * m);
        return dot(mapped, mapped) > 0.0 ? mapped : n;
    }
    SurfaceUv own = mapSet(u, draw.materialIndex, 1);
    vec2 duv1 = transformedGradient(material.mapUv[2], material.mapUv[3], own.dx);
    vec2 duv2 = transformedGradient(material.mapUv[2], material.mapUv[3], own.dy);
    vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
    vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
    vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
    float scale = max(dot(t, t), dot(b, b));
    if (!(scale > 0.0) || isinf(scale)) return n;
    float inv = inversesqrt(scale);
    vec3 mapped = safeNormalize(mat3(-t * inv, b * inv, n) * m);
    return dot(mapped, mapped) > 0.0 ? mapped : n;
}

// The occlusion map's factor on the ambient term: 1 + strength (R - 1).
float mappedOcclusion(MapUv u, MaterialData material) {
    float ao = mapTexel(occlusionTexture, u, draw.materialIndex, 2).r;
    return 1.0 + material.pbrParams.w * (ao - 1.0);
}

// What the emissive map adds to a colour that already holds the side's emission: e (texel - 1).
vec3 mappedEmissionChange(MaterialSideData side, MapUv u) {
    vec3 texel = mapTexel(emissiveTexture, u, draw.materialIndex, 3).rgb;
    return side.emission.rgb * (texel - 1.0);
}

#endif
