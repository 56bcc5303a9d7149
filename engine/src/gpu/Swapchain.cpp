// Swapchain creation, rebuilding, acquire and present.
#include "gpu/Swapchain.h"

#include <algorithm>

namespace lantern::gpu {
namespace {

bool isSrgb(VkFormat f) {
    return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R8G8B8A8_SRGB ||
           f == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

const char* modeName(VkPresentModeKHR m) {
    switch (m) {
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return "immediate";
    case VK_PRESENT_MODE_MAILBOX_KHR: return "mailbox";
    case VK_PRESENT_MODE_FIFO_KHR: return "fifo";
    case VK_PRESENT_MODE_FIFO_RELAXED_KHR: return "fifo-relaxed";
    default: return "other";
    }
}

} // namespace

Result<Swapchain> Swapchain::create(Context& ctx, VkSurfaceKHR surface,
                                    const std::vector<VkPresentModeKHR>& modes,
                                    std::uint32_t framesInFlight) {
    const VkPhysicalDevice pd = ctx.physicalDevice();
    VkBool32 supported = VK_FALSE;
    LANTERN_VK_TRY(vkGetPhysicalDeviceSurfaceSupportKHR(pd, ctx.queueFamily(), surface, &supported));
    if (!supported)
        return makeError(ErrorCode::Unsupported,
                         std::string("the device ") + ctx.properties().deviceName +
                             " cannot present to this window's surface from its graphics queue");

    std::uint32_t n = 0;
    LANTERN_VK_TRY(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(n);
    LANTERN_VK_TRY(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, formats.data()));
    formats.resize(n);
    if (formats.empty())
        return makeError(ErrorCode::Unsupported, "the window's surface offers no formats");

    Swapchain s;
    s.m_ctx = &ctx;
    s.m_surface = surface;
    s.m_framesInFlight = std::max<std::uint32_t>(framesInFlight, 1);
    // sRGB, so the blit from the linear float picture encodes it; otherwise the first format.
    s.m_format = formats[0];
    for (const VkSurfaceFormatKHR& f : formats)
        if (isSrgb(f.format) && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
            s.m_format = f;
            break;
        }
    if (!isSrgb(s.m_format.format))
        ctx.log(LogLevel::Warning, "the window's surface offers no sRGB format; the picture is "
                                   "shown without sRGB encoding (too dark)");
    VkFormatProperties fp{};
    vkGetPhysicalDeviceFormatProperties(pd, s.m_format.format, &fp);
    VkFormatProperties src{};
    vkGetPhysicalDeviceFormatProperties(pd, VK_FORMAT_R32G32B32A32_SFLOAT, &src);
    if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) ||
        !(src.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT))
        return makeError(ErrorCode::Unsupported,
                         "the device cannot blit the float picture into the window's format");

    LANTERN_VK_TRY(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, nullptr));
    std::vector<VkPresentModeKHR> offered(n);
    LANTERN_VK_TRY(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, offered.data()));
    offered.resize(n);
    s.m_mode = VK_PRESENT_MODE_FIFO_KHR;
    for (VkPresentModeKHR m : modes)
        if (std::find(offered.begin(), offered.end(), m) != offered.end()) {
            s.m_mode = m;
            break;
        }
    if (!modes.empty() && s.m_mode != modes.front())
        ctx.log(LogLevel::Info, std::string("present mode ") + modeName(modes.front()) +
                                    " is not offered; using " + modeName(s.m_mode));
    return s;
}

