// Renderer::create(ExternalDevice): a renderer on a VkInstance/VkDevice/queue the test creates
// itself, as a host would (validation layer on, with its own messenger): the picture equals
// the one from Lantern's own device, the host's device survives the renderer and is
// destroyed by the host without a validation message (a leaked Lantern object would show),
// the host may submit to the shared queue from another thread under its queue mutex, and
// devices Lantern cannot use are refused with the reason.
#include "TestSupport.h"

#include <lantern/ExternalDevice.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

struct HostOptions {
    bool synchronization2 = true;
    bool device = true;  ///< false: an instance and a physical device only
};

/// What a host application owns: an instance (validation layer and messenger when the layer
/// is installed, as GpuTest's renderer has), a device on the same physical device as the
/// shared test renderer, and one graphics queue. Counts validation warnings and errors.
class HostVulkan {
public:
    static std::unique_ptr<HostVulkan> create(const HostOptions& options, std::string& failure) {
        std::unique_ptr<HostVulkan> h(new HostVulkan());
        failure = h->init(options);
        if (!failure.empty()) return nullptr;
        return h;
    }
    ~HostVulkan() {
        destroyDevice();
        if (m_messenger) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
            destroy(instance, m_messenger, nullptr);
        }
        if (instance) vkDestroyInstance(instance, nullptr);
    }
    HostVulkan(const HostVulkan&) = delete;
    HostVulkan& operator=(const HostVulkan&) = delete;

    /// The host's part: after every Lantern object on the device is gone.
    void destroyDevice() {
        if (device) vkDestroyDevice(device, nullptr);
        device = VK_NULL_HANDLE;
        queue = VK_NULL_HANDLE;
    }

    ExternalDevice external() {
        ExternalDevice e;
        e.instance = instance;
        e.instanceApiVersion = VK_API_VERSION_1_3;
        e.physicalDevice = physical;
        e.device = device;
        e.queueFamily = family;
        e.queue = queue;
        e.enabledFeatures = &m_features;
        e.enabledExtensions = m_extensions;
        return e;
    }

    std::uint64_t messages() const { return m_messages.load(); }
    bool validated() const { return m_messenger != VK_NULL_HANDLE; }

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;

private:
    HostVulkan() = default;

    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
        if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
        static_cast<HostVulkan*>(user)->m_messages.fetch_add(1);
        std::cerr << "[host validation] " << (data && data->pMessage ? data->pMessage : "") << "\n";
        return VK_FALSE;
    }

    std::string init(const HostOptions& options) {
        std::uint32_t n = 0;
        vkEnumerateInstanceLayerProperties(&n, nullptr);
        std::vector<VkLayerProperties> layers(n);
        vkEnumerateInstanceLayerProperties(&n, layers.data());
        bool validation = false;
        for (const auto& l : layers) validation |= std::strcmp(l.layerName, kValidationLayer) == 0;

        VkDebugUtilsMessengerCreateInfoEXT mci{
            VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
        mci.pfnUserCallback = &HostVulkan::onMessage;
        mci.pUserData = this;

        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "lantern external-device test";
        app.apiVersion = VK_API_VERSION_1_3;
        const char* layer = kValidationLayer;
        const char* debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ici.pApplicationInfo = &app;
        if (validation) {
            ici.pNext = &mci;
            ici.enabledLayerCount = 1;
            ici.ppEnabledLayerNames = &layer;
            ici.enabledExtensionCount = 1;
            ici.ppEnabledExtensionNames = &debugUtils;
        }
        if (vkCreateInstance(&ici, nullptr, &instance) != VK_SUCCESS)
            return "vkCreateInstance failed";
        if (validation) {
            auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
            if (createMessenger(instance, &mci, nullptr, &m_messenger) != VK_SUCCESS)
                return "vkCreateDebugUtilsMessengerEXT failed";
        }

        // The shared test renderer's device, so that the pictures can be compared.
        const std::string wanted = test::sharedRenderer()->device().name;
        vkEnumeratePhysicalDevices(instance, &n, nullptr);
        std::vector<VkPhysicalDevice> devices(n);
        vkEnumeratePhysicalDevices(instance, &n, devices.data());
        for (VkPhysicalDevice pd : devices) {
            VkPhysicalDeviceProperties p{};
            vkGetPhysicalDeviceProperties(pd, &p);
            if (wanted == p.deviceName) physical = pd;
        }
        if (!physical) return "no physical device named " + wanted;
        if (!options.device) return {};

        vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, nullptr);
        std::vector<VkQueueFamilyProperties> families(n);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, families.data());
        while (family < n && !(families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++family;
        if (family == n) return "no graphics queue";

        // The optional features Lantern's own device enables, so that both render alike.
        VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        vkGetPhysicalDeviceFeatures2(physical, &supported);
        m_features.features.geometryShader = supported.features.geometryShader;
        m_features.features.independentBlend = supported.features.independentBlend;
        m_features.features.fillModeNonSolid = supported.features.fillModeNonSolid;
        m_features.features.wideLines = supported.features.wideLines;
        m_features.features.shaderFloat64 = supported.features.shaderFloat64;
        m_features.pNext = &m_features13;
        m_features13.dynamicRendering = VK_TRUE;
        m_features13.synchronization2 = options.synchronization2 ? VK_TRUE : VK_FALSE;

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = family;
        qci.queueCount = 1;
        qci.pQueuePriorities = &priority;
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &m_features};
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        if (vkCreateDevice(physical, &dci, nullptr, &device) != VK_SUCCESS)
            return "vkCreateDevice failed";
        vkGetDeviceQueue(device, family, 0, &queue);
        return {};
    }

    VkDebugUtilsMessengerEXT m_messenger = VK_NULL_HANDLE;
    VkPhysicalDeviceVulkan13Features m_features13{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 m_features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    std::vector<std::string> m_extensions;
    std::atomic<std::uint64_t> m_messages{0};
};

