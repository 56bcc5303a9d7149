// Context: the Vulkan instance (with the validation layer and a debug messenger when asked and
// installed), the chosen physical device, the logical device, its graphics queue, the pipeline
// cache (loaded from disk and written back when the context goes, gpu/PipelineCache.h) and
// helpers for one-off submissions. Shared (std::shared_ptr) by everything that owns
// device objects, so the device outlives them whatever order a host destroys things in.
// Either Lantern creates and owns the instance and device (create), or the host lends its own
// (adopt): then they are checked, used and never destroyed.
#pragma once

#include "gpu/Handles.h"
#include "gpu/PipelineCache.h"
#include "gpu/Vk.h"

#include <lantern/ExternalDevice.h>
#include <lantern/Log.h>
#include <lantern/Result.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lantern::gpu {

struct ContextDesc {
    std::string deviceName;  ///< an index or a name substring; empty: LANTERN_DEVICE, else best
    bool validation = false;
    bool synchronizationValidation = false;
    std::vector<std::string> instanceExtensions;  ///< e.g. surface extensions for a window
    bool swapchain = false;                       ///< enable VK_KHR_swapchain on the device
    PipelineCacheSettings pipelineCache;          ///< kept on disk between runs, and where
    LogSink log;
};

/// Optional capabilities the device turned out to have.
struct Capabilities {
    bool provokingVertexLast = false;  ///< VK_EXT_provoking_vertex (GL-compatible flat)
    bool shaderFloat64 = false;
    bool primitiveIdInFragment = false;  ///< geometryShader feature: the AOV ids need it
    bool fillModeNonSolid = false;     ///< wireframe
    bool wideLines = false;            ///< lines wider than one pixel
    bool largePoints = false;          ///< points larger than one pixel
    bool debugUtils = false;           ///< object names and the messenger
    /// vertexPipelineStoresAndAtomics: the guarded vertex variants (shaders/include/guard.glsl)
    bool vertexStores = false;
    /// fragmentStoresAndAtomics: exact transparency's fragment lists (shaders/include/oit.glsl)
    bool fragmentStores = false;
    /// independentBlend: weighted transparency's two attachments blend differently
    bool independentBlend = false;
    /// multiDrawIndirect and drawIndirectCount: the clusters' indirect draws (gpu/Clusters.h)
    bool multiDrawIndirect = false;
    std::uint32_t colorDepthSampleCounts = VK_SAMPLE_COUNT_1_BIT;  ///< float colour & depth
};

