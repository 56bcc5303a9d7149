// Instance, validation messenger, device selection (with reasons for each rejection) and
// device creation.
#include "gpu/Context.h"

#if defined(LANTERN_ASAN)
#include "core/SanitizerSupport.h"
#endif

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>
#include <utility>

namespace lantern::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

const char* typeName(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

int typeRank(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

bool hasExtension(const std::vector<VkExtensionProperties>& exts, const char* name) {
    return std::any_of(exts.begin(), exts.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice pd) {
    std::uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
    exts.resize(n);
    return exts;
}

struct Candidate {
    VkPhysicalDevice device;
    VkPhysicalDeviceProperties props;
    std::uint32_t queueFamily;
    std::string rejection;  // empty: usable
};

Candidate examine(VkPhysicalDevice pd, bool needSwapchain) {
    Candidate c{pd, {}, 0, {}};
    vkGetPhysicalDeviceProperties(pd, &c.props);
    if (c.props.apiVersion < VK_API_VERSION_1_3) {
        c.rejection = "supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(c.props.apiVersion)) +
                      "." + std::to_string(VK_API_VERSION_MINOR(c.props.apiVersion)) +
                      ", Lantern needs 1.3";
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

} // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL Context::debugCallback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* self = static_cast<Context*>(user);
    const bool serious = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    // Validation (and general) warnings and errors count as failures; performance hints only
    // go to the log at debug level.
    const bool counted = serious && (types & (VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                              VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT));
    if (counted) self->m_validationMessages.fetch_add(1);
    LogLevel level = LogLevel::Debug;
    if (counted)
        level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? LogLevel::Error
                                                                           : LogLevel::Warning;
    self->log(level, std::string("vulkan validation: ") +
                         (data && data->pMessage ? data->pMessage : "(no message)"));
    return VK_FALSE;
}

Result<std::shared_ptr<Context>> Context::create(const ContextDesc& desc) {
    armFaultsFromEnvironment();
#if defined(LANTERN_ASAN)
    core::pinVulkanLibraries();
#endif
    std::shared_ptr<Context> ctx(new Context());
    ctx->m_log = desc.log;

    std::uint32_t loaderVersion = 0;
    if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS ||
        loaderVersion < VK_API_VERSION_1_3)
        return makeError(ErrorCode::NoDevice,
                         "the Vulkan loader does not support Vulkan 1.3 (install libvulkan1 "
                         "from Debian 12 or newer)");

    // Layers and instance extensions.
    std::uint32_t nl = 0;
    vkEnumerateInstanceLayerProperties(&nl, nullptr);
    std::vector<VkLayerProperties> layers(nl);
    vkEnumerateInstanceLayerProperties(&nl, layers.data());
    const bool wantValidation = desc.validation || desc.synchronizationValidation;
    const bool haveValidation =
        std::any_of(layers.begin(), layers.end(), [](const VkLayerProperties& l) {
            return std::strcmp(l.layerName, kValidationLayer) == 0;
        });
    if (wantValidation && !haveValidation)
        ctx->log(LogLevel::Warning, "validation requested but VK_LAYER_KHRONOS_validation is not "
                                    "installed (Debian package vulkan-validationlayers)");
    ctx->m_validation = wantValidation && haveValidation;

    std::uint32_t ne = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &ne, nullptr);
    std::vector<VkExtensionProperties> instExts(ne);
    vkEnumerateInstanceExtensionProperties(nullptr, &ne, instExts.data());

    std::vector<const char*> extensions;
    for (const auto& e : desc.instanceExtensions) {
        if (!hasExtension(instExts, e.c_str()))
            return makeError(ErrorCode::Unsupported, "instance extension " + e + " is missing");
        extensions.push_back(e.c_str());
    }
    const bool debugUtils =
        ctx->m_validation && hasExtension(instExts, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    std::vector<const char*> enabledLayers;
    if (ctx->m_validation) enabledLayers.push_back(kValidationLayer);

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "lantern";
    app.pEngineName = "Lantern";
    app.apiVersion = VK_API_VERSION_1_3;

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = &Context::debugCallback;
    messengerInfo.pUserData = ctx.get();

    VkValidationFeatureEnableEXT syncFeature =
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT validationFeatures{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    validationFeatures.enabledValidationFeatureCount = 1;
    validationFeatures.pEnabledValidationFeatures = &syncFeature;

    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = std::uint32_t(enabledLayers.size());
    ici.ppEnabledLayerNames = enabledLayers.data();
    ici.enabledExtensionCount = std::uint32_t(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    // Chain the messenger so instance creation and destruction are validated too.
    if (debugUtils) {
        ici.pNext = &messengerInfo;
        if (desc.synchronizationValidation) messengerInfo.pNext = &validationFeatures;
    }
    VkResult r = vkCreateInstance(&ici, nullptr, &ctx->m_instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
        return makeError(ErrorCode::NoDevice,
                         std::string("no Vulkan driver could be loaded (") + vkResultName(r) +
                             "); install mesa-vulkan-drivers for the lavapipe CPU device");
    if (r != VK_SUCCESS) return vkError(r, "vkCreateInstance");

    if (debugUtils) {
        auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->m_instance, "vkCreateDebugUtilsMessengerEXT"));
        messengerInfo.pNext = nullptr;
        if (createMessenger)
            LANTERN_VK_TRY(createMessenger(ctx->m_instance, &messengerInfo, nullptr,
                                           &ctx->m_messenger));
        ctx->m_setObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(ctx->m_instance, "vkSetDebugUtilsObjectNameEXT"));
        ctx->m_caps.debugUtils = true;
    }

    // Physical device.
    std::uint32_t nd = 0;
    r = vkEnumeratePhysicalDevices(ctx->m_instance, &nd, nullptr);
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) return vkError(r, "vkEnumeratePhysicalDevices");
    if (nd == 0)
        return makeError(ErrorCode::NoDevice,
                         "no Vulkan device found; install mesa-vulkan-drivers for the lavapipe "
                         "CPU device, or a GPU driver");
    std::vector<VkPhysicalDevice> devices(nd);
    vkEnumeratePhysicalDevices(ctx->m_instance, &nd, devices.data());

    std::vector<Candidate> candidates;
    for (VkPhysicalDevice pd : devices) candidates.push_back(examine(pd, desc.swapchain));
    const std::string wanted = lower(desc.deviceName);
    const Candidate* chosen = nullptr;
    for (const Candidate& c : candidates) {
        if (!c.rejection.empty()) continue;
        if (!wanted.empty() && lower(c.props.deviceName).find(wanted) == std::string::npos)
            continue;
        if (!chosen || typeRank(c.props.deviceType) < typeRank(chosen->props.deviceType))
            chosen = &c;
    }
    if (!chosen) {
        std::ostringstream msg;
        msg << (wanted.empty() ? "no usable Vulkan device"
                               : "no usable Vulkan device matches \"" + desc.deviceName + "\"")
            << "; devices present:";
        for (const Candidate& c : candidates)
            msg << " [" << c.props.deviceName << " (" << typeName(c.props.deviceType) << ")"
                << (c.rejection.empty() ? "" : ": " + c.rejection) << "]";
        return makeError(ErrorCode::NoDevice, msg.str());
    }
    ctx->m_physical = chosen->device;
    ctx->m_queueFamily = chosen->queueFamily;

    // Optional features.
    const auto exts = deviceExtensions(ctx->m_physical);
    VkPhysicalDeviceProvokingVertexFeaturesEXT provoking{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT};
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    const bool haveProvoking = hasExtension(exts, VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME);
    if (haveProvoking) f13.pNext = &provoking;
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13, {}};
    vkGetPhysicalDeviceFeatures2(ctx->m_physical, &supported);

    VkPhysicalDeviceFeatures core{};
    core.fillModeNonSolid = supported.features.fillModeNonSolid;
    core.wideLines = supported.features.wideLines;
    core.shaderFloat64 = supported.features.shaderFloat64;
    core.independentBlend = supported.features.independentBlend;
    // The id AOV reads gl_PrimitiveID in fragment shaders: SPIR-V's Geometry capability.
    core.geometryShader = supported.features.geometryShader;
    ctx->m_caps.primitiveIdInFragment = core.geometryShader;
    ctx->m_caps.fillModeNonSolid = core.fillModeNonSolid;
    ctx->m_caps.wideLines = core.wideLines;
    ctx->m_caps.shaderFloat64 = core.shaderFloat64;
    ctx->m_caps.provokingVertexLast = haveProvoking && provoking.provokingVertexLast;

    VkPhysicalDeviceVulkan13Features enable13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    enable13.dynamicRendering = VK_TRUE;
    enable13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceProvokingVertexFeaturesEXT enableProvoking{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT};
    enableProvoking.provokingVertexLast = VK_TRUE;
    std::vector<const char*> devExts;
    if (ctx->m_caps.provokingVertexLast) {
        enable13.pNext = &enableProvoking;
        devExts.push_back(VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME);
    }
    if (desc.swapchain) devExts.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &enable13, core};

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = ctx->m_queueFamily;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = std::uint32_t(devExts.size());
    dci.ppEnabledExtensionNames = devExts.data();
    LANTERN_VK_TRY(vkCreateDevice(ctx->m_physical, &dci, nullptr, &ctx->m_device));
    vkGetDeviceQueue(ctx->m_device, ctx->m_queueFamily, 0, &ctx->m_queue);
    LANTERN_TRY(ctx->finishSetup());
    return ctx;
}

