// reference/Lighting.h: the CPU reference of Lantern's lighting equation in double precision:
// the C++ twin of shaders/include/lighting.glsl, with the same function names and the same
// guards, evaluated from the scene's own (double) data. Every term is always evaluated: the
// reference has no notion of which terms a pipeline variant compiled. Used by tests, --probe
// and the accuracy benchmark.
#pragma once

#include "frame/Frame.h"

#include <lantern/Scene.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace lantern::ref {

/// Lights are placed once, by the frame model (frame::placeLights).
using EyeLight = frame::EyeLight;

/// The lighting switches that change the equation.
struct Settings {
    glm::dvec3 globalAmbient{0.2, 0.2, 0.2};
    bool localViewer = false;
    SpecularModel specular = SpecularModel::Blinn;
    bool unlit = false;
};

/// The three sums of the equation (see lighting.glsl).
struct LightSums {
    glm::dvec3 emissiveSpecular{0.0};
    glm::dvec3 ambient{0.0};
    glm::dvec3 diffuse{0.0};
};

/// One light's terms at a point, for --probe. The ambient and diffuse sums still lack the
/// material's a_m and d_m (a vertex colour may replace them; the caller applies them).
struct LightContribution {
    double attenuation = 1.0;   ///< att_i
    double spot = 1.0;          ///< spot_i
    double nDotL = 0.0;         ///< n.l_i (unclamped; f_i = 1 where it is > 0)
    double specularTerm = 0.0;  ///< spec_i where f_i = 1 and the variant has a specular term
    glm::dvec3 ambient{0.0};    ///< att spot a_i
    glm::dvec3 diffuse{0.0};    ///< att spot max(n.l, 0) d_i
    glm::dvec3 specular{0.0};   ///< att spot f_i spec_i s_m s_i (complete)
};

glm::dvec3 safeNormalize(const glm::dvec3& v);
double safeLength(const glm::dvec3& v);
/// max(a.b, 0)^s for unit a, b (s = 0 gives 1), exactly: exp(s log1p(-|a-b|^2/2)).
double lobe(const glm::dvec3& a, const glm::dvec3& b, double s);
/// GL's spot factor for the unit vector from the light towards the point: x^e inside the
/// cone, 0 outside, with 1 - x = |towardsPoint - axis|^2 / 2 compared with 1 - cos(cutoff).
double glSpotFactor(const glm::dvec3& towardsPoint, const glm::dvec3& axis,
                    double oneMinusCosCutoff, double exponent);
double specularTerm(const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v,
                    double shininess, SpecularModel model);
glm::dvec3 viewVector(const glm::dvec3& V, bool localViewer);

/// The sums at eye-space point V with unit (or zero) normal n for material side m.
/// `visibility`, one per light: the share of the light that reaches V (0 in its shadow), which
/// scales the light's diffuse and specular terms (its ambient term is not shadowed); null: 1.
LightSums evaluateLighting(const glm::dvec3& V, const glm::dvec3& n, const MaterialSide& m,
                           const std::vector<EyeLight>& lights, const Settings& settings,
                           std::vector<LightContribution>* contributions = nullptr,
                           const std::vector<double>* visibility = nullptr);

/// The material's ambient and diffuse colours and alpha at a point (materialColours in the
/// shaders): a vertex colour replaces ambient and diffuse, or scales them when `scales` (unlit
/// and PBR-mapped materials), and multiplies alpha.
struct MaterialColours {
    glm::dvec3 ambient{0.0}, diffuse{0.0};
    double alpha = 1.0;
};
MaterialColours materialColours(const MaterialSide& m, const glm::dvec4* vertexColor,
                                bool scales);

/// colour = base + texel * textured, as splitColour in the shaders.
struct SplitColour {
    glm::dvec3 base{0.0}, textured{0.0};
};
SplitColour splitColour(const LightSums& s, const glm::dvec3& ambientM,
                        const glm::dvec3& diffuseM, bool ambientFollowsDiffuse, bool glClamp);

/// One shadow ray from a point: towards p + t * dir for t in (0, tMax).
struct ShadowRay {
    glm::dvec3 dir{0.0};
    double tMax = 1.0;
};

/// The shadow rays from eye-space point p towards `light`: one to a point-like light (ending at
/// it; unbounded along a directional light), or, when the options give lights a size (PCSS:
/// ShadowOptions::lightRadius, sunRadius), kAreaLightRays rays to points spread evenly over
/// the light's disc as p sees it (a sunflower pattern), whose unblocked share is the light's
/// visibility. Positional lights are discs of that radius facing p; directional lights cones
/// of that angular radius.
constexpr int kAreaLightRays = 64;
std::vector<ShadowRay> shadowRays(const EyeLight& light, const glm::dvec3& p,
                                  const ShadowOptions& options);

/// The full colour at a point without textures or vertex colours (unclamped).
glm::dvec3 shade(const glm::dvec3& V, const glm::dvec3& n, const MaterialSide& m,
                 const std::vector<EyeLight>& lights, const Settings& settings);

} // namespace lantern::ref
