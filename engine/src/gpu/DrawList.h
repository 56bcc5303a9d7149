// DrawList.h: what a frame asks of the GPU, with no Vulkan in it: the render target, the
// uniform data already packed in the shaders' layouts (gpu/GpuLayouts.h), and per view the
// draws in order, each with its pipeline variant, primitive, texture and push constants.
// render/ builds it from a frame::Frame; gpu/ records it (gpu/Recorder.cpp).
#pragma once

#include "frame/Frame.h"
#include "gpu/GpuLayouts.h"

#include <lantern/Image.h>

#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace lantern::gpu {

/// Where a blended draw's colour goes (render/Variants.cpp, from RenderOptions::transparency).
enum class BlendPath : std::uint8_t {
    Over,      ///< blended over the colour attachment, in draw order (sorted transparency)
    List,      ///< stored in its pixel's fragment list, composited after the pass (exact)
    Weighted,  ///< added into the weighted sums of the weighted pass (weighted)
};

/// Everything that selects a pipeline: the program, the specialisation constants (indexed by
/// LANTERN_SC_* of lantern_shared.h) and the fixed-function state that cannot be dynamic.
struct PipelineKey {
    frame::Program program = frame::Program::Phong;
    Topology topology = Topology::Triangles;
    std::array<std::uint32_t, LANTERN_SC_COUNT> constants{};
    bool blend = false;
    BlendPath blendPath = BlendPath::Over;  ///< with blend: where the colour goes
    bool aov = false;  ///< the fragment stage also writes the AOV attachments
    bool aovSurface = false;  ///< with aov: the surface attachment (uv, range) exists
    std::uint32_t samples = 1;
    bool reversedZ = true;
    /// Set by gpu/ (never by render/): flat triangles lit once per triangle by the pre-pass
    /// (shaders/flatlight.comp) and drawn indexed, instead of the per-corner flat streams.
    bool flatPerTriangle = false;
    /// Set by gpu/: the draw's colours are checked where they are made (the guarded vertex
    /// variant, the flat pre-pass, or a constant: shaders/include/guard.glsl), so that the
    /// host need not check the picture (gpu/Readback.cpp).
    bool guard = false;
    /// Set by gpu/: the variant for weighted transparency's own pass (blendPath Weighted), whose
    /// attachments are the weighted sums and the revealage.
    bool weightedPass = false;

    bool operator==(const PipelineKey&) const = default;
};
struct PipelineKeyHash {
    std::size_t operator()(const PipelineKey& key) const noexcept;
};

/// One draw call.
struct DrawCommand {
    PipelineKey pipeline;
    std::uint32_t mesh = 0, primitive = 0;  ///< Scene::meshes[mesh].primitives[primitive]
    /// The material whose textures are bound (Scene::materials index); -1: white defaults
    int textureSet = -1;
    bool cullBack = true;
    bool frontClockwise = false;  ///< a mirroring transform: clockwise triangles are front
    DrawBlock block{};            ///< push constants
    int deform = -1;  ///< DrawList::deforms index whose output it draws; -1: its own streams
    /// With pipeline.constants[LANTERN_SC_INSTANCED]: the draw covers DrawList::instances
    /// [firstInstance, firstInstance + instanceCount), and `block` is its first instance's
    /// (whose transforms the shader ignores; its material and flags hold for all).
    std::uint32_t firstInstance = 0, instanceCount = 1;
};

/// One deformation the pre-pass computes before the draws (shaders/deform.comp): a primitive
/// as a pose skins and morphs it, read by the draws that name it.
struct DeformCommand {
    std::uint32_t mesh = 0, primitive = 0;
    bool flat = false;          ///< the flat-shading streams (per triangle corner) instead
    std::vector<Mat4> joints;   ///< world from bind space, per joint; empty: not skinned
    std::vector<float> weights; ///< morph weights, per target; empty: no morph targets
};