RendererDesc loggingDesc() {
    RendererDesc desc;
    desc.log = [](LogLevel level, std::string_view message) {
        if (level >= LogLevel::Warning) std::cerr << "[lantern] " << message << "\n";
    };
    return desc;
}

RenderOptions small() {
    RenderOptions o;
    o.width = 64;
    o.height = 64;
    return o;
}

class ExternalDevice_ : public GpuTest {
protected:
    std::unique_ptr<HostVulkan> host(const HostOptions& options = {}) {
        std::string failure;
        auto h = HostVulkan::create(options, failure);
        EXPECT_TRUE(h) << "the host's own Vulkan setup failed: " << failure;
        if (h && !h->validated())
            std::cerr << "note: VK_LAYER_KHRONOS_validation is not installed; the host's "
                         "device is not validated\n";
        return h;
    }

    /// A host device, the spheres, and their picture at `time` from Lantern's own device.
    struct Setup {
        std::unique_ptr<HostVulkan> host;
        Scene scene;
        Image expected;
    };
    std::optional<Setup> setUp(double time) {
        Setup s;
        s.host = host();
        auto scene = builtinScene("spheres");
        if (!s.host || !scene) return std::nullopt;
        s.scene = std::move(*scene);
        auto expected = renderer().render(s.scene, small(), time);
        EXPECT_TRUE(expected) << expected.error().describe();
        if (!expected) return std::nullopt;
        s.expected = std::move(*expected);
        return s;
    }
};

