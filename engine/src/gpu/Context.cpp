// Context: the instance and validation messenger, the logical device with the optional
// features it offers, adopting a host's device, and one-off submissions. The choice and checks
// of the physical device are in DeviceSelection.cpp.
#include "gpu/Context.h"

#include "gpu/DeviceSelection.h"
#include "gpu/DriverReport.h"

#if defined(LANTERN_ASAN)
#include "core/SanitizerSupport.h"
#endif

#include <algorithm>
#include <cstring>
#include <utility>

namespace lantern::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

Result<void> checkLoaderVersion() {
    std::uint32_t loaderVersion = 0;
    if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS ||
        loaderVersion < VK_API_VERSION_1_3)
        return makeError(ErrorCode::NoDevice,
                         "the Vulkan loader does not support Vulkan 1.3 (install libvulkan1 "
                         "from Debian 12 or newer)");
    return {};
}

bool validationLayerInstalled() {
    std::uint32_t nl = 0;
    vkEnumerateInstanceLayerProperties(&nl, nullptr);
    std::vector<VkLayerProperties> layers(nl);
    vkEnumerateInstanceLayerProperties(&nl, layers.data());
    return std::any_of(layers.begin(), layers.end(), [](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, kValidationLayer) == 0;
    });
}

std::vector<VkExtensionProperties> instanceExtensionProperties() {
    std::uint32_t ne = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &ne, nullptr);
    std::vector<VkExtensionProperties> instExts(ne);
    vkEnumerateInstanceExtensionProperties(nullptr, &ne, instExts.data());
    return instExts;
}

VkDebugUtilsMessengerCreateInfoEXT
messengerCreateInfo(PFN_vkDebugUtilsMessengerCallbackEXT callback, void* user) {
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = callback;
    messengerInfo.pUserData = user;
    return messengerInfo;
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
    LANTERN_TRY(ctx->createInstance(desc));
    const DeviceRequest request = deviceRequest(desc.deviceName);
    Result<ChosenDevice> chosen = choosePhysicalDevice(ctx->m_instance, request, desc.swapchain);
    if (!chosen) return std::move(chosen).error();
    if (!request.text.empty()) ctx->log(LogLevel::Info, "device chosen by " + request.label);
    ctx->m_physical = chosen->device;
    ctx->m_queueFamily = chosen->queueFamily;
    const VkPhysicalDeviceFeatures core = ctx->readOptionalFeatures();
    LANTERN_TRY(ctx->createDevice(core, desc.swapchain));
    LANTERN_TRY(ctx->finishSetup(desc.pipelineCache));
    return ctx;
}

Result<void> Context::createInstance(const ContextDesc& desc) {
    LANTERN_TRY(checkLoaderVersion());

    // Layers and instance extensions.
    const bool wantValidation = desc.validation || desc.synchronizationValidation;
    const bool haveValidation = validationLayerInstalled();
    if (wantValidation && !haveValidation)
        log(LogLevel::Warning, "validation requested but VK_LAYER_KHRONOS_validation is not "
                               "installed (Debian package vulkan-validationlayers)");
    m_validation = wantValidation && haveValidation;

    const std::vector<VkExtensionProperties> instExts = instanceExtensionProperties();
    std::vector<const char*> extensions;
    for (const auto& e : desc.instanceExtensions) {
        if (!hasExtension(instExts, e.c_str()))
            return makeError(ErrorCode::Unsupported, "instance extension " + e + " is missing");
        extensions.push_back(e.c_str());
    }
    const bool debugUtils =
        m_validation && hasExtension(instExts, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    std::vector<const char*> enabledLayers;
    if (m_validation) enabledLayers.push_back(kValidationLayer);

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "lantern";
    app.pEngineName = "Lantern";
    app.apiVersion = VK_API_VERSION_1_3;

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo =
        messengerCreateInfo(&Context::debugCallback, this);
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
    const VkResult r = vkCreateInstance(&ici, nullptr, &m_instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
        return makeError(ErrorCode::NoDevice,
                         noDeviceMessage(std::string("no Vulkan driver could be loaded "
                                                     "(vkCreateInstance: ") +
                                         vkResultName(r) + ")"));
    if (r != VK_SUCCESS) return vkError(r, "vkCreateInstance");
    if (debugUtils) LANTERN_TRY(createMessenger(messengerInfo));
    return {};
}

Result<void> Context::createMessenger(VkDebugUtilsMessengerCreateInfoEXT messengerInfo) {
    auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(m_instance, "vkCreateDebugUtilsMessengerEXT"));
    messengerInfo.pNext = nullptr;
    if (createMessenger)
        LANTERN_VK_TRY(createMessenger(m_instance, &messengerInfo, nullptr, &m_messenger));
    m_setObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(m_instance, "vkSetDebugUtilsObjectNameEXT"));
    m_caps.debugUtils = true;
    return {};
}

