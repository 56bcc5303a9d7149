// ClearDraw.h: clearing a pass's colour and AOV attachments by drawing one triangle over the
// whole render area, instead of their LOAD_OP_CLEAR, on a device where that is the faster way:
// a CPU device (lavapipe). llvmpipe fills each 64x64 tile of a cleared attachment whose
// texels are wider than 4 bytes with one memcpy call per texel (util_fill_rect), which is most
// of a 1080p RGBA32F frame; its fragment stage writes the same texels four by four.
// docs/performance.md has the measurements. The depth attachment (4 bytes a texel) keeps its
// LOAD_OP_CLEAR. The pixels are the same either way: the draw writes the clear values exactly,
// into every sample.
#pragma once

#include "gpu/Context.h"
#include "gpu/Handles.h"
#include "gpu/Targets.h"

#include <map>
#include <utility>

namespace lantern::gpu {

class Pipelines;

/// The clear pipelines of one frame's passes; null: that pass clears with LOAD_OP_CLEAR.
struct ClearFrame {
    VkPipeline scene = VK_NULL_HANDLE;  ///< the scene pass
    VkPipeline aov = VK_NULL_HANDLE;    ///< the single-sampled AOV pass (MSAA with AOVs)
};

class ClearDraw {
public:
    ClearDraw(Context& ctx, Pipelines& pipelines) : m_ctx(ctx), m_pipelines(pipelines) {}

    /// Whether the device clears faster by drawing: true on a CPU device.
    static bool preferred(const Context& ctx);

    /// The pipelines (made on first use) that clear `target`'s passes.
    Result<ClearFrame> prepare(const Target& target);

    /// Records the clear as the first command of a begun pass whose attachments are not loaded:
    /// the whole `width` x `height` area, every colour attachment of the pass (`clear` for the
    /// colour, the AOV background for the AOV planes). Leaves viewport, scissor, cull mode and
    /// front face set for the whole area, and the clear pipeline bound.
    static void record(VkCommandBuffer cmd, VkPipelineLayout layout, VkPipeline pipeline,
                       std::uint32_t width, std::uint32_t height, const float clear[4]);

private:
    Result<VkPipeline> pipeline(std::uint32_t samples, std::uint32_t colorAttachments);

    Context& m_ctx;
    Pipelines& m_pipelines;
    std::map<std::pair<std::uint32_t, std::uint32_t>, UniquePipeline> m_cache;
};

} // namespace lantern::gpu
