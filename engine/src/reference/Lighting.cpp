// The lighting equation in double precision: lighting.glsl's twin, function for function.
#include "reference/Lighting.h"

#include "lantern_shared.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <glm/geometric.hpp>
#include <string>

namespace lantern::ref {

glm::dvec3 safeNormalize(const glm::dvec3& v) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(m > 0.0) || std::isinf(m)) return glm::dvec3(0.0);
    const glm::dvec3 u = v / m;
    return u / std::sqrt(glm::dot(u, u));
}

double safeLength(const glm::dvec3& v) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(m > 0.0) || std::isinf(m)) return m;
    return m * glm::length(v / m);
}

double lobe(const glm::dvec3& a, const glm::dvec3& b, double s) {
    if (s == 0.0) return 1.0;
    const glm::dvec3 d = a - b;
    const double y = 0.5 * glm::dot(d, d);
    if (y >= 1.0) return 0.0;
    return std::exp(s * std::log1p(-y));
}

double glSpotFactor(const glm::dvec3& towardsPoint, const glm::dvec3& axis,
                    double oneMinusCosCutoff, double exponent) {
    const glm::dvec3 d = towardsPoint - axis;
    const double y = 0.5 * glm::dot(d, d);
    return y <= oneMinusCosCutoff ? lobe(towardsPoint, axis, exponent) : 0.0;
}

double specularTerm(const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v, double shininess,
                    SpecularModel model) {
    if (shininess == 0.0) return 1.0;
    if (model == SpecularModel::Phong) {
        const glm::dvec3 r = 2.0 * glm::dot(n, l) * n - l;
        return lobe(r, v, shininess);
    }
    const glm::dvec3 h = safeNormalize(l + v);
    if (h == glm::dvec3(0.0)) return 0.0;
    return lobe(n, h, shininess);
}

glm::dvec3 viewVector(const glm::dvec3& V, bool localViewer) {
    if (!localViewer) return {0.0, 0.0, 1.0};
    const glm::dvec3 v = safeNormalize(-V);
    return v == glm::dvec3(0.0) ? glm::dvec3(0.0, 0.0, 1.0) : v;
}

LightSums evaluateLighting(const glm::dvec3& V, const glm::dvec3& n, const MaterialSide& m,
                           const std::vector<EyeLight>& lights, const Settings& st,
                           std::vector<LightContribution>* contributions,
                           const std::vector<double>* visibility) {
    LightSums s;
    if (st.unlit) {
        s.diffuse = glm::dvec3(1.0);
        return s;
    }
    s.emissiveSpecular = m.emission;
    s.ambient = st.globalAmbient;
    const glm::dvec3 v = viewVector(V, st.localViewer);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const EyeLight& L = lights[i];
        LightContribution c;
        glm::dvec3 l;
        if (L.type == LightType::Directional) {
            l = L.toLight;
        } else {
            const glm::dvec3 toLight = L.position - V;
            const double d = safeLength(toLight);
            l = d > 0.0 ? safeNormalize(toLight) : n;
            if (L.falloff == LightFalloff::Gl) {
                const double denominator =
                    L.attenuation.x + L.attenuation.y * d + (L.attenuation.z * d) * d;
                c.attenuation = 1.0 / std::max(denominator, LANTERN_MIN_ATTENUATION_DENOMINATOR);
            } else {
                double window = 1.0;
                if (L.invRange > 0.0) {
                    double q = d * L.invRange;
                    q = q * q;
                    window = std::clamp(1.0 - q * q, 0.0, 1.0);
                }
                c.attenuation = window / std::max(d * d, LANTERN_MIN_GLTF_DISTANCE_SQUARED);
            }
            if (L.type == LightType::Spot) {
                if (L.falloff == LightFalloff::Gl) {
                    c.spot = glSpotFactor(-l, L.spotAxis, L.oneMinusCosCutoff, L.exponent);
                } else {
                    const double cd = glm::dot(-l, L.spotAxis);
                    const double t = std::clamp((cd - L.cosOuter) * L.coneScale, 0.0, 1.0);
                    c.spot = t * t;
                }
            }
        }
        const double k = c.attenuation * c.spot;
        // A shadow dims the light's diffuse and specular terms, not its ambient one.
        const double lit = visibility ? (*visibility)[i] * k : k;
        c.nDotL = glm::dot(n, l);
        s.ambient += k * L.ambient;
        s.diffuse += (lit * std::max(c.nDotL, 0.0)) * L.diffuse;
        c.ambient = k * L.ambient;
        c.diffuse = (lit * std::max(c.nDotL, 0.0)) * L.diffuse;
        if (c.nDotL > 0.0) {
            c.specularTerm = specularTerm(n, l, v, m.shininess, st.specular);
            c.specular = (lit * c.specularTerm) * (m.specular * L.specular);
            s.emissiveSpecular += c.specular;
        }
        if (contributions) contributions->push_back(c);
    }
    return s;
}