VkPhysicalDeviceFeatures Context::readOptionalFeatures() {
    const auto exts = deviceExtensions(m_physical);
    VkPhysicalDeviceProvokingVertexFeaturesEXT provoking{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT};
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    const bool haveProvoking = hasExtension(exts, VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME);
    if (haveProvoking) f13.pNext = &provoking;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12, {}};
    vkGetPhysicalDeviceFeatures2(m_physical, &supported);

    VkPhysicalDeviceFeatures core{};
    core.fillModeNonSolid = supported.features.fillModeNonSolid;
    core.wideLines = supported.features.wideLines;
    core.largePoints = supported.features.largePoints;
    core.shaderFloat64 = supported.features.shaderFloat64;
    core.independentBlend = supported.features.independentBlend;
    // The id AOV reads gl_PrimitiveID in fragment shaders: SPIR-V's Geometry capability.
    core.geometryShader = supported.features.geometryShader;
    core.vertexPipelineStoresAndAtomics = supported.features.vertexPipelineStoresAndAtomics;
    core.fragmentStoresAndAtomics = supported.features.fragmentStoresAndAtomics;
    core.multiDrawIndirect = supported.features.multiDrawIndirect;
    // The clusters' indirect draws name their instance (an instanced draw's records).
    core.drawIndirectFirstInstance = supported.features.drawIndirectFirstInstance;
    m_caps.fragmentStores = core.fragmentStoresAndAtomics;
    // Capabilities::multiDrawIndirect stands for the three features the clusters' draws use.
    m_caps.multiDrawIndirect = core.multiDrawIndirect && core.drawIndirectFirstInstance && f12.drawIndirectCount;
    m_caps.independentBlend = core.independentBlend;
    m_caps.primitiveIdInFragment = core.geometryShader;
    m_caps.vertexStores = core.vertexPipelineStoresAndAtomics;
    m_caps.fillModeNonSolid = core.fillModeNonSolid;
    m_caps.wideLines = core.wideLines;
    m_caps.largePoints = core.largePoints;
    m_caps.shaderFloat64 = core.shaderFloat64;
    m_caps.provokingVertexLast = haveProvoking && provoking.provokingVertexLast;
    return core;
}

Result<void> Context::createDevice(const VkPhysicalDeviceFeatures& core, bool swapchain) {
    VkPhysicalDeviceVulkan13Features enable13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    enable13.dynamicRendering = VK_TRUE;
    enable13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceProvokingVertexFeaturesEXT enableProvoking{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT};
    enableProvoking.provokingVertexLast = VK_TRUE;
    std::vector<const char*> devExts;
    if (m_caps.provokingVertexLast) {
        enable13.pNext = &enableProvoking;
        devExts.push_back(VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME);
    }
    if (swapchain) devExts.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &enable13};
    enable12.drawIndirectCount = m_caps.multiDrawIndirect ? VK_TRUE : VK_FALSE;
    VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &enable12, core};

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = m_queueFamily;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = std::uint32_t(devExts.size());
    dci.ppEnabledExtensionNames = devExts.data();
    LANTERN_VK_TRY(vkCreateDevice(m_physical, &dci, nullptr, &m_device));
    vkGetDeviceQueue(m_device, m_queueFamily, 0, &m_queue);
    return {};
}

Result<std::shared_ptr<Context>> Context::adopt(const ExternalDevice& e, bool swapchain,
                                                const PipelineCacheSettings& pipelineCache,
                                                LogSink log) {
    armFaultsFromEnvironment();
#if defined(LANTERN_ASAN)
    core::pinVulkanLibraries();
#endif
    Result<EnabledFeatures> checked = checkExternalDevice(e, swapchain);
    if (!checked) return std::move(checked).error();
    const EnabledFeatures& f = *checked;

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
    ctx->m_caps.largePoints = f.core.largePoints;
    ctx->m_caps.shaderFloat64 = f.core.shaderFloat64;
    ctx->m_caps.vertexStores = f.core.vertexPipelineStoresAndAtomics;
    ctx->m_caps.fragmentStores = f.core.fragmentStoresAndAtomics;
    ctx->m_caps.independentBlend = f.core.independentBlend;
    // The clusters' draws need drawIndirectCount too, which the host's device need not have
    // enabled: an adopted device draws every cluster.
    ctx->m_caps.multiDrawIndirect = false;
    ctx->m_caps.provokingVertexLast =
        f.provokingVertexLast && extensionEnabled(e, VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME);
    LANTERN_TRY(ctx->finishSetup(pipelineCache));
    return ctx;
}

Result<void> Context::finishSetup(const PipelineCacheSettings& pipelineCache) {
    vkGetPhysicalDeviceProperties(m_physical, &m_properties);
    vkGetPhysicalDeviceMemoryProperties(m_physical, &m_memory);
    VkPhysicalDeviceVulkan12Properties p12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
    VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES,
                                           &p12};
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p11, {}};
    vkGetPhysicalDeviceProperties2(m_physical, &props2);
    m_driverInfo = std::string(p12.driverName) + " " + p12.driverInfo;
    m_maxAllocation = p11.maxMemoryAllocationSize;
    const auto& lim = m_properties.limits;
    // The integer AOV attachments are never multisampled (the AOV pass is single-sampled), so
    // only float colour and depth bound the sample counts.
    m_caps.colorDepthSampleCounts =
        lim.framebufferColorSampleCounts & lim.framebufferDepthSampleCounts;

    auto cache = PipelineCache::create(m_device, m_properties, pipelineCache, m_log);
    if (!cache) return std::move(cache).error();
    m_pipelineCache = std::move(*cache);

    VkCommandPoolCreateInfo cpci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cpci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    cpci.queueFamilyIndex = m_queueFamily;
    VkCommandPool pool = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateCommandPool(m_device, &cpci, nullptr, &pool));
    m_oneShotPool = UniqueCommandPool(m_device, pool);

    log(LogLevel::Info, std::string("device: ") + m_properties.deviceName + " (" +
                            deviceTypeName(m_properties.deviceType) + ", " + m_driverInfo + ")" +
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
    // Every pipeline this context compiled is in the cache by now: keep them for the next run.
    savePipelineCache();
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
