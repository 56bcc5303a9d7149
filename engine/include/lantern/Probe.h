// Probe.h: what Renderer::probe() reports for one pixel: the lighting equation made visible,
// each term evaluated in double precision by the CPU reference at the surface point the
// renderer drew at that pixel's centre, under the same shading rule as the render.
#pragma once

#include <lantern/Scene.h>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lantern {

/// One light's share of a probed colour (see ProbeReport). Linear RGB.
struct ProbeLight {
    std::string name;  ///< the light's name, or "light N" (N: its index in Scene::lights)
    LightType type = LightType::Directional;  ///< as drawn: a GL spot with cutoff 180 is Point
    double attenuation = 1.0;  ///< att_i
    double spot = 1.0;         ///< spot_i
    double nDotL = 0.0;        ///< n.l_i (the highlight needs it > 0)
    double specularTerm = 0.0; ///< spec_i: the Blinn or Phong lobe (0 on the dark side)
    glm::dvec3 ambient{0.0};   ///< att spot a_m a_i
    glm::dvec3 diffuse{0.0};   ///< att spot max(n.l, 0) d_m d_i
    glm::dvec3 specular{0.0};  ///< att spot f_i spec_i s_m s_i (after the shadow)
    /// Shadows (docs/shadows.md): whether the light casts them in this frame; if so the share
    /// of it the reference's exact shadow ray from the point lets through (1 lit, 0 in the
    /// shadow; diffuse and specular above include it), and the node whose opaque triangle
    /// the ray meets first.
    bool castsShadows = false;
    double visibility = 1.0;
    int occluderNode = -1;     ///< Scene::nodes index; -1: nothing between the point and the light
    std::string occluderName;
};

/// One evaluation of the lighting equation that a probed pixel's colour is made of: at the
/// surface point (phong shading), at the triangle's centroid with its face normal (flat), at
/// a vertex (gouraud: three, weighted by the pixel's perspective-correct barycentrics; GL
/// flat: the provoking vertex).
struct ProbeEvaluation {
    std::string where;      ///< "surface point", "triangle centroid", "vertex 17", ...
    double weight = 1.0;    ///< its share of the pixel's colour
    glm::dvec3 position{0.0};  ///< eye space, where the equation was evaluated
    glm::dvec3 normal{0.0};    ///< eye space, unit (zero: no direction) as lit (back side negated)
    glm::dvec3 ambientM{0.0}, diffuseM{0.0};  ///< a_m and d_m after COLOR_0
    glm::dvec3 emission{0.0};       ///< e_m
    glm::dvec3 globalAmbient{0.0};  ///< a_m * A_global
    std::vector<ProbeLight> lights;  ///< in the renderer's order
    glm::dvec3 colour{0.0};  ///< the equation's result here (per-vertex clamp with --gl-compat)
    double alpha = 1.0;
};

/// What Renderer::probe() reports for one pixel: the lighting equation made visible,
/// evaluated in double precision by the CPU reference at the surface point the renderer drew
/// at that pixel's centre, under the same shading rule as the render.
struct ProbeReport {
    int x = 0, y = 0;  ///< the pixel: x from the left, y from the top row (as image viewers)
    bool hit = false;  ///< false: no surface covers the pixel (everything below is empty)
    int view = 0;      ///< RenderOptions::views index (0 without views)
    int node = -1, mesh = -1, primitive = -1;
    Topology topology = Topology::Triangles;  ///< what the primitive draws
    std::uint32_t triangle = 0;      ///< index of the triangle (line, point) in the primitive
    std::uint32_t vertices[3] = {};  ///< its vertex indices (a line's and a point's last repeats)
    glm::dvec3 barycentric{0.0};     ///< perspective-correct weights of the vertices at the centre
    std::string nodeName;
    glm::dvec3 position{0.0};  ///< eye space: the pixel centre's ray meets the triangle here
    glm::dvec3 normal{0.0};    ///< eye space, unit: the shading normal there (interpolated and
                               ///< renormalised; the face normal with flat shading), front side
    bool backFacing = false;   ///< the renderer saw the back of the triangle
    bool backMaterial = false; ///< two-sided lighting: the back material and -normal were used
    int material = -1;         ///< Scene::materials index; -1: the default material
    std::string materialName;
    MaterialSide materialSide; ///< the side used, after GL-compat limits
    bool unlit = false;
    bool textured = false;  ///< textures (base colour, maps) modulate the pixel; the probe does not
                            ///< sample them (colour is the material without its textures)
    ShadingMode shading = ShadingMode::Phong;
    SpecularModel specular = SpecularModel::Blinn;
    bool specularPresent = false;  ///< the pipeline variant has a specular term
    bool localViewer = false, twoSided = false, glCompat = false;
    bool clamped = false;          ///< --clamp or --gl-compat clamp to [0, 1]
    std::vector<ProbeEvaluation> evaluations;  ///< their weighted sum is `colour`
    double materialAlpha = 1.0;  ///< the material's alpha there (what alpha-mask compares)
    glm::dvec4 colour{0.0};  ///< the reference's linear RGB and alpha for the surface
    glm::dvec4 pixel{0.0};   ///< what the renderer wrote at the pixel (after blending)
};

} // namespace lantern
