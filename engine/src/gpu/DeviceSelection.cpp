// Which physical device Lantern renders on: the choice among an instance's devices for
// Context::create (with the reason each one was passed over), the same choice described for
// lantern::listDevices (`lantern info --devices`), and the checks on a host's device for
// Context::adopt.
#include "gpu/DeviceSelection.h"

#include "core/SanitizerSupport.h"

#include "gpu/DriverReport.h"
#include "gpu/PipelineCache.h"

#include "gpu/Device.h"

#include <lantern/RenderTypes.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <utility>

namespace lantern::gpu {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

int typeRank(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return 3;
    default:
        return 4;
    }
}

struct Candidate {
    VkPhysicalDevice device;
    VkPhysicalDeviceProperties props;
    std::uint32_t queueFamily;
    std::string rejection; // empty: usable
};

Candidate examine(VkPhysicalDevice pd, bool needSwapchain) {
    Candidate c{pd, {}, 0, {}};
    vkGetPhysicalDeviceProperties(pd, &c.props);
    if (c.props.apiVersion < VK_API_VERSION_1_3) {
        c.rejection =
            "supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(c.props.apiVersion)) + "." +
            std::to_string(VK_API_VERSION_MINOR(c.props.apiVersion)) + ", Lantern needs 1.3";
        return c;
    }
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13, {}};
    vkGetPhysicalDeviceFeatures2(pd, &f2);
    if (!f13.dynamicRendering || !f13.synchronization2) {
        c.rejection = "lacks dynamicRendering or synchronization2";
        return c;
    }
    std::uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, families.data());
    bool found = false;
    for (std::uint32_t i = 0; i < nq; ++i)
        if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
            c.queueFamily = i;
            found = true;
            break;
        }
    if (!found) {
        c.rejection = "has no graphics queue";
        return c;
    }
    if (needSwapchain && !hasExtension(deviceExtensions(pd), VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        c.rejection = "lacks VK_KHR_swapchain";
    return c;
}

// The best usable candidate whose name contains `wanted` (lower case; empty: any), or null.
const Candidate* bestCandidate(const std::vector<Candidate>& candidates,
                               const std::string& wanted) {
    const Candidate* chosen = nullptr;
    for (const Candidate& c : candidates) {
        if (!c.rejection.empty()) continue;
        if (!wanted.empty() && lower(c.props.deviceName).find(wanted) == std::string::npos)
            continue;
        if (!chosen || typeRank(c.props.deviceType) < typeRank(chosen->props.deviceType))
            chosen = &c;
    }
    return chosen;
}

// "[0] llvmpipe (LLVM 15.0.6, 256 bits) (cpu) [1] ...": every device found, with the index a
// request may give and why a device cannot be used.
std::string candidateList(const std::vector<Candidate>& candidates) {
    std::ostringstream out;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const Candidate& c = candidates[i];
        out << (i ? " " : "") << "[" << i << "] " << c.props.deviceName << " ("
            << deviceTypeName(c.props.deviceType) << ")"
            << (c.rejection.empty() ? "" : ": " + c.rejection);
    }
    return out.str();
}

// The candidate `request` picks, or NoDevice saying why none fits and listing every device.
Result<const Candidate*> pickCandidate(const std::vector<Candidate>& candidates,
                                       const DeviceRequest& request) {
    const std::string found = "; the loader found " + std::to_string(candidates.size()) +
                              (candidates.size() == 1 ? " device: " : " devices: ") +
                              candidateList(candidates);
    if (request.index) {
        const std::size_t i = *request.index;
        if (i >= candidates.size())
            return makeError(ErrorCode::NoDevice, request.label + ": there is no device " +
                                                      std::to_string(i) + found);
        if (!candidates[i].rejection.empty())
            return makeError(ErrorCode::NoDevice,
                             request.label + ": device " + std::to_string(i) + " (" +
                                 candidates[i].props.deviceName + ") cannot be used" + found);
        return &candidates[i];
    }
    if (const Candidate* c = bestCandidate(candidates, lower(request.text))) return c;
    return makeError(ErrorCode::NoDevice,
                     request.text.empty()
                         ? "no usable Vulkan device" + found
                         : request.label + ": no usable Vulkan device's name contains \"" +
                               request.text + "\"" + found);
}

