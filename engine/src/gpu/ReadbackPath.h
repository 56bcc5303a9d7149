// ReadbackPath.h: how the host reads a render target back. In place: the target is a linear
// image in memory the host maps, read through its row pitch once the frame's fence has
// signalled, with no copy on the device. Staged: an optimal-tiling image that the frame's
// command buffer copies into a host-visible buffer. Chosen per plane (colour, AOVs) from the
// device's properties, never from its name: the format's linear-tiling features, whether a
// linear image of that size and usage can be made, and the memory types.
#pragma once

#include "gpu/Vk.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace lantern::gpu {

/// What the device says about one plane's format with VK_IMAGE_TILING_LINEAR.
struct LinearSupport {
    VkFormatFeatureFlags features = 0;  ///< vkGetPhysicalDeviceFormatProperties: linearTilingFeatures
    bool imageSupported = false;  ///< vkGetPhysicalDeviceImageFormatProperties accepted the usage
    VkExtent3D maxExtent{0, 0, 0};  ///< its answer's largest extent
};

/// The decision for one plane, with the reason in one sentence (logged at debug level).
struct ReadbackChoice {
    bool inPlace = false;
    std::string why;
};

/// The linear-tiling features a plane rendered in place needs: a colour attachment (blended for
/// the float colour, whose transparent draws blend), and a transfer and blit source (a window
/// frame blits the colour into the swapchain).
VkFormatFeatureFlags inPlaceFeatures(bool blended);

/// The memory type a linear target read in place is bound to, among `typeBits`, or -1 when the
/// host should not read render targets in place on this device. A type must be device-local
/// (the device renders into it at full speed), host-visible and host-cached (the host reads it
/// at memory speed; uncached write-combined memory, a discrete GPU's BAR window, reads slowly);
/// and every device-local type must be host-visible: a device with memory of its own that the
/// host cannot map renders faster into that, with the copy, than into memory the host sees.
int inPlaceMemoryType(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits);

/// In place when the format's linear tiling has `needed`, a linear image of width x height
/// with the plane's usage can be made, and inPlaceMemoryType() finds a type among `typeBits`
/// (all types before the image exists; its memoryTypeBits after); otherwise staged.
ReadbackChoice chooseReadback(const LinearSupport& linear, VkFormatFeatureFlags needed,
                              const VkPhysicalDeviceMemoryProperties& memory,
                              std::uint32_t typeBits, std::uint32_t width, std::uint32_t height);

/// True when one of the `n` floats is NaN or Inf (either sign, any payload): the check the
/// readback makes on every row it copies, vectorised (gpu/Readback.cpp).
bool anyNonFinite(const float* values, std::size_t n);

} // namespace lantern::gpu
