// Light placement: the scene's lights carried into a camera's eye space in double precision,
// or GL's light 0 when the scene has none. The only place lights are placed; the GPU packing
// (render/Packing.cpp) and the CPU reference both read the result.
#include "frame/Frame.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::frame {
namespace {

constexpr double kPi = 3.14159265358979323846;

EyeLight place(const Light& l, const std::string& fallbackName, const glm::dmat4& viewFromLight,
               bool glCompat) {
    EyeLight e;
    e.name = l.name.empty() ? fallbackName : l.name;
    e.falloff = l.falloff;
    e.type = l.type;
    // A GL spot whose cutoff is 180 degrees is a point light (GL's own rule).
    if (l.type == LightType::Spot && l.falloff == LightFalloff::Gl && l.spotCutoffDeg == 180.0)
        e.type = LightType::Point;
    e.position = glm::dvec3(viewFromLight[3]);
    glm::dvec3 axis = glm::dmat3(viewFromLight) * glm::dvec3(0, 0, -1);
    const double len = glm::length(axis);
    axis = (len > 0.0 && std::isfinite(len)) ? axis / len : glm::dvec3(0, 0, -1);
    e.spotAxis = axis;
    e.toLight = -axis;
    e.ambient = l.ambient;
    e.diffuse = l.diffuse;
    e.specular = l.specular;
    e.attenuation = l.attenuation;
    e.invRange = std::isinf(l.range) ? 0.0 : 1.0 / l.range;
    // 1 - cos(cutoff) as 2 sin^2(cutoff / 2): exact for small cutoffs (lighting.glsl's
    // glSpotFactor compares 1 - cos(angle) with it).
    const double halfCutoff = std::min(l.spotCutoffDeg, 90.0) * kPi / 360.0;
    e.oneMinusCosCutoff = 2.0 * std::sin(halfCutoff) * std::sin(halfCutoff);
    e.exponent = glCompat ? std::min(l.spotExponent, 128.0) : l.spotExponent;
    e.cosOuter = std::cos(l.outerConeAngle);
    e.coneScale = 1.0 / std::max(std::cos(l.innerConeAngle) - e.cosOuter, 1e-6);
    e.castShadows = l.castShadows && !glCompat;
    // The cone's half-angle: a GL cutoff or glTF's outer angle.
    e.coneAngle = l.falloff == LightFalloff::Gl ? std::min(l.spotCutoffDeg, 90.0) * kPi / 180.0
                                                : l.outerConeAngle;
    return e;
}

} // namespace

std::vector<EyeLight> placeLights(const Scene& scene, const Pose& pose,
                                  const glm::dmat4& viewFromWorld, bool glCompat) {
    std::vector<EyeLight> out;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (pose.visible[i] && scene.nodes[i].light >= 0)
            out.push_back(place(scene.lights[std::size_t(scene.nodes[i].light)],
                                "light " + std::to_string(scene.nodes[i].light),
                                viewFromWorld * pose.worldFromNode[i], glCompat));
    if (out.empty()) {
        // GL's light 0 is defined in eye space: a white directional headlight along +Z.
        Light l;
        l.name = "GL default light 0";
        l.type = LightType::Directional;
        out.push_back(place(l, l.name, glm::dmat4(1.0), glCompat));
    }
    return out;
}

} // namespace lantern::frame
