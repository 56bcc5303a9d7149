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
#include <lantern/WindowTypes.h>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

namespace lantern {

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