EnabledFeatures readEnabledFeatures(const ExternalDevice& e) {
    EnabledFeatures f;
    if (e.enabledCoreFeatures) f.core = *e.enabledCoreFeatures;
    // Every feature structure starts with sType and pNext (VkBaseInStructure).
    for (auto* s = static_cast<const VkBaseInStructure*>(e.enabledFeatures); s; s = s->pNext) {
        switch (s->sType) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2:
            f.core = reinterpret_cast<const VkPhysicalDeviceFeatures2*>(s)->features;
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES: {
            const auto* v = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(s);
            f.dynamicRendering = f.dynamicRendering || v->dynamicRendering;
            f.synchronization2 = f.synchronization2 || v->synchronization2;
            break;
        }
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
            f.dynamicRendering =
                f.dynamicRendering ||
                reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(s)
                    ->dynamicRendering;
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
            f.synchronization2 =
                f.synchronization2 ||
                reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(s)
                    ->synchronization2;
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT:
            f.provokingVertexLast =
                reinterpret_cast<const VkPhysicalDeviceProvokingVertexFeaturesEXT*>(s)
                    ->provokingVertexLast;
            break;
        default:
            break;
        }
    }
    return f;
}

std::string versionText(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v));
}

// The handles are all set and the instance was made for Vulkan 1.3.
Result<void> checkExternalHandles(const ExternalDevice& e) {
    const std::pair<const char*, bool> handles[] = {
        {"instance", e.instance != VK_NULL_HANDLE},
        {"physicalDevice", e.physicalDevice != VK_NULL_HANDLE},
        {"device", e.device != VK_NULL_HANDLE},
        {"queue", e.queue != VK_NULL_HANDLE}};
    for (const auto& [name, set] : handles)
        if (!set)
            return makeError(ErrorCode::Usage,
                             std::string(name) + " is VK_NULL_HANDLE: the host's instance, "
                                                 "physical device, device and queue are all needed",
                             std::string("ExternalDevice.") + name);
    if (e.instanceApiVersion < VK_API_VERSION_1_3)
        return makeError(ErrorCode::Unsupported,
                         "the instance was created for Vulkan " +
                             versionText(e.instanceApiVersion) +
                             " (VkApplicationInfo::apiVersion); Lantern records Vulkan 1.3 "
                             "commands and needs an instance created for 1.3 or newer",
                         "ExternalDevice.instanceApiVersion");
    return {};
}

// The physical device is one of the instance's, supports Vulkan 1.3, and the queue family exists
// and has graphics.
Result<void> checkExternalPhysicalDevice(const ExternalDevice& e) {
    // The physical device must be one of the instance's (handles from two instances mix badly).
    std::uint32_t nd = 0;
    LANTERN_VK_TRY(vkEnumeratePhysicalDevices(e.instance, &nd, nullptr));
    std::vector<VkPhysicalDevice> devices(nd);
    const VkResult listed = vkEnumeratePhysicalDevices(e.instance, &nd, devices.data());
    if (listed != VK_SUCCESS && listed != VK_INCOMPLETE)
        return vkError(listed, "vkEnumeratePhysicalDevices");
    if (std::find(devices.begin(), devices.end(), e.physicalDevice) == devices.end())
        return makeError(ErrorCode::Usage, "physicalDevice is not one of the instance's devices",
                         "ExternalDevice.physicalDevice");

    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(e.physicalDevice, &props);
    if (props.apiVersion < VK_API_VERSION_1_3)
        return makeError(ErrorCode::Unsupported,
                         std::string(props.deviceName) + " supports Vulkan " +
                             versionText(props.apiVersion) + ", Lantern needs 1.3",
                         "ExternalDevice.physicalDevice");

    std::uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(e.physicalDevice, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(e.physicalDevice, &nq, families.data());
    if (e.queueFamily >= nq)
        return makeError(ErrorCode::Usage,
                         "queue family " + std::to_string(e.queueFamily) +
                             " does not exist (the "
                             "device has " +
                             std::to_string(nq) + ")",
                         "ExternalDevice.queueFamily");
    if (!(families[e.queueFamily].queueFlags & VK_QUEUE_GRAPHICS_BIT))
        return makeError(ErrorCode::Unsupported,
                         "queue family " + std::to_string(e.queueFamily) +
                             " has no VK_QUEUE_GRAPHICS_BIT; Lantern draws on a graphics queue",
                         "ExternalDevice.queueFamily");
    return {};
}

} // namespace

