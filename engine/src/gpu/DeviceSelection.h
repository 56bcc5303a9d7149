// Which physical device Lantern renders on: the choice among an instance's devices for
// Context::create, and the checks on a host's device for Context::adopt.
#pragma once

#include "gpu/Vk.h"

#include <cstdint>
#include <lantern/ExternalDevice.h>
#include <lantern/Result.h>
#include <optional>
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

/// Which device the host asked for: RendererDesc::deviceName (the CLI's --device) when it is
/// set, else the environment variable LANTERN_DEVICE, else none. A whole number is an index
/// into the device list (the loader's order, as listDevices() lists them); any other text a
/// substring of the device's name, case-insensitive.
struct DeviceRequest {
    std::string text;                  ///< empty: the best-ranked usable device
    std::string label;                 ///< for messages: `device "x"` or `LANTERN_DEVICE=x`
    std::optional<std::size_t> index;  ///< set when `text` is a whole number
};
DeviceRequest deviceRequest(const std::string& deviceName);

/// The device `request` picks among `instance`'s devices: the one at its index, or the best
/// usable one (discrete before integrated before virtual before CPU) whose name contains its
/// text. NoDevice, listing every device found with its index and the reason any was passed
/// over, when none fits; NoDevice with the drivers the loader saw and how to install lavapipe
/// when there is no device at all. `swapchain`: VK_KHR_swapchain is needed.
Result<ChosenDevice> choosePhysicalDevice(VkInstance instance, const DeviceRequest& request,
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