class Context {
public:
    static Result<std::shared_ptr<Context>> create(const ContextDesc& desc);
    /// A context on the host's objects (lantern/ExternalDevice.h): checks that the device has
    /// what Lantern needs (Unsupported or Usage naming what is missing) and never destroys
    /// them. `swapchain`: presentation was asked for (VK_KHR_swapchain must be enabled).
    static Result<std::shared_ptr<Context>> adopt(const ExternalDevice& external, bool swapchain,
                                                  const PipelineCacheSettings& pipelineCache,
                                                  LogSink log);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return m_instance; }
    VkPhysicalDevice physicalDevice() const { return m_physical; }
    VkDevice device() const { return m_device; }
    VkQueue queue() const { return m_queue; }
    std::uint32_t queueFamily() const { return m_queueFamily; }
    VkPipelineCache pipelineCache() const { return m_pipelineCache.get(); }
    /// The cache's file and what was loaded from it.
    const PipelineCache& diskCache() const { return m_pipelineCache; }
    /// Writes the pipeline cache to its file now if it changed (also done on destruction).
    bool savePipelineCache() { return m_pipelineCache.save(m_device, m_log); }
    const VkPhysicalDeviceProperties& properties() const { return m_properties; }
    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return m_memory; }
    /// The largest single allocation the device accepts (Vulkan 1.1 maxMemoryAllocationSize).
    VkDeviceSize maxAllocation() const { return m_maxAllocation; }
    /// The size of the largest device-local memory heap (0: none reported), what the
    /// memory checks of targets, shadow maps and transparency lists measure against.
    VkDeviceSize largestDeviceLocalHeap() const {
        VkDeviceSize heap = 0;
        for (std::uint32_t i = 0; i < m_memory.memoryHeapCount; ++i)
            if (m_memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
                heap = std::max(heap, m_memory.memoryHeaps[i].size);
        return heap;
    }
    const Capabilities& capabilities() const { return m_caps; }
    bool validationEnabled() const { return m_validation; }
    /// True when the instance and device are the host's (adopt()).
    bool external() const { return m_external; }
    std::string driverInfo() const { return m_driverInfo; }

    /// A memory type index with all `required` flags among `typeBits`, preferring one that
    /// also has `preferred`; -1 when none.
    int findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                       VkMemoryPropertyFlags preferred = 0) const;

    /// Waits until Lantern's work on the device is done: vkDeviceWaitIdle on a device Lantern
    /// owns; on the host's device only the queue Lantern uses (under the queue lock), so the
    /// host's other queues are neither waited for nor raced.
    void waitIdle();

    /// Records `record` into a fresh command buffer, submits it and waits for it.
    Result<void> submitAndWait(const std::function<void(VkCommandBuffer)>& record);

    /// Names a Vulkan object for validation messages and debuggers (no-op without debug utils).
    void setName(VkObjectType type, std::uint64_t handle, const std::string& name) const;
    template <typename T>
    void setName(VkObjectType type, T handle, const std::string& name) const {
        setName(type, reinterpret_cast<std::uint64_t>(handle), name);
    }

    void log(LogLevel level, const std::string& message) const {
        if (m_log) m_log(level, message);
    }
    std::uint64_t validationMessageCount() const { return m_validationMessages.load(); }
    /// Bytes of device memory Lantern's buffers and images hold now (CountedBytes).
    std::uint64_t deviceBytes() const { return m_deviceBytes.load(); }
    std::atomic<std::uint64_t>& deviceBytesCounter() { return m_deviceBytes; }

    /// Queue submissions must be externally synchronised (one queue, many users).
    std::mutex& queueMutex() { return *m_queueLock; }

private:
    Context() = default;
    // The steps of create(): the instance (and messenger), then, once the physical device is
    // chosen, the optional features it offers (filling m_caps) and the device with its queue.
    Result<void> createInstance(const ContextDesc& desc);
    Result<void> createMessenger(VkDebugUtilsMessengerCreateInfoEXT messengerInfo);
    VkPhysicalDeviceFeatures readOptionalFeatures();
    Result<void> createDevice(const VkPhysicalDeviceFeatures& core, bool swapchain);
    Result<void> finishSetup(const PipelineCacheSettings& pipelineCache);
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    LogSink m_log;
    VkInstance m_instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT m_messenger = VK_NULL_HANDLE;
    VkPhysicalDevice m_physical = VK_NULL_HANDLE;
    VkDevice m_device = VK_NULL_HANDLE;
    VkQueue m_queue = VK_NULL_HANDLE;
    std::uint32_t m_queueFamily = 0;
    VkPhysicalDeviceProperties m_properties{};
    VkPhysicalDeviceMemoryProperties m_memory{};
    Capabilities m_caps;
    bool m_validation = false;
    bool m_external = false;
    std::string m_driverInfo;
    VkDeviceSize m_maxAllocation = 0;
    PipelineCache m_pipelineCache;
    UniqueCommandPool m_oneShotPool;
    std::mutex m_oneShotMutex;
    std::mutex m_queueMutex;
    std::mutex* m_queueLock = &m_queueMutex;  ///< m_queueMutex, or the host's
    std::atomic<std::uint64_t> m_validationMessages{0};
    std::atomic<std::uint64_t> m_deviceBytes{0};
    PFN_vkSetDebugUtilsObjectNameEXT m_setObjectName = nullptr;
};

} // namespace lantern::gpu
