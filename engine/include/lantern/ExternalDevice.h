// ExternalDevice.h: a Renderer on Vulkan objects the host owns (its VkInstance, VkPhysicalDevice,
// VkDevice and a graphics queue), for a host that renders with Vulkan itself and wants Lantern's
// pictures on the same device. It includes vulkan.h, as lantern/Window.h does: the host's
// handles cross the API on purpose.
//
//   lantern::ExternalDevice ext;
//   ext.instance = instance;  ext.instanceApiVersion = VK_API_VERSION_1_3;
//   ext.physicalDevice = gpu; ext.device = device;
//   ext.queueFamily = family; ext.queue = queue;
//   ext.enabledFeatures = deviceCreateInfo.pNext;            // what vkCreateDevice was given
//   ext.enabledCoreFeatures = deviceCreateInfo.pEnabledFeatures;
//   ext.enabledExtensions = {deviceCreateInfo.ppEnabledExtensionNames,
//                            deviceCreateInfo.ppEnabledExtensionNames +
//                                deviceCreateInfo.enabledExtensionCount};
//   auto renderer = lantern::Renderer::create(ext);
//
// What the host must have enabled (checked by Renderer::create, which fails with Unsupported
// naming what is missing, or Usage for a null or mismatched handle):
//   - an instance created for Vulkan 1.3 or newer (VkApplicationInfo::apiVersion), and a
//     physical device of that instance supporting Vulkan 1.3;
//   - on the device: dynamicRendering and synchronization2 (VkPhysicalDeviceVulkan13Features,
//     or VkPhysicalDeviceDynamicRenderingFeatures and VkPhysicalDeviceSynchronization2Features);
//   - a queue of a family with VK_QUEUE_GRAPHICS_BIT;
//   - VK_KHR_swapchain, when RendererDesc::presentation is set (for lantern/Window.h; the
//     instance then needs the host's surface extensions).
// Optional, used when enabled (a feature that is not enabled turns off what needs it, with a
// clear error when that is asked for):
//   - geometryShader and independentBlend: AOVs (RenderOptions::aovs, Renderer::probe);
//   - fillModeNonSolid: the wireframe overlay;
//   - VK_EXT_provoking_vertex with provokingVertexLast: RenderOptions::glCompat flat shading
//     with GL's provoking vertex.
//   - the float colour and depth sample counts the device offers bound RenderOptions::msaa.
//
// Ownership: Lantern never destroys the host's objects. It creates its own command pools,
// pipelines, buffers, images and so on on the device and destroys all of them when the last
// object holding the device lets go: the Renderer, every PreparedScene it prepared and every
// WindowTarget made from it must be destroyed before the host destroys the device. Lantern
// never waits for the whole device (vkDeviceWaitIdle): where it must drain its work (a
// Renderer or a swapchain going away) it waits for its queue (vkQueueWaitIdle, under the
// queue lock).
//
// Lantern calls Vulkan through the system loader (libvulkan.so.1), so the handles must come
// from that loader too. Validation layers and debug messengers are the host's: they are on
// the host's instance, and RendererDesc::validation is ignored.
#pragma once

#include <lantern/Export.h>
#include <lantern/RenderTypes.h>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace lantern {

/// The host's Vulkan objects a Renderer is created on (Renderer::create(ExternalDevice, ...)).
/// The pointers are read only during that call; the handles must stay valid until everything
/// created on them is destroyed.
struct ExternalDevice {
    VkInstance instance = VK_NULL_HANDLE;
    /// The apiVersion the instance was created with (VkApplicationInfo::apiVersion): Lantern
    /// records Vulkan 1.3 commands, which need an instance created for 1.3 or newer.
    std::uint32_t instanceApiVersion = 0;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;  ///< one of `instance`'s devices
    VkDevice device = VK_NULL_HANDLE;                  ///< created on `physicalDevice`
    std::uint32_t queueFamily = 0;  ///< the family of `queue`: it must support graphics
    VkQueue queue = VK_NULL_HANDLE; ///< where Lantern submits (and presents, for windows)

    /// The features the device was created with: VkDeviceCreateInfo::pNext (the chain is
    /// searched for VkPhysicalDeviceFeatures2, VkPhysicalDeviceVulkan13Features,
    /// VkPhysicalDeviceDynamicRenderingFeatures, VkPhysicalDeviceSynchronization2Features and
    /// VkPhysicalDeviceProvokingVertexFeaturesEXT; other structures are skipped).
    const void* enabledFeatures = nullptr;
    /// VkDeviceCreateInfo::pEnabledFeatures, when the host used it instead of a
    /// VkPhysicalDeviceFeatures2 in the chain (null otherwise).
    const VkPhysicalDeviceFeatures* enabledCoreFeatures = nullptr;
    /// The device extensions enabled (VkDeviceCreateInfo::ppEnabledExtensionNames).
    std::vector<std::string> enabledExtensions;

    /// Vulkan requires submissions to one queue to be externally synchronised. When the host
    /// submits to `queue` from other threads while Lantern renders, it passes the mutex it
    /// locks around its own vkQueueSubmit/vkQueuePresentKHR/vkQueueWaitIdle calls, and Lantern
    /// locks it around its own such calls (it waits for its fences without the lock). Null:
    /// Lantern uses a mutex of its own, and the host must not use the queue during Lantern
    /// calls.
    std::mutex* queueMutex = nullptr;
};

} // namespace lantern
