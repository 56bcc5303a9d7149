// lighting.glsl: the only GLSL copy of Lantern's lighting equation (scene-format.md section 1),
// used per fragment (phong), per vertex (gouraud) and per triangle (flat). Its C++ twin, with
// the same function names and guards, is engine/src/reference/Lighting.cpp.
//
//   c = e_m + a_m A + sum_i att_i spot_i (a_m a_i + max(n.l_i, 0) d_m d_i + f_i spec_i s_m s_i)
//
// evaluateLighting() returns the three sums that multiply 1, a_m and d_m, so that a base-colour
// texture or a vertex colour can scale a_m and d_m after the lights were summed (per fragment
// in every mode).
#ifndef LANTERN_LIGHTING_GLSL
#define LANTERN_LIGHTING_GLSL

#include "lantern_shared.h"
#include "specialization.glsl"
#include "uniforms.glsl"
#include "shadows.glsl"

struct LightSums {
    vec3 emissiveSpecular;  // e_m + sum att spot f spec s_m s_i
    vec3 ambient;           // A + sum att spot a_i          (times a_m)
    vec3 diffuse;           // sum att spot max(n.l, 0) d_i  (times d_m)
};

// The unit vector along v, computed without overflow or underflow (scaled by its largest
// component first: normalize(1e20, 0, 0) is 0 on lavapipe). The zero vector maps to zero.
vec3 safeNormalize(vec3 v) {
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (!(m > 0.0) || isinf(m)) return vec3(0.0);
    vec3 u = v / m;
    return u * inversesqrt(dot(u, u));
}

// |v| without overflow or underflow.
float safeLength(vec3 v) {
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (!(m > 0.0) || isinf(m)) return m;
    return m * length(v / m);
}

// ln(1 - y) for y in [0, 1) with a small relative error for every y. GLSL's log() only
// promises an absolute error of 2^-21 near 1 (and lavapipe's has it: Kahan's log1p trick
// built on it lost 6% of the highlight at shininess 1e6), so below 1/16 the series
// -(y + y^2/2 + ... + y^6/6) is used (truncation < 1e-8 relative); above, |ln(1 - y)| > 0.06
// and log()'s absolute error is < 1e-5 of it.
float logOneMinus(float y) {
    if (y < 0.0625) {
        float p = 1.0 / 5.0 + y * (1.0 / 6.0);
        p = 1.0 / 3.0 + y * (1.0 / 4.0 + y * p);
        return -y * (1.0 + y * (1.0 / 2.0 + y * p));
    }
    return log(1.0 - y);
}

// max(a.b, 0)^s for unit vectors a and b, evaluated as exp(s ln(1 - y)) with
// y = 1 - a.b = |a - b|^2 / 2: no cancellation near the peak, so the highlight stays within
// 1e-6 of the exact value for any shininess (pow(dot(a, b), s) loses 3% at s = 1e6).
// s = 0 gives 1 for every a, b (x^0 = 1, where GLSL's pow(0, 0) is undefined and lavapipe's
// is 0). Every power in the equation (shininess, spot exponent) goes through here.
float lobe(vec3 a, vec3 b, float s) {
    if (s == 0.0) return 1.0;
    vec3 d = a - b;
    float y = 0.5 * dot(d, d);
    if (y >= 1.0) return 0.0;
    return exp(s * logOneMinus(y));
}

// GL's spot factor: x = max(-l.s, 0); x^e inside the cone (x >= cos(cutoff)), else 0. Evaluated
// as 1 - x = |(-l) - s|^2 / 2 against oneMinusCosCutoff = 1 - cos(cutoff) (computed in double
// on the CPU) and x^e as lobe(): no cancellation near the axis, so a cutoff of 0.01 degrees
// keeps its edge and a huge exponent its shape (1 - x rounds to 0 in float within 0.02
// degrees of the axis). Outside 90 degrees x is 0, and the cutoff is at most 90.
float glSpotFactor(vec3 towardsPoint, vec3 axis, float oneMinusCosCutoff, float exponent) {
    vec3 d = towardsPoint - axis;
    float y = 0.5 * dot(d, d);
    return y <= oneMinusCosCutoff ? lobe(towardsPoint, axis, exponent) : 0.0;
}

