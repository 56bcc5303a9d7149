// The choice between reading a render target in place and staging it through a buffer, and
// the NaN/Inf check of what the host reads.
#include "gpu/ReadbackPath.h"

#include <algorithm>
#include <cstring>

namespace lantern::gpu {

VkFormatFeatureFlags inPlaceFeatures(bool blended) {
    VkFormatFeatureFlags f = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                             VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if (blended) f |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT | VK_FORMAT_FEATURE_BLIT_SRC_BIT;
    return f;
}

int inPlaceMemoryType(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits) {
    const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT |
                                         VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                         VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    const std::uint32_t count = std::min<std::uint32_t>(memory.memoryTypeCount, VK_MAX_MEMORY_TYPES);
    for (std::uint32_t i = 0; i < count; ++i) {
        const VkMemoryPropertyFlags f = memory.memoryTypes[i].propertyFlags;
        if ((f & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) && !(f & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT))
            return -1;
    }
    for (std::uint32_t i = 0; i < count; ++i)
        if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted)
            return int(i);
    return -1;
}

ReadbackChoice chooseReadback(const LinearSupport& linear, VkFormatFeatureFlags needed,
                              const VkPhysicalDeviceMemoryProperties& memory,
                              std::uint32_t typeBits, std::uint32_t width, std::uint32_t height) {
    if ((linear.features & needed) != needed)
        return {false, "staged: the format's linear tiling lacks the attachment, blend or "
                       "transfer features a render target needs"};
    if (!linear.imageSupported)
        return {false, "staged: the device makes no linear image of this format and usage"};
    if (width > linear.maxExtent.width || height > linear.maxExtent.height)
        return {false, "staged: a linear image is limited to " +
                           std::to_string(linear.maxExtent.width) + "x" +
                           std::to_string(linear.maxExtent.height) + " pixels"};
    const int type = inPlaceMemoryType(memory, typeBits);
    if (type < 0)
        return {false, "staged: no device-local, host-visible, host-cached memory type, or "
                       "device-local memory the host cannot map"};
    return {true, "in place: a linear image in memory type " + std::to_string(type) +
                      " (device-local, host-visible, host-cached)"};
}

// A float is NaN or Inf when all its exponent bits are set, and only then does adding 1 to its
// exponent carry into the sign bit. OR-ing those sums costs an AND, an ADD and an OR per value,
// which the compiler vectorises with plain SSE2 in blocks of a fixed size (the per-value
// isfinite test it would not: a fifth of a 1080p readback went to it).
bool anyNonFinite(const float* v, std::size_t n) {
    constexpr std::size_t kBlock = 64;
    std::uint32_t carry = 0;
    std::size_t i = 0;
    for (; i + kBlock <= n; i += kBlock) {
        std::uint32_t u[kBlock];
        std::memcpy(u, v + i, sizeof u);
        for (std::size_t k = 0; k < kBlock; ++k) carry |= (u[k] & 0x7f800000u) + 0x00800000u;
    }
    for (; i < n; ++i) {
        std::uint32_t u;
        std::memcpy(&u, v + i, 4);
        carry |= (u & 0x7f800000u) + 0x00800000u;
    }
    return (carry & 0x80000000u) != 0;
}

} // namespace lantern::gpu