MaterialColours materialColours(const MaterialSide& m, const glm::dvec4* vertexColor,
                                bool scales) {
    MaterialColours r{m.ambient, glm::dvec3(m.diffuse), m.diffuse.a};
    if (vertexColor) {
        const glm::dvec3 rgb(*vertexColor);
        r.ambient = scales ? r.ambient * rgb : rgb;
        r.diffuse = scales ? r.diffuse * rgb : rgb;
        r.alpha *= vertexColor->a;
    }
    return r;
}

SplitColour splitColour(const LightSums& s, const glm::dvec3& ambientM, const glm::dvec3& diffuseM,
                        bool ambientFollowsDiffuse, bool glClamp) {
    SplitColour r;
    if (ambientFollowsDiffuse) {
        r.base = s.emissiveSpecular;
        r.textured = ambientM * s.ambient + diffuseM * s.diffuse;
    } else {
        r.base = s.emissiveSpecular + ambientM * s.ambient;
        r.textured = diffuseM * s.diffuse;
    }
    if (glClamp) {
        r.textured = glm::clamp(r.base + r.textured, 0.0, 1.0);
        r.base = glm::dvec3(0.0);
    }
    return r;
}

glm::dvec3 shade(const glm::dvec3& V, const glm::dvec3& n, const MaterialSide& m,
                 const std::vector<EyeLight>& lights, const Settings& settings) {
    const LightSums s = evaluateLighting(V, n, m, lights, settings);
    const SplitColour c = splitColour(s, m.ambient, glm::dvec3(m.diffuse), false, false);
    return c.base + c.textured;
}

std::vector<ShadowRay> shadowRays(const EyeLight& light, const glm::dvec3& p,
                                  const ShadowOptions& options) {
    const bool directional = light.type == LightType::Directional;
    const ShadowRay centre{directional ? light.toLight : light.position - p,
                           directional ? std::numeric_limits<double>::infinity() : 1.0};
    const bool soft = options.filter == ShadowFilter::Pcss;
    const double size = directional ? std::tan(options.sunRadius * 0.017453292519943295)
                                    : options.lightRadius;
    if (!soft || !(size > 0.0)) return {centre};
    // The disc's frame: w towards the light, u and v across it.
    const glm::dvec3 w = safeNormalize(centre.dir);
    const glm::dvec3 a = std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(w, a)), v = glm::cross(w, u);
    std::vector<ShadowRay> rays;
    rays.reserve(kAreaLightRays);
    const double golden = 2.399963229728653;  // pi (3 - sqrt 5)
    for (int i = 0; i < kAreaLightRays; ++i) {
        const double r = std::sqrt((i + 0.5) / kAreaLightRays), phi = i * golden;
        const glm::dvec3 offset = (r * std::cos(phi)) * u + (r * std::sin(phi)) * v;
        rays.push_back(directional ? ShadowRay{w + size * offset, centre.tMax}
                                   : ShadowRay{centre.dir + size * offset, 1.0});
    }
    return rays;
}

} // namespace lantern::ref
