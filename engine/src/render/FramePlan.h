// FramePlan.h: everything one frame needs, computed on the CPU from (scene, options, time):
// resolved lighting options, cameras per view, lights and materials packed for the GPU in eye
// space, the features the scene uses, and the sorted draw list with each draw's pipeline
// variant. No Vulkan here: the plan is testable without a device and is what --explain and
// --probe describe.
#pragma once

#include "render/GpuLayouts.h"

#include <lantern/Renderer.h>
#include <lantern/Scene.h>

#include <glm/mat4x4.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lantern::render {

/// The shader programs (vertex + fragment entry points).
enum class Program : std::uint32_t {
    Phong,    ///< mesh.vert + phong.frag: per fragment
    Gouraud,  ///< pervertex.vert + pervertex.frag: per vertex
    Flat,     ///< pervertex.vert(FLAT_CENTROID) + pervertex.frag(FLAT): per triangle centroid
    GlFlat,   ///< pervertex.vert(FLAT_PROVOKING) + pervertex.frag(FLAT): GL's provoking vertex
    Floor,    ///< mesh.vert + floor.frag: constant colour, no lighting (FeatureMode::Floor)
};
const char* toString(Program program) noexcept;

/// The lighting switches after combining the scene's LANTERN_lighting with RenderOptions.
struct ResolvedLighting {
    LightingModel model;
    Program program = Program::Phong;
    std::uint32_t clamp = LANTERN_CLAMP_NONE;
    bool glCompat = false;
};
ResolvedLighting resolveLighting(const Scene& scene, int root, const RenderOptions& options);

/// Everything that selects a pipeline: the program, the specialisation constants and the
/// fixed-function state that cannot be dynamic.
struct VariantKey {
    Program program = Program::Phong;
    std::array<std::uint32_t, LANTERN_SC_COUNT> constants{};
    bool blend = false;
    bool aov = false;
    std::uint32_t samples = 1;
    bool reversedZ = true;

    bool operator==(const VariantKey&) const = default;
    std::string describe() const;  ///< one line, e.g. "phong lights=dir specular=blinn ..."
};
struct VariantKeyHash {
    std::size_t operator()(const VariantKey& k) const noexcept;
};

/// A camera resolved for one view, in double precision.
struct ResolvedCamera {
    glm::dmat4 viewFromWorld{1.0};
    Projection projection;
    glm::dmat4 clipFromView{1.0};  ///< Vulkan clip space for this view's aspect and depth mode
    std::string description;       ///< e.g. "camera 0 \"Main\"", "automatic framing"
};

/// Resolves a CameraSpec for a view of the given aspect. InvalidInput when the spec names a
/// camera that does not exist or is not placed by any node.
Result<ResolvedCamera> resolveCamera(const Scene& scene, const Pose& pose,
                                     const CameraSpec& spec, double aspect, DepthMode depth,
                                     const std::string& object);

/// One draw call.
struct DrawItem {
    std::uint32_t mesh = 0, primitive = 0;  ///< Scene::meshes[mesh].primitives[primitive]
    std::uint32_t node = 0;
    DrawBlock block{};                      ///< push constants (draw index filled in)
    VariantKey key;
    bool cullBack = true;
    bool mirrored = false;     ///< det(viewFromModel) < 0: front faces flip
    bool hasColors = false, hasTexcoords = false;
    int texture = -1;          ///< Scene::textures index, -1: the white default
    float sortDepth = 0.0f;    ///< eye-space z of the primitive's bounds centre
    glm::dmat4 viewFromModel{1.0};  ///< double precision, for --probe
};

struct ViewPlan {
    int x = 0, y = 0, width = 0, height = 0;  ///< GL convention: origin bottom-left
    ResolvedCamera camera;
    FrameBlock frame{};
    std::vector<LightData> lights;  ///< eye space of this view's camera
    std::vector<DrawItem> draws;    ///< opaque first (grouped by variant), then blended far to near
};

struct FramePlan {
    ResolvedLighting lighting;
    std::vector<MaterialData> materials;  ///< scene materials, then the default material last
    std::vector<ViewPlan> views;
    std::vector<std::string> features;    ///< what the scene uses, for --explain
    Pose pose;
};

/// Builds the plan. Validates options (sizes, sample counts are checked by the renderer).
Result<FramePlan> buildFramePlan(const Scene& scene, const RenderOptions& options, double time);

/// The GPU packing of one light given its world transform and the view's viewFromWorld.
LightData packLight(const Light& light, const glm::dmat4& viewFromLight, bool glCompat);
/// The GPU packing of a material (GL-compat limits shininess to [0, 128]).
MaterialData packMaterial(const Material& material, bool glCompat);

/// World-space bounds that stay fixed over the scene's animations (sampled at the keys), so
/// automatic framing does not follow the animation.
Bounds animationBounds(const Scene& scene, int root);

} // namespace lantern::render