const char* deviceTypeName(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return "cpu";
    default:
        return "other";
    }
}

bool hasExtension(const std::vector<VkExtensionProperties>& exts, const char* name) {
    return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice pd) {
    std::uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
    exts.resize(n);
    return exts;
}

DeviceRequest deviceRequest(const std::string& deviceName) {
    DeviceRequest r;
    // An explicit name (RendererDesc::deviceName, --device) wins over the environment.
    const char* fromEnv = std::getenv("LANTERN_DEVICE");
    if (!deviceName.empty()) {
        r.text = deviceName;
        r.label = "device \"" + deviceName + "\"";
    } else if (fromEnv && *fromEnv) {
        r.text = fromEnv;
        r.label = "LANTERN_DEVICE=" + r.text;
    }
    if (!r.text.empty() && r.text.size() <= 9 &&
        std::all_of(r.text.begin(), r.text.end(), [](unsigned char c) { return std::isdigit(c); }))
        r.index = std::size_t(std::stoul(r.text));
    return r;
}

Result<ChosenDevice> choosePhysicalDevice(VkInstance instance, const DeviceRequest& request,
                                          bool swapchain) {
    std::uint32_t nd = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance, &nd, nullptr);
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) return vkError(r, "vkEnumeratePhysicalDevices");
    if (nd == 0)
        return makeError(ErrorCode::NoDevice,
                         noDeviceMessage("the loader found 0 physical devices"));
    std::vector<VkPhysicalDevice> devices(nd);
    vkEnumeratePhysicalDevices(instance, &nd, devices.data());
    devices.resize(nd);

    std::vector<Candidate> candidates;
    for (VkPhysicalDevice pd : devices)
        candidates.push_back(examine(pd, swapchain));
    Result<const Candidate*> chosen = pickCandidate(candidates, request);
    if (!chosen) return std::move(chosen).error();
    return ChosenDevice{(*chosen)->device, (*chosen)->queueFamily};
}

