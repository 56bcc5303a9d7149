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
#include <memory>
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
    /// Makes the shader modules (on this thread: Pipelines' module registry is not shared).
    static Result<std::unique_ptr<ClearDraw>> create(Context& ctx, Pipelines& pipelines);

    /// Whether a frame of `width` x `height` pixels clears faster by drawing: on a CPU device,
    /// from kMinPixels up (smaller, the clear costs less than the clear pipeline's compilation
    /// is worth), and not on a renderer's first frame: llvmpipe compiles a draw's triangle
    /// setup on its first use, outside any cache, which costs a one-frame render (a single
    /// `lantern render`) more than the drawn clear saves (docs/performance.md).
    static bool preferred(const Context& ctx, std::uint32_t width, std::uint32_t height,
                          bool firstFrame);
    static constexpr std::uint64_t kMinPixels = 1000000;

    /// Whether `target`'s pipelines are made (prepare() then only looks them up).
    bool ready(const Target& target) const;
    /// The pipelines (made on first use) that clear `target`'s passes. May run on another
    /// thread while the scene's pipelines are made: it touches only this object.
    Result<ClearFrame> prepare(const Target& target);

    /// Records the clear as the first command of a begun pass whose attachments are not loaded:
    /// the whole `width` x `height` area, every colour attachment of the pass (`clear` for the
    /// colour, the AOV background for the AOV planes). Leaves viewport, scissor, cull mode and
    /// front face set for the whole area, and the clear pipeline bound.
    static void record(VkCommandBuffer cmd, VkPipelineLayout layout, VkPipeline pipeline,
                       std::uint32_t width, std::uint32_t height, const float clear[4]);

private:
    ClearDraw(Context& ctx, VkPipelineLayout layout) : m_ctx(ctx), m_layout(layout) {}
    Result<VkPipeline> pipeline(std::uint32_t samples, std::uint32_t colorAttachments);

    Context& m_ctx;
    VkPipelineLayout m_layout;
    VkShaderModule m_vertex = VK_NULL_HANDLE, m_fragment = VK_NULL_HANDLE, m_fragmentAov = VK_NULL_HANDLE;
    std::map<std::pair<std::uint32_t, std::uint32_t>, UniquePipeline> m_cache;
};

} // namespace lantern::gpu