TEST_F(ExternalDevice_, RendersWhatItsOwnDeviceRenders) {
    auto setup = setUp(0.5);
    ASSERT_TRUE(setup);
    auto& h = setup->host;
    const Scene* scene = &setup->scene;
    const Image* expected = &setup->expected;
    {
        auto r = Renderer::create(h->external(), loggingDesc());
        ASSERT_TRUE(r) << r.error().describe();
        EXPECT_EQ(r->device().name, renderer().device().name);
        EXPECT_FALSE(r->device().validationEnabled) << "validation is the host's business";

        auto once = r->render(*scene, small(), 0.5);
        ASSERT_TRUE(once) << once.error().describe();
        EXPECT_LE(test::maxAbsDifference(*once, *expected), 1.0f / 255.0f)
            << test::saveComparison(*once, *expected, "external-vs-own");
        EXPECT_GT(test::countCovered(*once), once->pixelCount() / 8) << "nothing was drawn";

        auto prepared = r->prepare(std::make_shared<const Scene>(*scene));
        ASSERT_TRUE(prepared) << prepared.error().describe();
        for (int frame = 0; frame < 3; ++frame) {
            auto img = r->render(*prepared, small(), 0.5);
            ASSERT_TRUE(img) << img.error().describe();
            EXPECT_LE(test::maxAbsDifference(*img, *expected), 1.0f / 255.0f);
        }
    }  // the renderer and its prepared scene are gone: Lantern's objects must be too

    // The host's device is still the host's: it can use it, then destroy it. The validation
    // layer reports any object Lantern left on it at vkDestroyDevice.
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateFence(h->device, &fci, nullptr, &fence), VK_SUCCESS);
    ASSERT_EQ(vkQueueSubmit(h->queue, 0, nullptr, fence), VK_SUCCESS);
    EXPECT_EQ(vkWaitForFences(h->device, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
    vkDestroyFence(h->device, fence, nullptr);
    h->destroyDevice();
    EXPECT_EQ(h->messages(), 0u) << "validation messages on the host's instance (see stderr)";
}

TEST_F(ExternalDevice_, SharesTheQueueWithAHostThreadUnderItsMutex) {
    auto setup = setUp(0.0);
    ASSERT_TRUE(setup);
    auto& h = setup->host;
    const Scene* scene = &setup->scene;
    const Image* expected = &setup->expected;

    std::mutex queueMutex;
    std::atomic<bool> stop{false};
    std::atomic<int> hostSubmits{0};
    // The host keeps submitting to the same queue (empty batches with a fence) while Lantern
    // renders and while its renderer is destroyed. Vulkan requires the queue to be externally
    // synchronised; the validation layer's thread-safety checks report a race.
    std::thread hostThread([&] {
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence fence = VK_NULL_HANDLE;
        if (vkCreateFence(h->device, &fci, nullptr, &fence) != VK_SUCCESS) return;
        while (!stop.load()) {
            {
                std::lock_guard lock(queueMutex);
                if (vkQueueSubmit(h->queue, 0, nullptr, fence) != VK_SUCCESS) break;
            }
            vkWaitForFences(h->device, 1, &fence, VK_TRUE, UINT64_MAX);
            vkResetFences(h->device, 1, &fence);
            hostSubmits.fetch_add(1);
        }
        vkDestroyFence(h->device, fence, nullptr);
    });
    {
        ExternalDevice e = h->external();
        e.queueMutex = &queueMutex;
        auto r = Renderer::create(e, loggingDesc());
        ASSERT_TRUE(r) << r.error().describe();
        for (int frame = 0; frame < 3; ++frame) {
            auto img = r->render(*scene, small(), 0.0);
            ASSERT_TRUE(img) << img.error().describe();
            EXPECT_LE(test::maxAbsDifference(*img, *expected), 1.0f / 255.0f);
        }
    }
    stop = true;
    hostThread.join();
    EXPECT_GT(hostSubmits.load(), 0) << "the host thread never submitted";
    h->destroyDevice();
    EXPECT_EQ(h->messages(), 0u) << "validation messages on the host's instance (see stderr)";
}

TEST_F(ExternalDevice_, RefusesDevicesItCannotUse) {
    std::string failure;
    HostOptions instanceOnly;
    instanceOnly.device = false;
    auto other = HostVulkan::create(instanceOnly, failure);
    ASSERT_TRUE(other) << failure;
    HostOptions noSynchronization2;
    noSynchronization2.synchronization2 = false;
    struct Row {
        const char* name;
        HostOptions host;
        std::function<void(ExternalDevice&, RendererDesc&)> edit;
        ErrorCode code;
        const char* names;  ///< in the message or the object
    };
    const Row rows[] = {
        {"device created without synchronization2", noSynchronization2, {},
         ErrorCode::Unsupported, "synchronization2"},
        {"null device", {}, [](ExternalDevice& e, RendererDesc&) { e.device = VK_NULL_HANDLE; },
         ErrorCode::Usage, "ExternalDevice.device"},
        {"null instance", {},
         [](ExternalDevice& e, RendererDesc&) { e.instance = VK_NULL_HANDLE; }, ErrorCode::Usage,
         "ExternalDevice.instance"},
        {"null queue", {}, [](ExternalDevice& e, RendererDesc&) { e.queue = VK_NULL_HANDLE; },
         ErrorCode::Usage, "ExternalDevice.queue"},
        {"physical device of another instance", {},
         [&](ExternalDevice& e, RendererDesc&) { e.physicalDevice = other->physical; },
         ErrorCode::Usage, "not one of the instance's devices"},
        {"instance created for Vulkan 1.2", {},
         [](ExternalDevice& e, RendererDesc&) { e.instanceApiVersion = VK_API_VERSION_1_2; },
         ErrorCode::Unsupported, "1.3"},
        {"queue family that does not exist", {},
         [](ExternalDevice& e, RendererDesc&) { e.queueFamily = 99; }, ErrorCode::Usage,
         "queue family 99"},
        {"presentation without VK_KHR_swapchain", {},
         [](ExternalDevice&, RendererDesc& d) { d.presentation = true; }, ErrorCode::Unsupported,
         "VK_KHR_swapchain"},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.name);
        auto h = host(row.host);
        ASSERT_TRUE(h);
        ExternalDevice e = h->external();
        RendererDesc desc = loggingDesc();
        if (row.edit) row.edit(e, desc);
        auto r = Renderer::create(e, desc);
        ASSERT_FALSE(r) << "accepted";
        EXPECT_EQ(r.error().code, row.code) << r.error().describe();
        EXPECT_NE(r.error().describe().find(row.names), std::string::npos)
            << r.error().describe();
        // A refused device is left as it was: nothing of Lantern's is on it.
        h->destroyDevice();
        EXPECT_EQ(h->messages(), 0u);
    }
}

} // namespace