Result<bool> Swapchain::rebuild(std::uint32_t width, std::uint32_t height) {
    Context& ctx = *m_ctx;
    VkSurfaceCapabilitiesKHR caps{};
    LANTERN_VK_TRY(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physicalDevice(), m_surface, &caps));
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == 0xFFFFFFFFu) {  // the surface lets the application choose
        extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    m_views.clear();
    m_images.clear();
    if (extent.width == 0 || extent.height == 0) {
        m_swapchain.reset();
        m_extent = {0, 0};
        return false;
    }
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if ((caps.supportedUsageFlags & usage) != usage)
        return makeError(ErrorCode::Unsupported,
                         "the window's swapchain images cannot be blitted to and drawn into");

    // One image per frame in flight plus the one on screen; mailbox wants a spare one.
    std::uint32_t count = std::max({caps.minImageCount, m_framesInFlight + 1,
                                    m_mode == VK_PRESENT_MODE_MAILBOX_KHR ? 3u : 2u});
    if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);

    VkCompositeAlphaFlagBitsKHR alpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    for (VkCompositeAlphaFlagBitsKHR a :
         {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
          VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR, VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
        if (caps.supportedCompositeAlpha & a) {
            alpha = a;
            break;
        }

    VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    ci.surface = m_surface;
    ci.minImageCount = count;
    ci.imageFormat = m_format.format;
    ci.imageColorSpace = m_format.colorSpace;
    ci.imageExtent = extent;
    ci.imageArrayLayers = 1;
    ci.imageUsage = usage;
    ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                          ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                          : caps.currentTransform;
    ci.compositeAlpha = alpha;
    ci.presentMode = m_mode;
    ci.clipped = VK_TRUE;
    ci.oldSwapchain = m_swapchain.get();
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateSwapchainKHR(ctx.device(), &ci, nullptr, &handle));
    m_swapchain = UniqueSwapchain(ctx.device(), handle);  // destroys the old one
    ctx.setName(VK_OBJECT_TYPE_SWAPCHAIN_KHR, handle, "window swapchain");
    m_extent = extent;

    std::uint32_t n = 0;
    LANTERN_VK_TRY(vkGetSwapchainImagesKHR(ctx.device(), handle, &n, nullptr));
    m_images.resize(n);
    LANTERN_VK_TRY(vkGetSwapchainImagesKHR(ctx.device(), handle, &n, m_images.data()));
    for (std::uint32_t i = 0; i < n; ++i) {
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = m_images[i];
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = m_format.format;
        vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateImageView(ctx.device(), &vci, nullptr, &view));
        m_views.emplace_back(ctx.device(), view);
        ctx.setName(VK_OBJECT_TYPE_IMAGE, m_images[i], "swapchain image " + std::to_string(i));
    }
    ctx.log(LogLevel::Debug, "swapchain " + std::to_string(extent.width) + "x" +
                                 std::to_string(extent.height) + ", " + std::to_string(n) +
                                 " images, " + modeName(m_mode));
    return true;
}

Result<SwapchainState> Swapchain::acquire(VkSemaphore signal, std::uint32_t& index) {
    if (!m_swapchain) return SwapchainState::OutOfDate;
    const VkResult r = vkAcquireNextImageKHR(m_ctx->device(), m_swapchain.get(), UINT64_MAX,
                                             signal, VK_NULL_HANDLE, &index);
    switch (r) {
    case VK_SUCCESS: return SwapchainState::Ready;
    case VK_SUBOPTIMAL_KHR: return SwapchainState::Suboptimal;
    case VK_ERROR_OUT_OF_DATE_KHR: return SwapchainState::OutOfDate;
    default: return vkError(r, "vkAcquireNextImageKHR");
    }
}

Result<SwapchainState> Swapchain::present(VkSemaphore wait, std::uint32_t index) {
    VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &wait;
    pi.swapchainCount = 1;
    const VkSwapchainKHR handle = m_swapchain.get();
    pi.pSwapchains = &handle;
    pi.pImageIndices = &index;
    VkResult r;
    {
        std::lock_guard lock(m_ctx->queueMutex());
        r = vkQueuePresentKHR(m_ctx->queue(), &pi);
    }
    switch (r) {
    case VK_SUCCESS: return SwapchainState::Ready;
    case VK_SUBOPTIMAL_KHR: return SwapchainState::Suboptimal;
    case VK_ERROR_OUT_OF_DATE_KHR: return SwapchainState::OutOfDate;
    default: return vkError(r, "vkQueuePresentKHR");
    }
}

} // namespace lantern::gpu