namespace {

// The features a host enabled on its device, gathered from what it gave vkCreateDevice.
struct EnabledFeatures {
    VkPhysicalDeviceFeatures core{};
    bool dynamicRendering = false;
    bool synchronization2 = false;
    bool provokingVertexLast = false;
};

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

} // namespace

Result<std::shared_ptr<Context>> Context::adopt(const ExternalDevice& e, bool swapchain,
                                                LogSink log) {
    armFaultsFromEnvironment();
#if defined(LANTERN_ASAN)
    core::pinVulkanLibraries();
#endif
    const std::pair<const char*, bool> handles[] = {{"instance", e.instance != VK_NULL_HANDLE},
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
    const auto enabled = [&](const char* name) {
        return std::find(e.enabledExtensions.begin(), e.enabledExtensions.end(), name) !=
               e.enabledExtensions.end();
    };
    if (swapchain && !enabled(VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        return makeError(ErrorCode::Unsupported,
                         "RendererDesc::presentation needs VK_KHR_swapchain enabled on the device",
                         "ExternalDevice.enabledExtensions");

    std::shared_ptr<Context> ctx(new Context());
    ctx->m_log = std::move(log);
    ctx->m_external = true;
    ctx->m_instance = e.instance;
    ctx->m_physical = e.physicalDevice;
    ctx->m_device = e.device;
    ctx->m_queue = e.queue;
    ctx->m_queueFamily = e.queueFamily;
    if (e.queueMutex) ctx->m_queueLock = e.queueMutex;
    // Optional capabilities are what the host enabled, not what the device could do.
    ctx->m_caps.primitiveIdInFragment = f.core.geometryShader && f.core.independentBlend;
    ctx->m_caps.fillModeNonSolid = f.core.fillModeNonSolid;
    ctx->m_caps.wideLines = f.core.wideLines;
    ctx->m_caps.shaderFloat64 = f.core.shaderFloat64;
    ctx->m_caps.provokingVertexLast =
        f.provokingVertexLast && enabled(VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME);
    LANTERN_TRY(ctx->finishSetup());
    return ctx;
}

Result<void> Context::finishSetup() {
    vkGetPhysicalDeviceProperties(m_physical, &m_properties);
    vkGetPhysicalDeviceMemoryProperties(m_physical, &m_memory);
    VkPhysicalDeviceVulkan12Properties p12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p12, {}};
    vkGetPhysicalDeviceProperties2(m_physical, &props2);
    m_driverInfo = std::string(p12.driverName) + " " + p12.driverInfo;
    const auto& lim = m_properties.limits;
    // The integer AOV attachments are never multisampled (the AOV pass is single-sampled), so
    // only float colour and depth bound the sample counts.
    m_caps.colorDepthSampleCounts =
        lim.framebufferColorSampleCounts & lim.framebufferDepthSampleCounts;

    VkPipelineCacheCreateInfo pcci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    VkPipelineCache cache = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreatePipelineCache(m_device, &pcci, nullptr, &cache));
    m_pipelineCache = UniquePipelineCache(m_device, cache);

    VkCommandPoolCreateInfo cpci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cpci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    cpci.queueFamilyIndex = m_queueFamily;
    VkCommandPool pool = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateCommandPool(m_device, &cpci, nullptr, &pool));
    m_oneShotPool = UniqueCommandPool(m_device, pool);

    log(LogLevel::Info, std::string("device: ") + m_properties.deviceName + " (" +
                            typeName(m_properties.deviceType) + ", " + m_driverInfo + ")" +
                            (m_external ? ", the host's" : "") +
                            (m_validation ? ", validation on" : ""));
    return {};
}