// spec_i: Blinn max(n.h, 0)^s with h = normalize(l + v), or Phong max(r.v, 0)^s with
// r = 2(n.l)n - l. Shininess 0 gives 1 (x^0 = 1 for every x); otherwise, when l = -v there is
// no halfway vector and the term is 0.
float specularTerm(vec3 n, vec3 l, vec3 v, float shininess) {
    if (shininess == 0.0) return 1.0;
    if (SC_SPECULAR == LANTERN_SPECULAR_PHONG) {
        vec3 r = 2.0 * dot(n, l) * n - l;
        return lobe(r, v, shininess);
    }
    vec3 h = safeNormalize(l + v);
    if (h == vec3(0.0)) return 0.0;
    return lobe(n, h, shininess);
}

// The view vector: towards the eye with a local viewer, else GL's (0, 0, 1).
vec3 viewVector(vec3 V) {
    if (!SC_LOCAL_VIEWER) return vec3(0.0, 0.0, 1.0);
    vec3 v = safeNormalize(-V);
    return v == vec3(0.0) ? vec3(0.0, 0.0, 1.0) : v;
}

// Light i's terms of the sum, added to s, for a point at V with unit normal n, view vector v,
// shininess and the material's specular colour. The light is read where it lies, its specular
// colour before the branch that uses it (llvmpipe reads a storage buffer inside a branch lane
// by lane). `kind` is the light's type and falloff (type | falloff << 2) when the pipeline
// knows it, or LANTERN_LIGHT_KIND_ANY to read them from the light; with a known kind the other
// kinds' code is removed.
void addLight(inout LightSums s, uint i, uint kind, vec3 V, vec3 n, vec3 v,
              float shininess, vec3 specularM) {
    vec4 lightSpecular = LIGHT(i, specular);  // read outside the branch below
    bool known = kind != LANTERN_LIGHT_KIND_ANY;
    uint type = known ? (kind & 3u) : LIGHT(i, info).x;
    uint falloff = known ? (kind >> 2u) & 1u : LIGHT(i, info).y;
    vec3 l;
    float att = 1.0;
    float spot = 1.0;
    if (type == LANTERN_LIGHT_DIRECTIONAL) {
        if ((SC_LIGHT_TYPES & LANTERN_LIGHT_BIT_DIRECTIONAL) == 0u) return;
        l = LIGHT(i, position).xyz;
    } else {
        if ((SC_LIGHT_TYPES & (LANTERN_LIGHT_BIT_POINT | LANTERN_LIGHT_BIT_SPOT)) == 0u) return;
        vec3 toLight = LIGHT(i, position).xyz - V;
        float d = safeLength(toLight);
        // A light exactly at the point shines along the normal (finite, documented).
        l = d > 0.0 ? safeNormalize(toLight) : n;
        if (SC_GL_ATTENUATION && falloff == LANTERN_FALLOFF_GL) {
            vec4 k = LIGHT(i, attenuation);
            // (kq d) d rather than kq (d d): kq = 0 with d^2 = inf must give 0, not NaN.
            float denominator = k.x + k.y * d + (k.z * d) * d;
            att = 1.0 / max(denominator, LANTERN_MIN_ATTENUATION_DENOMINATOR);
        }
        if (SC_GLTF_FALLOFF && falloff == LANTERN_FALLOFF_GLTF) {
            float invRange = LIGHT(i, attenuation).w;
            float window = 1.0;
            if (invRange > 0.0) {
                float q = d * invRange;
                q = q * q;
                window = clamp(1.0 - q * q, 0.0, 1.0);
            }
            att = window / max(d * d, LANTERN_MIN_GLTF_DISTANCE_SQUARED);
        }
        if (type == LANTERN_LIGHT_SPOT) {
            if ((SC_LIGHT_TYPES & LANTERN_LIGHT_BIT_SPOT) == 0u) return;
            vec3 axis = LIGHT(i, spotDirection).xyz;
            if (SC_GL_SPOT && falloff == LANTERN_FALLOFF_GL)
                spot = glSpotFactor(-l, axis, LIGHT(i, spotDirection).w, LIGHT(i, spot).x);
            if (SC_GLTF_FALLOFF && falloff == LANTERN_FALLOFF_GLTF) {
                float t = clamp((dot(-l, axis) - LIGHT(i, spot).y) * LIGHT(i, spot).z, 0.0, 1.0);
                spot = t * t;
            }
        }
    }
    float k = att * spot;
    float ndotl = dot(n, l);
    s.ambient += k * LIGHT(i, ambient).rgb;
    // A shadow dims the light's diffuse and specular terms, not its ambient one.
    float lit = k;
    if (SC_SHADOWS != LANTERN_SHADOW_NONE && ndotl > 0.0 && k > 0.0) {
        uvec4 info = LIGHT(i, info);
        if (info.z != 0u) lit *= shadowVisibility(info.z - 1u, info.w, V, n, LIGHT(i, position).xyz);
    }
    s.diffuse += (lit * max(ndotl, 0.0)) * LIGHT(i, diffuse).rgb;
    // f_i selects rather than multiplies, so a non-finite term on the dark side cannot leak.
    if (SC_SPECULAR != LANTERN_SPECULAR_NONE && ndotl > 0.0) {
        float spec = specularTerm(n, l, v, shininess);
        s.emissiveSpecular += (lit * spec) * (specularM * lightSpecular.rgb);
    }
}