/// One viewport's share of the frame.
struct ViewCommands {
    int x = 0, y = 0, width = 0, height = 0;  ///< GL convention: origin bottom-left
    FrameBlock frame{};
    std::vector<LightData> lights;  ///< at least one
    std::vector<DrawCommand> draws;
};

/// The images a frame renders into and what is read back of them.
struct TargetDesc {
    std::uint32_t width = 0, height = 0;
    std::uint32_t samples = 1;
    AovSet aovs;              ///< AOV planes to read back (any: the AOV attachments exist)
    bool ids = false;         ///< with AOVs, read back the draw and primitive ids too (the probe)
    /// The draw and primitive ids are read back: the probe's, or an id plane asked for.
    bool readIds() const { return ids || aovs.anyId(); }
    bool reversedZ = true;    ///< depth clears to 0 (far) instead of 1
    /// Exact: the frame's blended draws go to fragment lists, resolved after the scene pass;
    /// Weighted: into the weighted sums, composited after their pass. Sorted whenever the
    /// frame has no blended draw, so such a frame allocates and records nothing for them.
    TransparencyMethod transparency = TransparencyMethod::Sorted;
    glm::vec4 clear{0.0f};    ///< linear, premultiplied
    float pointSize = 1.0f;   ///< pixels across a point (GL_POINTS)
    float lineWidth = 1.0f;   ///< pixels across a line (GL_LINES)
};

/// The display overlays (viewers), drawn after each view's shaded draws.
struct Overlays {
    bool wireframe = false;
    bool normals = false;
    float normalLength = 0.0f;  ///< eye units
    bool any() const { return wireframe || normals; }
};

/// The frame's shadow maps (frame/Shadows.cpp, gpu/Shadows.h): one depth-only pass per map
/// over the first view's opaque triangles, and what the lighting reads of them.
struct ShadowCommands {
    std::uint32_t resolution = 0;
    std::vector<FrameBlock> passes;   ///< per map: the block its pass draws with (the map's clip space)
    /// per map: the first view's draws its pass records (indices into views[0].draws)
    std::vector<std::vector<std::uint32_t>> passDraws;
    std::vector<ShadowData> lookups;  ///< per view, per map (ShadowBlock in shadows.glsl)
    float slopeBias = 0.0f;           ///< the passes' depth-bias slope factor (reversed Z: negative)
    bool any() const { return !passes.empty(); }
};

enum class OutputGuard { Auto, Always, Never };

struct DrawList {
    TargetDesc target;
    std::vector<MaterialData> materials;  ///< at least one
    std::vector<ViewCommands> views;
    std::vector<DeformCommand> deforms;  ///< skinned and morphing primitives (usually none)
    /// The instanced draws' per-instance transforms, every view's (render/DrawLists.cpp).
    std::vector<InstanceData> instances;
    ShadowCommands shadows;
    Overlays overlays;
    /// Which draws check their colours where they are made (shaders/include/guard.glsl):
    /// Auto weighs the vertex stage's check against the host's (gpu/FrameRing.cpp); tests
    /// force either way.
    OutputGuard outputGuard = OutputGuard::Auto;
    /// A band of a taller picture (render::renderBands): the target holds the picture's rows
    /// [bandTop, bandTop + target.height), and every view keeps its place in the picture.
    /// pictureHeight 0: the target is the whole picture.
    std::uint32_t bandTop = 0, pictureHeight = 0;
    /// The clusters of large meshes are culled by the pre-pass (gpu/Clusters.h), which draws
    /// whole the frames that read the primitive ids (each indirect draw counts its own from 0).
    bool clusterCulling = false;
    float lodError = 0.0f;  ///< the level-of-detail bound in pixels (0: full detail)

    /// Draw calls (an instanced draw counts once).
    std::size_t drawCount() const {
        std::size_t n = 0;
        for (const ViewCommands& v : views) n += v.draws.size();
        return n;
    }
};

} // namespace lantern::gpu
