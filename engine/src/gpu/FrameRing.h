// FrameRing.h: the ring of frame slots. Each slot owns its command buffer, fence, uniform
// arena (materials, then per view a FrameBlock and its lights, the instances), descriptor set, timestamp
// queries, render targets and readback buffers, so frame i+1 records and renders while frame
// i is still being read back. submit() records a DrawList into the next slot
// (gpu/Recorder.cpp) and submits it; collect() waits for a slot and reads it back
// (gpu/Readback.cpp).
#pragma once

#include "gpu/ClearDraw.h"
#include "gpu/Clusters.h"
#include "gpu/Context.h"
#include "gpu/Deform.h"
#include "gpu/Device.h"
#include "gpu/DrawList.h"
#include "gpu/FlatLight.h"
#include "gpu/Overlays.h"
#include "gpu/Pipelines.h"
#include "gpu/SceneBuffers.h"
#include "gpu/Shadows.h"
#include "gpu/Targets.h"
#include "gpu/Transparency.h"

#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace lantern::gpu {

/// What a window frame adds to a submission (gpu/Presenter.cpp): recording after the scene,
/// semaphores, and whether the picture is read back.
struct SubmitHooks {
    bool readback = true;  ///< copy the colour (and AOV) images into the readback buffers
    /// Records after the scene, with the colour image in `layout` (TRANSFER_SRC_OPTIMAL, or
    /// GENERAL when it is read in place), made available to the transfer stage (blits included).
    std::function<void(VkCommandBuffer, VkImage color, VkImageLayout layout, std::uint32_t width,
                       std::uint32_t height)>
        afterRender;
    VkSemaphore wait = VK_NULL_HANDLE;  ///< waited for at the transfer stage
    VkSemaphore signal = VK_NULL_HANDLE;
};

/// One frame's pipelines, one per draw in list order: the scene pass's (null: the draw writes
/// nothing there), the single-sampled AOV pass's (MSAA with AOVs) and the weighted
/// transparency pass's (null for the draws it does not draw; empty without that pass).
struct FramePipelines {
    std::vector<VkPipeline> main, aov, weighted;
};

class FrameRing {
public:
    static Result<std::unique_ptr<FrameRing>> create(Context& ctx, Pipelines& pipelines,
                                                     std::uint32_t slots);
    ~FrameRing();
    FrameRing(const FrameRing&) = delete;
    FrameRing& operator=(const FrameRing&) = delete;

    Result<std::uint32_t> submit(const DrawList& list, const std::shared_ptr<SceneBuffers>& scene,
                                 const SubmitHooks& hooks = {});
    Result<FrameReadback> collect(std::uint32_t slot, lantern::Image storage = {},
                                  bool inPlace = false);
    bool busy(std::uint32_t slot) const { return m_slots[slot].busy; }
    std::uint32_t nextSlot() const { return m_next; }
    std::uint32_t slotCount() const { return std::uint32_t(m_slots.size()); }

    /// One slot of the ring (public for the recorder and readback, which are free functions).
    struct Slot {
        UniqueCommandPool pool;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        UniqueFence fence;
        Buffer arena;
        UniqueDescriptorPool descriptorPool;
        VkDescriptorSet frameSet = VK_NULL_HANDLE;
        VkQueryPool queries = VK_NULL_HANDLE;
        Target target;
        TargetDesc desc;                      ///< what the slot's frame asked for
        std::shared_ptr<SceneBuffers> scene;  ///< keeps geometry alive while the GPU uses it
        bool busy = false;
        bool readback = true;
        std::size_t draws = 0;
        OverlayFrame overlays;  ///< this frame's display overlays
        ClearFrame clear;       ///< the passes that clear by drawing (gpu/ClearDraw.h)
        DeformSlot deform;      ///< skinned and morphing streams (frames with deforms only)
        bool deforming = false; ///< this frame records the deformation pre-pass
        FlatSlot flat;          ///< flat triangles lit once per triangle (gpu/FlatLight.h)
        CullSlot cull;          ///< the clusters' culling pass (gpu/Clusters.h)
        ShadowSlot shadow;      ///< the shadow maps (a 1 x 1 layer when the frame has none)
        TransparencySlot transparency;  ///< fragment lists or weighted sums (gpu/Transparency.h)
        /// Every colour this frame writes comes from a guarded fragment variant or the clear
        /// colour (within LANTERN_GUARD_BOUND): unless the guard word at `guardOffset` of the
        /// arena is set, the host skips its NaN/Inf check of the picture (gpu/Readback.cpp).
        bool guarded = false;
        VkDeviceSize guardOffset = 0;
    };

