// Engine.h: the Vulkan half of rendering a FramePlan: pipeline variants (created on first use,
// cached), offscreen targets, and a ring of frame slots. Each slot owns its command buffer,
// fence, uniform arena, descriptor set, colour/depth/AOV images and readback buffers, so frame
// i+1 records and renders while frame i is still being read back (the headless double buffer).
#pragma once

#include "gpu/Context.h"
#include "gpu/Pipeline.h"
#include "gpu/Resources.h"
#include "render/DebugDraw.h"
#include "render/FramePlan.h"
#include "render/GpuScene.h"

#include <lantern/Renderer.h>

#include <array>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

namespace lantern::render {

/// Timing and health of one frame.
struct FrameResult {
    Image image;
    double gpuMs = -1.0;            ///< render pass time from GPU timestamps (-1: unavailable)
    std::uint64_t nonFinite = 0;    ///< NaN/Inf values found (and zeroed) at readback
    std::size_t draws = 0;
    /// With AOVs: per pixel (draw index + 1, primitive id); draw indices run over the whole
    /// frame (every view); 0 = none.
    std::vector<std::uint32_t> ids;
};

/// What a window frame adds to a submission (render/WindowFrames.cpp): recording after the
/// scene, semaphores, and whether the picture is read back.
struct SubmitHooks {
    bool readback = true;  ///< copy the colour image into the slot's readback buffer
    /// Records after the scene, with the colour image in TRANSFER_SRC_OPTIMAL, made available
    /// to the transfer stage (blits included).
    std::function<void(VkCommandBuffer, VkImage color, std::uint32_t width, std::uint32_t height)>
        afterRender;
    VkSemaphore wait = VK_NULL_HANDLE;  ///< waited for at the transfer stage
    VkSemaphore signal = VK_NULL_HANDLE;
};

class Engine {
public:
    static Result<std::unique_ptr<Engine>> create(std::shared_ptr<gpu::Context> ctx,
                                                  std::uint32_t framesInFlight);
    ~Engine();

    gpu::Context& context() { return *m_ctx; }
    const std::shared_ptr<gpu::Context>& sharedContext() const { return m_ctx; }
    VkDescriptorSetLayout textureLayout() const { return m_textureLayout.get(); }
    std::uint32_t slotCount() const { return std::uint32_t(m_slots.size()); }

    /// Checks size, sample count and memory before anything is allocated.
    Result<void> checkOptions(const RenderOptions& options) const;

    /// Records and submits a frame into the next slot (waiting for that slot's previous frame
    /// to be collected first is the caller's job: collect() every submitted slot in order).
    /// Returns the slot index.
    Result<std::uint32_t> submit(const std::shared_ptr<GpuScene>& scene, const FramePlan& plan,
                                 const RenderOptions& options, const SubmitHooks& hooks = {});
    /// Waits for the frame in `slot` and reads it back (the image stays empty when it was
    /// submitted without readback).
    Result<FrameResult> collect(std::uint32_t slot, const RenderOptions& options);
    /// True when `slot` holds a submitted frame not collected yet.
    bool busy(std::uint32_t slot) const { return m_slots[slot].busy; }
    /// The slot the next submit() uses.
    std::uint32_t nextSlot() const { return m_next; }

    /// Creates (or finds) the pipeline for a variant.
    Result<VkPipeline> pipeline(const VariantKey& key);
    std::size_t pipelineCount() const { return m_pipelines.size(); }

private:
    struct Target {
        std::uint32_t width = 0, height = 0, samples = 0;
        bool aov = false;
        gpu::Image color, colorMsaa, depth, normalDepth, ids;
        gpu::Image aovColor, aovDepth;  ///< the single-sampled AOV pass, with MSAA
        gpu::Buffer readColor, readNormalDepth, readIds;
    };
    struct Slot {
        gpu::UniqueCommandPool pool;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        gpu::UniqueFence fence;
        gpu::Buffer arena;
        gpu::UniqueDescriptorPool descriptorPool;
        VkDescriptorSet frameSet = VK_NULL_HANDLE;
        VkQueryPool queries = VK_NULL_HANDLE;
        Target target;
        std::shared_ptr<GpuScene> scene;  ///< keeps geometry alive while the GPU uses it
        bool busy = false;
        bool readback = true;
        std::size_t draws = 0;
        DebugFrame debug;  ///< this frame's display overlays
        float clearColor[4] = {0, 0, 0, 0};
        float clearDepth = 0.0f;
    };

    Engine() = default;
    Result<void> ensureTarget(Slot& slot, const RenderOptions& options);
    Result<VkShaderModule> shader(std::uint32_t id);
    void record(Slot& slot, GpuScene& scene, const FramePlan& plan,
                const std::vector<VkDeviceSize>& frameOffsets,
                const std::vector<VkDeviceSize>& lightOffsets,
                const std::vector<VkPipeline>& pipelines, const std::vector<VkPipeline>& aovPipelines,
                const SubmitHooks& hooks);

    std::shared_ptr<gpu::Context> m_ctx;
    gpu::UniqueDescriptorSetLayout m_frameLayout, m_textureLayout;
    gpu::UniquePipelineLayout m_pipelineLayout;
    std::vector<gpu::UniqueShaderModule> m_shaders;
    std::unordered_map<VariantKey, gpu::UniquePipeline, VariantKeyHash> m_pipelines;
    std::vector<Slot> m_slots;
    std::uint32_t m_next = 0;
    bool m_timestamps = false;
    std::unique_ptr<DebugDraw> m_debug;  ///< wireframe and normals overlays, made on first use
};

} // namespace lantern::render
