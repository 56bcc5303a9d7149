// WindowTypes.h: the types a window target's swapchain is described and drawn with (the
// host's surface, the present mode, the overlay's handles). The target itself is
// lantern/Window.h. Like it, this includes vulkan.h: the host owns the surface, and an overlay
// records its own Vulkan commands.
#pragma once

#include <lantern/Export.h>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

namespace lantern {

/// How frames reach the screen.
enum class PresentMode {
    Fifo,       ///< vsync, never tears; always available (the default)
    Mailbox,    ///< vsync, the newest frame replaces a waiting one (falls back to Fifo)
    Immediate,  ///< no vsync, may tear (falls back to Mailbox, then Fifo)
};
LANTERN_API const char* toString(PresentMode mode) noexcept;  ///< "fifo", "mailbox", "immediate"
LANTERN_API std::optional<PresentMode> parsePresentMode(std::string_view text) noexcept;

struct WindowTargetDesc {
    /// Created by the host on windowInstance(renderer); must outlive the target unless
    /// `ownsSurface`, in which case the target destroys it after its swapchain (and create()
    /// destroys it when it fails).
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    bool ownsSurface = false;
    /// The framebuffer's size in pixels now (0 x 0 while minimised); see resize().
    int width = 0, height = 0;
    PresentMode presentMode = PresentMode::Fifo;
    /// Prepare the overlay render pass (overlayContext()) that render()'s recorder draws in.
    bool overlay = false;
};

/// What a frame call did. None of these is an error.
enum class FrameStatus {
    Presented,  ///< rendered and queued for presentation
    Minimised,  ///< the framebuffer is 0 x 0: nothing rendered; wait for window events
    Recreated,  ///< the swapchain was out of date (a resize) and was rebuilt; nothing rendered:
                ///< build the options for the new width() x height() and call again
};

/// The handles an overlay renderer (ImGui's Vulkan backend) needs. The render pass has one
/// colour attachment in the swapchain's format (loaded, stored, presented) and one subpass;
/// the descriptor pool (combined image samplers, FREE_DESCRIPTOR_SET) is the overlay's own.
/// They stay valid for the target's lifetime, across swapchain rebuilds.
struct OverlayContext {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;  ///< submissions must go through submitOnce()
    VkPipelineCache pipelineCache = VK_NULL_HANDLE;
    VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
    VkRenderPass renderPass = VK_NULL_HANDLE;
    /// Per-frame resources must cover this many frames (the frames in flight, at least 2):
    /// a resource used by frame k is free again when frame k + imageCount is recorded.
    std::uint32_t imageCount = 2;
};

/// Records the host's overlay into the overlay render pass (already begun, viewport not set).
using OverlayRecorder = std::function<void(VkCommandBuffer commandBuffer)>;

} // namespace lantern
