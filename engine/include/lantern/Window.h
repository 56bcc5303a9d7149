// Window.h: presenting Lantern's pictures in a window the host owns, through a Vulkan
// swapchain on the host's VkSurfaceKHR, with room for the host's own overlay drawing (ImGui).
//
// It includes vulkan.h (as lantern/ExternalDevice.h does, and glfw/GlfwWindow.h through it):
// the host owns the surface, and an overlay records its own Vulkan commands, so the handles it
// needs cross this API on purpose. Nothing else in Lantern's public API exposes a Vulkan type.
// lantern/glfw/GlfwWindow.h wraps all of this for GLFW in a few lines.
//
// A frame: the scene is rendered into the frame slot's linear RGBA32F image (the very image a
// headless render reads back, so a capture is exactly the picture shown), which is blitted
// into the swapchain image (sRGB-encoded by the blit when the surface format is sRGB); then
// the overlay render pass runs, where the host records its drawing; then the image is
// presented. Frames in flight are the Renderer's frame slots (RendererDesc::framesInFlight),
// each with its own acquire semaphore; each swapchain image has its own render-finished
// semaphore.
#pragma once

#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Renderer.h>
#include <lantern/Result.h>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
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

/// What render() should do besides presenting.
struct FrameRequest {
    bool capture = false;  ///< also read the picture back (WindowFrame::capture); stalls once
};

struct WindowFrame {
    FrameStatus status = FrameStatus::Presented;
    /// Timings: cpuMs for this frame's planning, recording and submission; waitMs for waiting
    /// on the frame slot (frames in flight) and acquiring the image; gpuMs of the frame that
    /// last completed in this slot (-1: unknown yet).
    FrameStats stats;
    /// Milliseconds spent queueing the presentation. Software presentation (lavapipe's X11
    /// path) waits there until the frame is rendered and copies it to the window server.
    double presentMs = 0.0;
    /// With FrameRequest::capture: the linear, premultiplied picture that was blitted into the
    /// window, with Lantern's metadata (camera, time, shading), as render() returns it.
    std::optional<Image> capture;
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

/// A swapchain on a host-owned surface, presenting a Renderer's frames. Move-only. Must be
/// destroyed before the Renderer it was created from. Not thread-safe: use it from the thread
/// that uses its Renderer.
class LANTERN_API WindowTarget {
public:
    /// The instance the host creates its surface on (glfwCreateWindowSurface).
    static VkInstance windowInstance(const Renderer& renderer);

    /// Fails with Usage when the renderer was not created with RendererDesc::presentation, and
    /// with Unsupported when its device cannot present to the surface.
    static Result<WindowTarget> create(Renderer& renderer, const WindowTargetDesc& desc);

    WindowTarget(WindowTarget&&) noexcept;
    WindowTarget& operator=(WindowTarget&&) noexcept;
    ~WindowTarget();

    /// Tells the target the framebuffer's current size in pixels (from the window system's
    /// resize events); the swapchain is rebuilt at the next render(). 0 x 0: minimised.
    void resize(int width, int height);

    /// Waits until the frame slot the next render() uses is free (its previous frame has
    /// finished on the GPU): the frames-in-flight bound. A host that calls this before it
    /// samples input shortens the input-to-photon path by the time this waits; render() waits
    /// by itself otherwise. Returns the milliseconds waited.
    Result<double> waitForFrameSlot();

    /// Renders `scene` at `timeSeconds` with `options` (whose width and height are replaced by
    /// the swapchain's; views must fit width() x height()), records `overlay` (if any) and
    /// presents. A minimised window or an out-of-date swapchain is a status, not an error.
    Result<WindowFrame> render(const PreparedScene& scene, const RenderOptions& options,
                               double timeSeconds, const FrameRequest& request = {},
                               const OverlayRecorder& overlay = {});

    /// The swapchain's size in pixels (what render() draws), 0 x 0 while minimised.
    int width() const;
    int height() const;
    PresentMode presentMode() const;     ///< the mode in use (after any fallback)
    std::uint32_t imageCount() const;    ///< swapchain images
    std::uint32_t framesInFlight() const;
    VkFormat format() const;             ///< the swapchain's format (sRGB when offered)

    /// Valid when created with WindowTargetDesc::overlay.
    const OverlayContext& overlayContext() const;
    /// Records `record` into a one-off command buffer, submits it and waits (uploads such as an
    /// overlay's font texture).
    Result<void> submitOnce(const std::function<void(VkCommandBuffer)>& record);
    /// Waits until every submitted frame has finished (before the host frees overlay objects).
    Result<void> waitIdle();

private:
    struct Impl;
    explicit WindowTarget(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

} // namespace lantern