Result<EnabledFeatures> checkExternalDevice(const ExternalDevice& e, bool swapchain) {
    LANTERN_TRY(checkExternalHandles(e));
    LANTERN_TRY(checkExternalPhysicalDevice(e));
    const EnabledFeatures f = readEnabledFeatures(e);
    std::string missing;
    if (!f.dynamicRendering) missing += " dynamicRendering";
    if (!f.synchronization2) missing += " synchronization2";
    if (!missing.empty())
        return makeError(ErrorCode::Unsupported,
                         "the device was created without" + missing +
                             " (VkPhysicalDeviceVulkan13Features in VkDeviceCreateInfo::pNext); "
                             "Lantern renders with both",
                         "ExternalDevice.enabledFeatures");
    if (swapchain && !extensionEnabled(e, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        return makeError(ErrorCode::Unsupported,
                         "RendererDesc::presentation needs VK_KHR_swapchain enabled on the device",
                         "ExternalDevice.enabledExtensions");
    return f;
}

bool extensionEnabled(const ExternalDevice& e, const char* name) {
    return std::find(e.enabledExtensions.begin(), e.enabledExtensions.end(), name) !=
           e.enabledExtensions.end();
}

} // namespace lantern::gpu

namespace lantern {
namespace {

std::string fullVersionText(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

// What listDevices says of one candidate: its driver, sample counts and swapchain support.
DeviceListing describe(const gpu::Candidate& c) {
    DeviceListing d;
    d.name = c.props.deviceName;
    d.type = gpu::deviceTypeName(c.props.deviceType);
    d.apiVersion = fullVersionText(c.props.apiVersion);
    d.usable = c.rejection.empty();
    d.whyNot = c.rejection;
    if (c.props.apiVersion >= VK_API_VERSION_1_2) {
        VkPhysicalDeviceVulkan12Properties p12{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
        VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p12, {}};
        vkGetPhysicalDeviceProperties2(c.device, &props2);
        d.driver = std::string(p12.driverName) + " " + p12.driverInfo;
    }
    d.presentation =
        gpu::hasExtension(gpu::deviceExtensions(c.device), VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    const auto& lim = c.props.limits;
    const VkSampleCountFlags counts =
        lim.framebufferColorSampleCounts & lim.framebufferDepthSampleCounts;
    for (int s = 1; s <= 64; s *= 2)
        if (counts & VkSampleCountFlags(s)) d.msaaSampleCounts.push_back(s);
    // Where Renderer::create would keep its pipelines (the default settings, this environment).
    const gpu::PipelineCachePlace place = gpu::pipelineCachePlace({}, c.props);
    d.pipelineCacheFile = place.file.string();
    d.pipelineCacheOff = place.off;
    std::error_code error;
    // A link at the name is not the cache (the cache never follows one): its size is not told.
    if (!place.file.empty() && std::filesystem::symlink_status(place.file, error).type() ==
                                   std::filesystem::file_type::regular)
        d.pipelineCacheBytes = std::int64_t(std::filesystem::file_size(place.file, error));
    return d;
}

} // namespace

std::string gpu::vulkanLoaderVersion() {
    std::uint32_t version = 0;
    if (vkEnumerateInstanceVersion(&version) != VK_SUCCESS) return {};
    return fullVersionText(version);
}

Result<DeviceList> gpu::listDevices(const std::string& deviceName) {
#if defined(LANTERN_ASAN)
    // As Context::create: this instance loads the drivers first, and their one-off
    // allocations must keep a library name when LeakSanitizer looks at exit.
    core::pinVulkanLibraries();
#endif
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "lantern";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    const VkResult r = vkCreateInstance(&ici, nullptr, &instance);
    if (r != VK_SUCCESS)
        return makeError(ErrorCode::NoDevice,
                         gpu::noDeviceMessage(std::string("no Vulkan driver could be loaded "
                                                          "(vkCreateInstance: ") +
                                              gpu::vkResultName(r) + ")"));
    std::uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance, &n, nullptr);
    std::vector<VkPhysicalDevice> devices(n);
    vkEnumeratePhysicalDevices(instance, &n, devices.data());
    devices.resize(n);
    std::vector<gpu::Candidate> candidates;
    for (VkPhysicalDevice pd : devices)
        candidates.push_back(gpu::examine(pd, false));
    const gpu::DeviceRequest request = gpu::deviceRequest(deviceName);
    Result<const gpu::Candidate*> best = gpu::pickCandidate(candidates, request);
    DeviceList list;
    for (const gpu::Candidate& c : candidates) {
        list.devices.push_back(describe(c));
        list.devices.back().chosen = best && &c == *best;
    }
    vkDestroyInstance(instance, nullptr);
    const std::string ranking = "discrete GPUs first, then integrated, virtual, CPU";
    if (!best)
        list.choice = "none: " + (candidates.empty() ? gpu::noDeviceMessage(
                                                           "the loader found 0 physical devices")
                                                     : best.error().message);
    else if (request.index)
        list.choice = "device " + std::to_string(*request.index) + " of the list, as " +
                      request.label + " asks";
    else if (!request.text.empty())
        list.choice = "the best-ranked usable device whose name contains \"" + request.text +
                      "\" (" + request.label + "; " + ranking + ")";
    else
        list.choice = "the best-ranked usable device (" + ranking + ")";
    return list;
}

} // namespace lantern
