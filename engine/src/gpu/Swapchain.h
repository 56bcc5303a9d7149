// Swapchain: a VkSwapchainKHR on a host-owned surface: format and present-mode choice,
// (re)building for the surface's extent, image views, and acquire/present that report an
// out-of-date or suboptimal swapchain as a state rather than an error.
#pragma once

#include "gpu/Context.h"
#include "gpu/Handles.h"

#include <cstdint>
#include <vector>

namespace lantern::gpu {

/// What acquire() and present() found.
enum class SwapchainState {
    Ready,       ///< acquired / queued
    Suboptimal,  ///< acquired / queued, but the swapchain should be rebuilt soon
    OutOfDate,   ///< nothing acquired / presented: rebuild first
};

class Swapchain {
public:
    /// Checks that the device can present to `surface`, and picks the format (sRGB when
    /// offered) and the first present mode of `modes` the surface supports (FIFO always is).
    /// Nothing is built until rebuild().
    static Result<Swapchain> create(Context& ctx, VkSurfaceKHR surface,
                                    const std::vector<VkPresentModeKHR>& modes,
                                    std::uint32_t framesInFlight);

    Swapchain(Swapchain&&) noexcept = default;
    Swapchain& operator=(Swapchain&&) noexcept = default;

    /// Builds the swapchain (passing the current one as oldSwapchain) for the surface's
    /// current extent, or width x height where the surface lets the application choose. The
    /// caller makes sure the GPU no longer uses the current images. Returns false, and leaves
    /// no swapchain, when the extent is 0 x 0 (a minimised window).
    Result<bool> rebuild(std::uint32_t width, std::uint32_t height);

    /// Acquires the next image, signalling `signal` when it may be written.
    Result<SwapchainState> acquire(VkSemaphore signal, std::uint32_t& index);
    /// Queues image `index` for presentation once `wait` is signalled.
    Result<SwapchainState> present(VkSemaphore wait, std::uint32_t index);

    bool valid() const { return bool(m_swapchain); }
    VkFormat format() const { return m_format.format; }
    VkExtent2D extent() const { return m_extent; }
    VkPresentModeKHR presentMode() const { return m_mode; }
    std::uint32_t imageCount() const { return std::uint32_t(m_images.size()); }
    VkImage image(std::uint32_t i) const { return m_images[i]; }
    VkImageView view(std::uint32_t i) const { return m_views[i].get(); }

private:
    Swapchain() = default;

    Context* m_ctx = nullptr;
    VkSurfaceKHR m_surface = VK_NULL_HANDLE;
    VkSurfaceFormatKHR m_format{};
    VkPresentModeKHR m_mode = VK_PRESENT_MODE_FIFO_KHR;
    std::uint32_t m_framesInFlight = 2;
    VkExtent2D m_extent{0, 0};
    UniqueSwapchain m_swapchain;
    std::vector<VkImage> m_images;
    std::vector<UniqueImageView> m_views;
};

} // namespace lantern::gpu