    /// Where each view's FrameBlock and lights sit in a slot's arena.
    struct ArenaLayout {
        std::vector<VkDeviceSize> frameOffsets, lightOffsets;
        VkDeviceSize materialBytes = 0, lightRange = 0, guardOffset = 0, size = 0;
        VkDeviceSize instanceOffset = 0, instanceBytes = 0;
        std::vector<VkDeviceSize> shadowFrameOffsets;  ///< per map: its pass's FrameBlock
        VkDeviceSize shadowOffset = 0, shadowBytes = 0;  ///< the lookups (ShadowBlock)
    };

private:
    FrameRing(Context& ctx, Pipelines& pipelines) : m_ctx(ctx), m_pipelines(pipelines) {}
    Result<void> createSlot(Slot& slot, std::size_t index);
    Result<void> preparePipelines(const DrawList& list, SceneBuffers& scene, bool flatPerTriangle,
                                  FramePipelines& out, bool& guarded);
    Result<void> preparePrePasses(Slot& slot, const DrawList& list, const SceneBuffers& scene,
                                  bool flatPerTriangle);
    Result<ArenaLayout> fillArena(Slot& slot, const DrawList& list);
    void writeFrameSet(Slot& slot, const ArenaLayout& arena);
    Result<void> queueSubmit(Slot& slot, const SubmitHooks& hooks);

    Context& m_ctx;
    Pipelines& m_pipelines;
    std::unique_ptr<OverlayPipelines> m_overlays;  ///< made on first use
    std::unique_ptr<Deformer> m_deformer;          ///< made on first use
    std::unique_ptr<FlatLighter> m_flatLighter;    ///< made on first use
    std::unique_ptr<Culler> m_culler;              ///< made on first use
    std::unique_ptr<ClearDraw> m_clearDraw;        ///< made on first use
    std::unique_ptr<ShadowPass> m_shadowPass;      ///< made on first use
    std::unique_ptr<TransparencyPass> m_transparency;  ///< made on first use
    std::vector<Slot> m_slots;
    std::uint32_t m_next = 0;
    bool m_timestamps = false;
    bool m_inPlace = true;  ///< false: every plane staged (LANTERN_TEST_READBACK=staged)
    /// Passes clear by drawing where ClearDraw::preferred says so; LANTERN_TEST_CLEAR=draw or
    /// load (tests) sets it for every frame.
    std::optional<bool> m_clearByDraw;
    bool m_submittedOnce = false;  ///< a frame was submitted (the first clears its attachments)
    /// Shared with the views collected in place since the last submit (HostView::live); set
    /// false and replaced by the next submit and by the destructor.
    std::shared_ptr<std::atomic<bool>> m_viewsLive = std::make_shared<std::atomic<bool>>(true);
    void retireViews();
};

/// Records a frame into `slot.cmd` (begun): the deformation pre-pass (when the slot deforms),
/// the shadow maps (when it has them), the per-triangle flat lighting (when it has flat
/// triangle draws), barriers, the render pass(es) with every view's draws and overlays, the
/// transparency pass and composite (exact or weighted), the copies into the readback buffers,
/// then `hooks.afterRender`.
struct FramePasses {
    const OverlayPipelines* overlays = nullptr;
    const Deformer* deformer = nullptr;
    const FlatLighter* flatLighter = nullptr;
    const ShadowPass* shadows = nullptr;
    const TransparencyPass* transparency = nullptr;
    const Culler* culler = nullptr;
};
void recordFrame(VkPipelineLayout layout, const FramePasses& passes, FrameRing::Slot& slot,
                 const SceneBuffers& scene, const DrawList& list,
                 const FrameRing::ArenaLayout& arena, const FramePipelines& pipelines,
                 const SubmitHooks& hooks);

/// Converts a finished slot's readback buffers into a FrameReadback (every NaN or Inf counted
/// and replaced, so none leaves the renderer), reusing `storage`'s memory for the planes. With
/// `view` set (collect in place) the colour is only checked where it lies and `view` tells
/// where (its `live` is the caller's); no plane is copied.
Result<FrameReadback> readBack(Context& ctx, const FrameRing::Slot& slot, lantern::Image storage,
                               const HostView* view = nullptr);

} // namespace lantern::gpu
