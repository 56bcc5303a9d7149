// Which physical device Lantern renders on: the choice among an instance's devices for
// Context::create, and the checks on a host's device for Context::adopt.
#pragma once

#include "gpu/Vk.h"

#include <cstdint>
#include <lantern/ExternalDevice.h>
#include <lantern/Result.h>
#include <string>
#include <vector>

namespace lantern::gpu {

/// "discrete-gpu", "integrated-gpu", "virtual-gpu", "cpu" or "other".
const char* deviceTypeName(VkPhysicalDeviceType type);

bool hasExtension(const std::vector<VkExtensionProperties>& exts, const char* name);
std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice pd);

struct ChosenDevice {
    VkPhysicalDevice device = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0; ///< the first family with graphics
};

/// The best usable device of `instance` (discrete before integrated before virtual before
/// CPU) whose name contains `deviceName` (case-insensitive; empty: any). NoDevice, listing
/// every device with the reason it was passed over, when none is usable. `swapchain`:
/// VK_KHR_swapchain is needed.
Result<ChosenDevice> choosePhysicalDevice(VkInstance instance, const std::string& deviceName,
                                          bool swapchain);

/// The features a host enabled on its device, gathered from what it gave vkCreateDevice.
struct EnabledFeatures {
    VkPhysicalDeviceFeatures core{};
    bool dynamicRendering = false;
    bool synchronization2 = false;
    bool provokingVertexLast = false;
};

/// Checks that the host's objects have what Lantern needs (Unsupported or Usage naming the
/// ExternalDevice field at fault) and returns the features the host enabled. `swapchain`:
/// presentation was asked for.
Result<EnabledFeatures> checkExternalDevice(const ExternalDevice& e, bool swapchain);

/// Whether the host enabled the device extension `name`.
bool extensionEnabled(const ExternalDevice& e, const char* name);

} // namespace lantern::gpu