// LANTERN_UNROLL, a define of each entry point (shaders/CMakeLists.txt): the most lights it
// unrolls, 2 or 8 (LANTERN_MAX_UNROLLED_LIGHTS), or 0 for the loop. Each copy of a light's
// terms is inlined before the specialisation removes the unused ones, so an entry point for a
// few lights has only their copies (gpu/Pipelines.cpp picks it by SC_UNROLLED_LIGHTS).
#ifndef LANTERN_UNROLL
#define LANTERN_UNROLL 0
#endif

// Light i's kind when the lights are unrolled (LANTERN_SC_LIGHT_KINDS).
uint unrolledKind(uint i) {
    return (SC_LIGHT_KINDS >> (LANTERN_LIGHT_KIND_BITS * i)) & 0xFu;
}

// The sums of the equation at eye-space point V with unit normal n (zero normal: ambient and
// emission only) for material side m (its specular, emission and shininess; ambient and
// diffuse are applied by the caller).
LightSums evaluateLighting(vec3 V, vec3 n, MaterialSideData m) {
    LightSums s;
    if (SC_UNLIT) {
        s.emissiveSpecular = vec3(0.0);
        s.ambient = vec3(0.0);
        s.diffuse = vec3(1.0);
        return s;
    }
    s.emissiveSpecular = m.emission.rgb;
    s.ambient = frame.globalAmbient.rgb;
    s.diffuse = vec3(0.0);
    vec3 v = viewVector(V);
    float shininess = m.specular.w;
    vec3 specularM = m.specular.rgb;
#if LANTERN_UNROLL == 0
    for (uint i = 0u; i < frame.lightCount; ++i)
        addLight(s, i, LANTERN_LIGHT_KIND_ANY, V, n, v, shininess, specularM);
#else
    // Unrolled (at most LANTERN_MAX_UNROLLED_LIGHTS lights): each light is read at a constant
    // index outside any branch, which llvmpipe does once for all lanes, where the loop reads
    // every lane's copy under the loop's mask (docs/performance.md).
    if (SC_UNROLLED_LIGHTS > 0u) addLight(s, 0u, unrolledKind(0u), V, n, v, shininess, specularM);
    if (SC_UNROLLED_LIGHTS > 1u) addLight(s, 1u, unrolledKind(1u), V, n, v, shininess, specularM);
#if LANTERN_UNROLL > 2
    if (SC_UNROLLED_LIGHTS > 2u) addLight(s, 2u, unrolledKind(2u), V, n, v, shininess, specularM);
    if (SC_UNROLLED_LIGHTS > 3u) addLight(s, 3u, unrolledKind(3u), V, n, v, shininess, specularM);
    if (SC_UNROLLED_LIGHTS > 4u) addLight(s, 4u, unrolledKind(4u), V, n, v, shininess, specularM);
    if (SC_UNROLLED_LIGHTS > 5u) addLight(s, 5u, unrolledKind(5u), V, n, v, shininess, specularM);
    if (SC_UNROLLED_LIGHTS > 6u) addLight(s, 6u, unrolledKind(6u), V, n, v, shininess, specularM);
    if (SC_UNROLLED_LIGHTS > 7u) addLight(s, 7u, unrolledKind(7u), V, n, v, shininess, specularM);
#endif
#endif
    return s;
}

