// Frame.h: the device-free frame model. One function, buildFrame(), turns (scene, render
// options, time) into everything a frame is made of: the pose, the resolved lighting switches,
// each view's camera in double precision, the lights placed in that camera's eye space, the
// materials, and the draws in order with the features each needs. The GPU path (render/) packs
// it into its buffers and pipeline variants; the CPU reference (reference/) reads it directly.
// No Vulkan, no shader constant and no GPU layout appears here.
#pragma once

#include <lantern/Camera.h>
#include <lantern/Options.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace lantern::frame {

/// Where the lighting equation is evaluated: the shading rule, one shader program each.
enum class Program : std::uint32_t {
    Phong,    ///< per fragment
    Gouraud,  ///< per vertex, colours interpolated
    Flat,     ///< once per triangle, at its centroid with the face normal
    GlFlat,   ///< per vertex, the provoking (last) vertex colours the triangle (GL_FLAT)
    Floor,    ///< no lighting: constant white (FeatureMode::Floor, the cost of rasterising)
};
const char* toString(Program program) noexcept;

/// Where lit colours are clamped to [0, 1].
enum class Clamp : std::uint32_t {
    None,
    Fragment,  ///< the final colour (--clamp)
    Gl,        ///< each colour where it is computed, as GL does (--gl-compat)
};

/// The lighting switches after combining the scene's LANTERN_lighting with the options.
struct Lighting {
    LightingModel model;
    Program program = Program::Phong;
    Clamp clamp = Clamp::None;
    bool glCompat = false;
};

/// Combines the scene root's lighting model with the options' overrides.
Lighting resolveLighting(const Scene& scene, int root, const RenderOptions& options);

/// Whether back faces of `material` are lit with the reversed normal and the back material:
/// the scene's or the options' two-sided model when stated (GL's GL_LIGHT_MODEL_TWO_SIDE, for
/// every draw), else whether the material is double-sided (glTF: "back-face normals are
/// reversed").
bool twoSidedLighting(const Lighting& lighting, const Material& material) noexcept;

/// Material maps as bits (the values of LANTERN_MAP_*, checked where render/ maps them).
enum MapBit : std::uint32_t {
    kMapMetallicRoughness = 1,
    kMapNormal = 2,
    kMapOcclusion = 4,
    kMapEmissive = 8,
    kMapAll = 15,
    /// A map's bit shifted by kMapSecondSetShift: it reads Primitive::texcoords1.
    kMapSecondSetShift = 4,
    kMapSecondSets = 240,
};

/// The maps a material has (MapBit), each with its second-set bit when it reads
/// Primitive::texcoords1: a metallic-roughness map only with `pbr`.
std::uint32_t materialMaps(const Material& material) noexcept;

/// A camera resolved for one view, in double precision.
struct ViewCamera {
    glm::dmat4 viewFromWorld{1.0};
    Projection projection;
    glm::dmat4 clipFromView{1.0};  ///< Vulkan clip space for the view's aspect and depth mode
    DepthMode depth = DepthMode::ReversedZ;  ///< the depth mode clipFromView is for
    std::string description;       ///< e.g. "camera 0 \"Main\"", "automatic framing"
};

/// Resolves a CameraSpec for a view of aspect `aspect` (width / height). InvalidInput naming
/// `object` when the spec names a camera that does not exist or that no node places.
Result<ViewCamera> resolveCamera(const Scene& scene, const Pose& pose, const CameraSpec& spec,
                                 double aspect, DepthMode depth, const std::string& object);

/// World-space bounds that stay fixed over the scene's animations (sampled at the keys), so
/// that automatic framing does not follow the motion.
Bounds animationBounds(const Scene& scene, int root);

/// A light placed in a view's eye space, in double precision: everything the lighting
/// equation reads of it.
struct EyeLight {
    std::string name;  ///< the light's name, or "light N" (N: its index in Scene::lights)
    LightType type = LightType::Point;  ///< as evaluated: a GL spot with cutoff 180 is Point
    LightFalloff falloff = LightFalloff::Gl;
    glm::dvec3 position{0.0};      ///< eye space (positional lights)
    glm::dvec3 toLight{0, 0, 1};   ///< unit, towards the light (directional lights)
    glm::dvec3 spotAxis{0, 0, -1}; ///< unit, the direction the light shines
    glm::dvec3 ambient{0.0}, diffuse{1.0}, specular{1.0};
    glm::dvec3 attenuation{1, 0, 0};  ///< GL's kc, kl, kq
    double invRange = 0.0;            ///< glTF: 1 / range (0: unlimited)
    double oneMinusCosCutoff = 1.0;   ///< GL spot: 1 - cos(cutoff), as 2 sin^2(cutoff / 2)
    double exponent = 0.0;            ///< GL spot exponent (<= 128 with GL compatibility)
    double cosOuter = 0.0;            ///< glTF spot: cos(outer cone angle)
    double coneScale = 1.0;           ///< glTF spot: 1 / max(cos inner - cos outer, 1e-6)
    double coneAngle = 0.0;           ///< spot: the cone's half-angle, radians (GL cutoff, glTF outer)
    bool castShadows = false;         ///< Light::castShadows (never under GL compatibility)
};

/// The lights of a pose in the eye space of `viewFromWorld`, in node order: the one place
/// where lights are placed. With no light in the scene, GL's light 0 (a directional headlight
/// defined in eye space, so `viewFromWorld` does not move it). `glCompat` applies GL's limits.
std::vector<EyeLight> placeLights(const Scene& scene, const Pose& pose,
                                  const glm::dmat4& viewFromWorld, bool glCompat);

