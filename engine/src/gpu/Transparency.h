// Transparency.h: order-independent transparency (docs/transparency.md), for frames whose
// blended draws are composited exactly or weighted rather than sorted by object.
//
// Exact: during the scene pass every blended fragment that passes the depth test against the
// opaque surfaces is stored in its pixel's list (shaders/include/oit.glsl) in one device-local
// buffer: a header, one head word per pixel, then the nodes. After the pass one triangle over
// the target sorts each pixel's list by depth and composites it over the opaque picture
// (shaders/oit_resolve.frag). A frame that stores more fragments than the buffer holds loses
// the excess; the host reads the count back, and the next frame (render() renders the frame
// again at once) gets a buffer large enough.
//
// Weighted: after the scene pass, a pass of its own draws the blended draws into the weighted
// sums and the revealage (multisampled like the scene, resolved), against the scene's depth;
// one triangle then composites their average over the opaque picture
// (shaders/weighted_resolve.frag).
//
// A frame without blended draws (or sorting them) records nothing of this and binds 1 x 1
// stand-ins nobody reads.
#pragma once

#include "gpu/Context.h"
#include "gpu/Device.h"
#include "gpu/DrawList.h"
#include "gpu/Handles.h"
#include "gpu/Pipelines.h"
#include "gpu/Resources.h"
#include "gpu/Targets.h"

#include <memory>
#include <vector>

namespace lantern::gpu {

/// One frame slot's transparency resources.
struct TransparencySlot {
    TransparencyMethod method = TransparencyMethod::Sorted;  ///< this frame's
    Buffer lists;   ///< exact: header, heads, nodes (made on first use)
    Buffer header;  ///< exact: the lists' header, copied back after the frame (host-readable)
    std::uint32_t width = 0, height = 0, samples = 1;
    std::uint32_t capacity = 0;  ///< nodes `lists` holds
    /// Weighted: the sums and revealage, single-sampled (the composite reads them as storage
    /// images; 1 x 1 stand-ins otherwise) and, with MSAA, the multisampled ones drawn into.
    Image accum, reveal, accumMsaa, revealMsaa;
};

class TransparencyPass {
public:
    static Result<std::unique_ptr<TransparencyPass>> create(Context& ctx, Pipelines& pipelines);

    /// Sizes `slot` for the frame (its method from `target`) and makes the composite pipeline
    /// the frame needs. Refuses lists or images the device cannot hold.
    Result<void> prepare(TransparencySlot& slot, const TargetDesc& target);
    /// Points the frame set's fragment-list and weighted bindings at the slot's (the lists'
    /// binding at `standIn` when the frame has none).
    void writeDescriptors(VkDescriptorSet set, const TransparencySlot& slot,
                          VkDescriptorBufferInfo standIn) const;

    /// Before the scene pass: the lists emptied and their header written; the weighted images
    /// to their attachment layout (or the stand-ins to GENERAL).
    void begin(VkCommandBuffer cmd, const TransparencySlot& slot, bool reversedZ) const;
    /// The weighted pass's colour attachments (sums cleared to 0, revealage to 1).
    std::vector<VkRenderingAttachmentInfo> weightedAttachments(const TransparencySlot& slot) const;
    /// After the scene (and weighted) pass: the composite over the target's colour
    /// (single-sampled, COLOR_ATTACHMENT_OPTIMAL), then the lists' header copied back.
    void composite(VkCommandBuffer cmd, VkPipelineLayout layout, VkDescriptorSet frameSet,
                   const FrameSetOffsets& offsets, const TransparencySlot& slot,
                   const Target& target) const;
    /// After the slot's fence: what the lists held, into `frame`; a frame that lost fragments
    /// makes the next one's lists large enough (as far as the device allows).
    void readCounts(const TransparencySlot& slot, FrameReadback& frame);

private:
    TransparencyPass(Context& ctx, VkPipelineLayout layout) : m_ctx(ctx), m_layout(layout) {}
    Result<void> prepareLists(TransparencySlot& slot, const TargetDesc& target);
    Result<void> prepareWeighted(TransparencySlot& slot, const TargetDesc& target);
    Result<VkPipeline> compositePipeline(bool weighted);

    Context& m_ctx;
    VkPipelineLayout m_layout;
    VkShaderModule m_vertex = VK_NULL_HANDLE, m_listResolve = VK_NULL_HANDLE,
                   m_weightedResolve = VK_NULL_HANDLE;
    UniquePipeline m_listPipeline, m_weightedPipeline;
    /// Nodes the next frame's lists should hold: the most a frame asked for, with room to spare.
    std::uint64_t m_wantedNodes = 0;
    std::uint64_t m_firstNodes = 0;  ///< LANTERN_TEST_FRAGMENT_LIST_NODES: the first lists' size
};

} // namespace lantern::gpu