// The material's ambient and diffuse colours and alpha at a point: COLOR_0 replaces ambient
// and diffuse (GL's colour-material tracking) of a Phong material, scales them for unlit and
// PBR-mapped materials, and multiplies alpha in every case.
void materialColours(MaterialSideData m, vec4 vertexColor, out vec3 ambientM, out vec3 diffuseM,
                     out float alpha) {
    ambientM = m.ambient.rgb;
    diffuseM = m.diffuse.rgb;
    alpha = m.diffuse.a;
    if (SC_VERTEX_COLOR && (draw.flags & 1u) != 0u) {
        // glTF's meaning for unlit and PBR-mapped materials: COLOR_0 scales the base colour.
        bool scales = SC_UNLIT || SC_AMBIENT_FOLLOWS_DIFFUSE;
        ambientM = scales ? ambientM * vertexColor.rgb : vertexColor.rgb;
        diffuseM = scales ? diffuseM * vertexColor.rgb : vertexColor.rgb;
        alpha *= vertexColor.a;
    }
}

// clamp(v, 0, 1) that lets NaN and Inf through: lavapipe's clamp turns NaN into 0, which would
// hide a bug from the non-finite count taken at readback (numerics.md LN-13).
vec3 clampVisible(vec3 v) {
    bvec3 bad = bvec3(uvec3(isnan(v)) | uvec3(isinf(v)));
    return mix(clamp(v, 0.0, 1.0), v, bad);
}

// Splits the colour into `base` and `textured` so that colour = base + texel * textured: the
// base-colour texture scales the diffuse term (and the ambient term when the material's
// ambient follows its diffuse). With GL's clamp the lit colour is clamped where it is computed
// and the texture modulates all of it (GL_MODULATE).
void splitColour(LightSums s, vec3 ambientM, vec3 diffuseM, out vec3 base, out vec3 textured) {
    if (SC_AMBIENT_FOLLOWS_DIFFUSE) {
        base = s.emissiveSpecular;
        textured = ambientM * s.ambient + diffuseM * s.diffuse;
    } else {
        base = s.emissiveSpecular + ambientM * s.ambient;
        textured = diffuseM * s.diffuse;
    }
    if (SC_CLAMP == LANTERN_CLAMP_GL) {
        textured = clampVisible(base + textured);
        base = vec3(0.0);
    }
}

// splitColour as the fragment stage receives it: without a base-colour texture the two parts
// are summed here (pervertex.vert, flatlight.comp), and the fragment stage reads only `base`.
void splitLit(LightSums s, vec3 ambientM, vec3 diffuseM, out vec3 base, out vec3 textured) {
    splitColour(s, ambientM, diffuseM, base, textured);
    if (!SC_TEXTURE) {
        base += textured;
        textured = vec3(0.0);
    }
}

// The normal matrix of this draw.
mat3 drawNormalMatrix() {
    return mat3(draw.normalMatrix[0].xyz, draw.normalMatrix[1].xyz, draw.normalMatrix[2].xyz);
}

#endif
