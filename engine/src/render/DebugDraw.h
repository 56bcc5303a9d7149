// DebugDraw.h: the display overlays a viewer draws over the shaded scene, in the same render
// pass: the wireframe (each drawn triangle's edges) and the vertex normals (one line per vertex).
// They share the scene pipelines' layout, frame block and push constants (debug.vert).
#pragma once

#include "gpu/Context.h"
#include "gpu/Handles.h"
#include "render/FramePlan.h"
#include "render/GpuScene.h"

#include <lantern/Renderer.h>

#include <map>
#include <tuple>

namespace lantern::render {

/// The overlays of one frame: the pipelines to use (null: not drawn) and their parameters.
struct DebugFrame {
    VkPipeline wireframe = VK_NULL_HANDLE;
    VkPipeline normals = VK_NULL_HANDLE;
    float normalLength = 0.0f;  ///< eye units
    float depthBias = 0.0f;     ///< toward the eye: positive with reversed Z, negative without
    bool any() const { return wireframe != VK_NULL_HANDLE || normals != VK_NULL_HANDLE; }
};

class DebugDraw {
public:
    DebugDraw(gpu::Context& ctx, VkPipelineLayout layout) : m_ctx(ctx), m_layout(layout) {}

    /// Refuses what the overlays cannot do (with AOVs; wireframe without fillModeNonSolid).
    static Result<void> checkOptions(const gpu::Context& ctx, const RenderOptions& options);

    /// The pipelines (created on first use) and the normal length for this frame.
    Result<DebugFrame> prepare(const RenderOptions& options, const GpuScene& scene,
                               const FramePlan& plan);

    /// Records the overlays of one view; the view's viewport and scissor are set. Binds the
    /// frame set with the view's dynamic offsets itself (a view may have no draws).
    void recordView(VkCommandBuffer cmd, const GpuScene& scene, const ViewPlan& view,
                    VkDescriptorSet frameSet, const std::uint32_t dynamicOffsets[2],
                    const DebugFrame& frame) const;

private:
    Result<VkShaderModule> shader(std::uint32_t id);
    Result<VkPipeline> pipeline(bool normals, std::uint32_t samples, bool reversedZ);

    gpu::Context& m_ctx;
    VkPipelineLayout m_layout;
    std::map<std::uint32_t, gpu::UniqueShaderModule> m_shaders;
    std::map<std::tuple<bool, std::uint32_t, bool>, gpu::UniquePipeline> m_pipelines;
};

} // namespace lantern::render