/// What the lights of a frame need (the same for every view).
struct LightFeatures {
    bool glDefault = false;  ///< the scene has no light: GL's light 0 is used
    std::size_t directional = 0, point = 0, spot = 0;  ///< counts, as evaluated
    bool glAttenuation = false;  ///< a positional GL light has attenuation other than (1, 0, 0)
    bool glSpot = false;         ///< a GL spot light with a cone
    bool gltfFalloff = false;    ///< a positional light with glTF's falloff
    bool specular = false;       ///< some light has a specular colour
    /// Every light's type and falloff, in the order the views list them (the pipeline unrolls
    /// up to LANTERN_MAX_UNROLLED_LIGHTS of them, each for its kind: render/Variants.cpp).
    std::vector<std::pair<LightType, LightFalloff>> kinds;
};

/// What one draw needs beyond its frame's lights: the pipeline variant is chosen from this.
struct DrawFeatures {
    bool specular = false;  ///< a specular light meets a specular (lit) material
    bool vertexColor = false;
    bool texture = false;
    bool alphaMask = false;
    bool blend = false;
    bool unlit = false;
    bool ambientFollowsDiffuse = false;
    std::uint32_t maps = 0;  ///< MapBit: the maps the draw applies (all in phong shading)
    /// Back faces lit with the reversed normal and the back material: the scene's two-sided
    /// lighting model (GL_LIGHT_MODEL_TWO_SIDE), or a double-sided material (glTF's rule).
    bool twoSided = false;
};

/// One draw: a primitive of a node's mesh seen from a view.
struct Draw {
    std::uint32_t index = 0;  ///< numbered across the frame's views (what the id AOV records)
    std::uint32_t node = 0, mesh = 0, primitive = 0;
    std::uint32_t material = 0;  ///< Frame::materials index (the default material is last)
    glm::dmat4 viewFromModel{1.0};
    glm::dmat3 normalMatrix{1.0};  ///< normalMatrix(viewFromModel)
    bool mirrored = false;  ///< det(viewFromModel) < 0: clockwise triangles face the viewer
    bool cullBack = true;   ///< false for double-sided materials
    Topology topology = Topology::Triangles;
    bool unlitForWantOfNormals = false;  ///< lines or points without normals
    bool hasColors = false, hasTexcoords = false;
    /// Drawn with the pose's deformation (skin, morph targets: deformPrimitive()). Skinned
    /// draws are in world space: viewFromModel is then the view's viewFromWorld.
    bool deformed = false;
    int texture = -1;       ///< Scene::textures index of the base colour; -1: none (white)
    DrawFeatures features;
    double sortDepth = 0.0; ///< eye-space z of the primitive's bounds centre (blended draws)
};

struct View {
    int x = 0, y = 0, width = 0, height = 0;  ///< GL convention: origin bottom-left
    ViewCamera camera;
    std::vector<EyeLight> lights;  ///< in this view's eye space
    std::vector<Draw> draws;       ///< opaque in node order, then blended far to near
};

/// One shadow map of a frame (a layer of the frame's shadow-map array): the depths a light
/// sees, in its own Vulkan clip space with reversed Z (frame/Shadows.cpp).
struct ShadowMap {
    std::size_t light = 0;          ///< index into every view's lights
    glm::dmat4 clipFromWorld{1.0};
    bool perspective = false;
    /// A texel's world size: at unit distance from the light (perspective), or anywhere.
    double texel = 0.0;
    /// Map depth to distance d from the map's eye plane: perspective, depth = depthScale / d;
    /// orthographic, depth = depthScale * d + depthOffset.
    double depthScale = 0.0, depthOffset = 0.0;
    /// Clip units a lookup keeps from the map's edge: a cascade's points nearer its edge than
    /// its filter reaches take the next cascade.
    double margin = 0.0;
    /// PCSS: the light's radius in world units (perspective), or the tangent of its angular
    /// radius (orthographic); 0 under the hard filters.
    double lightSize = 0.0;
};

/// The frame's shadow maps: none unless a light casts shadows (then the frame pays nothing).
struct Shadows {
    std::vector<ShadowMap> maps;
    std::vector<int> firstMap;  ///< per light: its first map (a point light has six), -1: none
    std::vector<int> mapCount;  ///< per light: its maps (six cube faces, or the cascades)
    ShadowOptions options;      ///< what they were planned with (the reference's light sizes)
    bool any() const { return !maps.empty(); }
};

struct Frame {
    int root = 0;
    double time = 0.0;
    Pose pose;
    Lighting lighting;
    /// The scene's materials, then GL's default material (for primitives without one), with
    /// GL's limits applied under GL compatibility (shininess in [0, 128]).
    std::vector<Material> materials;
    LightFeatures lightFeatures;
    std::vector<View> views;
    Shadows shadows;

    std::size_t drawCount() const;
    /// The draw numbered `index` and its view, or null.
    const Draw* draw(std::uint32_t index, std::size_t* view = nullptr) const;
};

/// Builds the frame. InvalidInput for a root, time, view or camera the options name wrongly;
/// the scene must have passed Scene::validate().
Result<Frame> buildFrame(const Scene& scene, const RenderOptions& options, double time);

/// The shadow maps of a frame whose views are built: for each light that casts shadows
/// (ShadowOptions::all, or Light::castShadows), fitted to the bounds of what the frame draws:
/// a directional light's orthographic box around them, a spot light's cone, a point light's
/// six cube faces along the world axes.
Shadows planShadows(const Scene& scene, const Frame& frame, const RenderOptions& options);

/// The features a frame uses, one line each (e.g. "light:point x2", "shading:phong"), for
/// --explain and `lantern info`.
std::vector<std::string> describeFeatures(const Frame& frame, const RenderOptions& options);

} // namespace lantern::frame
