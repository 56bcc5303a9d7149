// Overlays.h: the display overlays a viewer draws over the shaded scene, in the same render
// pass: the wireframe (each drawn triangle's edges) and the vertex normals (one line per
// vertex). They share the scene pipelines' layout, frame set and push constants (debug.vert).
#pragma once

#include "gpu/Context.h"
#include "gpu/DrawList.h"
#include "gpu/Handles.h"
#include "gpu/SceneBuffers.h"

#include <map>
#include <tuple>

namespace lantern::gpu {

class Pipelines;

/// The overlays of one frame: the pipelines to use (null: not drawn) and their parameters.
struct OverlayFrame {
    VkPipeline wireframe = VK_NULL_HANDLE;
    VkPipeline normals = VK_NULL_HANDLE;
    float normalLength = 0.0f;  ///< eye units
    float depthBias = 0.0f;     ///< toward the eye: positive with reversed Z, negative without
    bool any() const { return wireframe != VK_NULL_HANDLE || normals != VK_NULL_HANDLE; }
};

class OverlayPipelines {
public:
    OverlayPipelines(Context& ctx, Pipelines& pipelines) : m_ctx(ctx), m_pipelines(pipelines) {}

    /// Refuses what the overlays cannot do (with AOVs; wireframe without fillModeNonSolid).
    static Result<void> check(const Context& ctx, const Overlays& overlays, const AovSet& aovs);

    /// The pipelines (created on first use) for this frame's overlays.
    Result<OverlayFrame> prepare(const Overlays& overlays, const TargetDesc& target);

    /// Records the overlays of one view; the view's viewport and scissor are set. Binds the
    /// frame set with the view's dynamic offsets itself (a view may have no draws).
    void recordView(VkCommandBuffer cmd, const SceneBuffers& scene, const ViewCommands& view,
                    VkDescriptorSet frameSet, const FrameSetOffsets& dynamicOffsets,
                    const OverlayFrame& frame) const;

private:
    Result<VkPipeline> pipeline(bool normals, std::uint32_t samples, bool reversedZ);

    Context& m_ctx;
    Pipelines& m_pipelines;
    std::map<std::tuple<bool, std::uint32_t, bool>, UniquePipeline> m_cache;
};

} // namespace lantern::gpu
