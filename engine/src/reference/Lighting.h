// reference/Lighting.h: the CPU reference of Lantern's lighting equation in double precision:
// the C++ twin of shaders/include/lighting.glsl, with the same function names and the same
// guards, evaluated from the scene's own (double) data. Used by tests, --probe and the
// accuracy benchmark.
#pragma once

#include <lantern/Renderer.h>
#include <lantern/Scene.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace lantern::ref {

/// A light in eye space, in double precision.
struct EyeLight {
    LightType type = LightType::Point;  ///< Spot with GL cutoff 180 is stored as Point
    LightFalloff falloff = LightFalloff::Gl;
    glm::dvec3 position{0.0};   ///< eye space (positional lights)
    glm::dvec3 toLight{0, 0, 1};  ///< unit, towards the light (directional lights)
    glm::dvec3 spotAxis{0, 0, -1};
    glm::dvec3 ambient{0.0}, diffuse{1.0}, specular{1.0};
    glm::dvec3 attenuation{1, 0, 0};
    double invRange = 0.0;
    double cosCutoff = -1.0, exponent = 0.0;       ///< GL spot
    double cosOuter = 0.0, coneScale = 1.0;        ///< glTF spot: 1/max(cos inner - cos outer, 1e-6)
    std::string name;
};

/// The lighting switches that change the equation.
struct Settings {
    glm::dvec3 globalAmbient{0.2, 0.2, 0.2};
    bool localViewer = false;
    SpecularModel specular = SpecularModel::Blinn;
    bool specularOn = true;  ///< false: the specular term is absent (as the variant compiles it)
    bool unlit = false;
};

/// The three sums of the equation (see lighting.glsl).
struct LightSums {
    glm::dvec3 emissiveSpecular{0.0};
    glm::dvec3 ambient{0.0};
    glm::dvec3 diffuse{0.0};
};

/// One light's share of the colour at a point, for --probe.
struct LightContribution {
    double attenuation = 1.0, spot = 1.0, nDotL = 0.0, specularTerm = 0.0;
    glm::dvec3 ambient{0.0}, diffuse{0.0}, specular{0.0};  ///< already times the material
};

glm::dvec3 safeNormalize(const glm::dvec3& v);
double safeLength(const glm::dvec3& v);
double powSafe(double x, double e);
/// max(a.b, 0)^s for unit a, b (s = 0 gives 1), exactly: exp(s log1p(-|a-b|^2/2)).
double lobe(const glm::dvec3& a, const glm::dvec3& b, double s);
double specularTerm(const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v,
                    double shininess, SpecularModel model);
glm::dvec3 viewVector(const glm::dvec3& V, bool localViewer);

/// The sums at eye-space point V with unit (or zero) normal n for material side m.
LightSums evaluateLighting(const glm::dvec3& V, const glm::dvec3& n, const MaterialSide& m,
                           const std::vector<EyeLight>& lights, const Settings& settings,
                           std::vector<LightContribution>* contributions = nullptr);

/// colour = base + texel * textured, as splitColour in the shaders.
struct SplitColour {
    glm::dvec3 base{0.0}, textured{0.0};
};
SplitColour splitColour(const LightSums& s, const glm::dvec3& ambientM,
                        const glm::dvec3& diffuseM, bool ambientFollowsDiffuse, bool glClamp);

/// The full colour at a point without textures: e + a A + ... with optional clamp.
glm::dvec3 shade(const glm::dvec3& V, const glm::dvec3& n, const MaterialSide& m,
                 const std::vector<EyeLight>& lights, const Settings& settings);

/// Eye-space lights of a scene at a pose, as the renderer places them (GL's light 0 when the
/// scene has none). `glCompat` limits spot exponents to 128.
std::vector<EyeLight> eyeLights(const Scene& scene, const Pose& pose,
                                const glm::dmat4& viewFromWorld, bool glCompat);

} // namespace lantern::ref
