// Presenter.h: the Vulkan half of a window target. A swapchain on the host's surface, one
// acquire semaphore per frame slot and one render-finished semaphore per swapchain image, and
// the overlay render pass the host records into (ImGui). A frame renders into the slot's float
// image (the very image a headless render reads back), which is blitted into the acquired
// swapchain image, then the overlay pass runs and the image is presented.
#pragma once

#include "gpu/Device.h"
#include "gpu/Swapchain.h"

#include <lantern/Image.h>
#include <lantern/RenderTypes.h>
#include <lantern/WindowTypes.h>

#include <memory>
#include <optional>

namespace lantern::gpu {

/// What present() did and measured.
struct PresentedFrame {
    FrameStatus status = FrameStatus::Presented;
    double gpuMs = -1.0;   ///< of the frame that last completed in this slot
    double waitMs = 0.0;   ///< waiting for the slot and acquiring
    double submitMs = 0.0; ///< recording and submission
    double presentMs = 0.0;
    std::size_t pipelinesCreated = 0;
    std::optional<FrameReadback> capture;  ///< with `capture`: the frame read back
};

class Presenter {
public:
    /// The instance a host creates its surface on.
    static VkInstance instance(Device& device);

    /// Checks that the device can present to `desc.surface`; builds the swapchain when the
    /// size is known. An owned surface is destroyed with the presenter (or on failure).
    static Result<std::unique_ptr<Presenter>> create(Device& device, const WindowTargetDesc& desc);
    ~Presenter();

    void resize(int width, int height);
    /// Before a frame: Minimised for a 0 x 0 window, Recreated after rebuilding a stale
    /// swapchain (nothing to render this time), nothing when a frame can be rendered.
    Result<std::optional<FrameStatus>> prepare();
    /// Renders `list` (sized to extent()) into the next acquired image and presents it.
    Result<PresentedFrame> present(const DrawList& list, const std::shared_ptr<SceneBuffers>& scene,
                                   bool capture, const OverlayRecorder& overlay);

    Result<double> waitForFrameSlot();
    Result<void> waitIdle();
    Result<void> submitOnce(const std::function<void(VkCommandBuffer)>& record);

    int width() const;
    int height() const;
    PresentMode presentMode() const;
    std::uint32_t imageCount() const;
    std::uint32_t framesInFlight() const;
    VkFormat format() const;
    const OverlayContext& overlayContext() const { return m_overlay; }

private:
    explicit Presenter(Device& device) : m_device(device) {}
    Result<void> drain();
    Result<void> makeOverlayObjects();
    Result<void> rebuild();
    void recordPresentation(VkCommandBuffer cmd, VkImage color, VkImageLayout layout,
                            std::uint32_t w, std::uint32_t h, std::uint32_t index,
                            const OverlayRecorder& recorder);

    Device& m_device;
    VkSurfaceKHR m_surface = VK_NULL_HANDLE;
    bool m_ownsSurface = false;
    std::optional<Swapchain> m_swapchain;
    int m_wantWidth = 0, m_wantHeight = 0;
    bool m_stale = true;                   ///< rebuild the swapchain before the next frame
    std::vector<UniqueSemaphore> m_acquired;  ///< per frame slot
    std::vector<UniqueSemaphore> m_rendered;  ///< per swapchain image (kept across rebuilds)
    UniqueRenderPass m_overlayPass;
    std::vector<UniqueFramebuffer> m_framebuffers;
    UniqueDescriptorPool m_overlayPool;
    OverlayContext m_overlay;
    double m_slotGpuMs = -1.0;  ///< GPU time of the frame waited for by waitForFrameSlot()
    double m_slotWaitMs = 0.0;  ///< and how long that took
};

} // namespace lantern::gpu
