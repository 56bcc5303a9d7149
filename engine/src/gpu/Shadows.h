// Shadows.h: the shadow maps of a frame (planned by frame/Shadows.cpp, packed by
// render/DrawLists.cpp). Before the scene pass (after any deformation, before the flat
// lighting pass, which reads them), one depth-only pass per map draws the first view's opaque
// triangles into a layer of the slot's D32 array, with reversed Z and a slope-scaled depth
// bias, through shaders/shadow.vert; the layers are then sampled with a comparison sampler
// (shaders/include/shadows.glsl). A frame without shadows binds a 1 x 1 layer nobody reads.
#pragma once

#include "gpu/Context.h"
#include "gpu/DrawList.h"
#include "gpu/Handles.h"
#include "gpu/Pipelines.h"
#include "gpu/Resources.h"

#include <memory>
#include <vector>

namespace lantern::gpu {

/// One frame slot's shadow maps.
struct ShadowSlot {
    Image image;  ///< D32, one layer per map (one when none), sampled through a 2D-array view
    std::vector<UniqueImageView> layerViews;  ///< one 2D view per layer: the passes' attachments
    std::uint32_t resolution = 0, layers = 0;
    bool rendering = false;  ///< this frame renders maps (else the image only waits to be bound)
};

class ShadowPass {
public:
    static Result<std::unique_ptr<ShadowPass>> create(Context& ctx, Pipelines& pipelines);

    /// Sizes `slot` for the list's maps (a 1 x 1 layer when it has none) and makes the
    /// pipelines it needs.
    Result<void> prepare(ShadowSlot& slot, const DrawList& list);
    VkSampler sampler() const { return m_sampler.get(); }
    /// Nearest, without comparison: the depths themselves (PCSS's blocker search).
    VkSampler depthSampler() const { return m_depthSampler.get(); }
    /// Points the frame set's map bindings at the slot's image: through the comparison sampler
    /// (LANTERN_BINDING_SHADOW_MAP) and as depths (LANTERN_BINDING_SHADOW_DEPTH, PCSS).
    void writeDescriptors(VkDescriptorSet set, const ShadowSlot& slot) const;
    /// The depth-only pipeline for plain or instanced draws (made by prepare()).
    VkPipeline pipeline(bool instanced) const { return m_pipelines[instanced ? 1 : 0].get(); }

    /// Every layer of the slot's image from whatever it held to `to`.
    static void transition(VkCommandBuffer cmd, const ShadowSlot& slot, VkImageLayout from,
                           VkImageLayout to);

private:
    ShadowPass(Context& ctx, Pipelines& pipelines) : m_ctx(ctx), m_programs(pipelines) {}
    Result<void> makePipelines();

    Context& m_ctx;
    Pipelines& m_programs;
    UniqueSampler m_sampler, m_depthSampler;
    UniquePipeline m_pipelines[2];
};

} // namespace lantern::gpu