void Context::waitIdle() {
    if (!m_device) return;
    if (!m_external) {
        vkDeviceWaitIdle(m_device);
        return;
    }
    std::lock_guard lock(*m_queueLock);
    vkQueueWaitIdle(m_queue);
}

Context::~Context() {
    waitIdle();
    m_oneShotPool.reset();
    m_pipelineCache.reset();
    if (m_external) return;  // the host's instance and device: never destroyed here
    if (m_device) vkDestroyDevice(m_device, nullptr);
    if (m_messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(m_instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(m_instance, m_messenger, nullptr);
    }
    if (m_instance) vkDestroyInstance(m_instance, nullptr);
}

int Context::findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred) const {
    int fallback = -1;
    for (std::uint32_t i = 0; i < m_memory.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        const VkMemoryPropertyFlags f = m_memory.memoryTypes[i].propertyFlags;
        if ((f & required) != required) continue;
        if ((f & preferred) == preferred) return int(i);
        if (fallback < 0) fallback = int(i);
    }
    return fallback;
}

Result<void> Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
    std::lock_guard lock(m_oneShotMutex);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = m_oneShotPool.get();
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkAllocateCommandBuffers(m_device, &ai, &cmd));
    struct Free {
        VkDevice d;
        VkCommandPool p;
        VkCommandBuffer c;
        ~Free() { vkFreeCommandBuffers(d, p, 1, &c); }
    } freeLater{m_device, m_oneShotPool.get(), cmd};

    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    LANTERN_VK_TRY(vkBeginCommandBuffer(cmd, &bi));
    record(cmd);
    LANTERN_VK_TRY(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateFence(m_device, &fci, nullptr, &fence));
    UniqueFence fenceOwner(m_device, fence);
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = cmd;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cbi;
    {
        std::lock_guard qlock(*m_queueLock);
        LANTERN_VK_TRY(vkQueueSubmit2(m_queue, 1, &si, fence));
    }
    LANTERN_VK_TRY(vkWaitForFences(m_device, 1, &fence, VK_TRUE, UINT64_MAX));
    return {};
}

void Context::setName(VkObjectType type, std::uint64_t handle, const std::string& name) const {
    if (!m_setObjectName || handle == 0) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    m_setObjectName(m_device, &info);
}

} // namespace lantern::gpu
