// VkResult names, their mapping to lantern::Error, and the test-only fault injection hook.
#include "gpu/Vk.h"

#include <atomic>
#include <cstdlib>
#include <mutex>
#include <string>
#include <vector>

namespace lantern::gpu {

const char* vkResultName(VkResult r) noexcept {
    switch (r) {
#define LANTERN_CASE(x)                                                                            \
    case x: return #x;
        LANTERN_CASE(VK_SUCCESS)
        LANTERN_CASE(VK_NOT_READY)
        LANTERN_CASE(VK_TIMEOUT)
        LANTERN_CASE(VK_EVENT_SET)
        LANTERN_CASE(VK_EVENT_RESET)
        LANTERN_CASE(VK_INCOMPLETE)
        LANTERN_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        LANTERN_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        LANTERN_CASE(VK_ERROR_INITIALIZATION_FAILED)
        LANTERN_CASE(VK_ERROR_DEVICE_LOST)
        LANTERN_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        LANTERN_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        LANTERN_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        LANTERN_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        LANTERN_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        LANTERN_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        LANTERN_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        LANTERN_CASE(VK_ERROR_FRAGMENTED_POOL)
        LANTERN_CASE(VK_ERROR_UNKNOWN)
        LANTERN_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        LANTERN_CASE(VK_ERROR_SURFACE_LOST_KHR)
        LANTERN_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        LANTERN_CASE(VK_SUBOPTIMAL_KHR)
        LANTERN_CASE(VK_ERROR_OUT_OF_DATE_KHR)
#undef LANTERN_CASE
    default: return "VK_RESULT_UNKNOWN";
    }
}

Error vkError(VkResult result, const char* call) {
    ErrorCode code = ErrorCode::Internal;
    switch (result) {
    case VK_ERROR_DEVICE_LOST: code = ErrorCode::DeviceLost; break;
    case VK_ERROR_OUT_OF_HOST_MEMORY:
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    case VK_ERROR_OUT_OF_POOL_MEMORY:
    case VK_ERROR_TOO_MANY_OBJECTS: code = ErrorCode::OutOfMemory; break;
    case VK_ERROR_INCOMPATIBLE_DRIVER:
    case VK_ERROR_INITIALIZATION_FAILED: code = ErrorCode::NoDevice; break;
    case VK_ERROR_FEATURE_NOT_PRESENT:
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_FORMAT_NOT_SUPPORTED: code = ErrorCode::Unsupported; break;
    default: break;
    }
    std::string what = code == ErrorCode::DeviceLost ? "the Vulkan device was lost"
                       : code == ErrorCode::OutOfMemory ? "out of memory"
                                                        : "Vulkan call failed";
    return makeError(code, what + " (" + vkResultName(result) + " from " + call + ")");
}

namespace {
struct Fault {
    std::string call;
    VkResult result;
    int skip;
};
std::mutex g_faultMutex;
std::vector<Fault> g_faults;
std::atomic<bool> g_anyFault{false};
} // namespace

void injectVkFault(const std::string& callSubstring, VkResult result, int afterCalls) {
    std::lock_guard lock(g_faultMutex);
    g_faults.push_back({callSubstring, result, afterCalls});
    g_anyFault = true;
}

void clearVkFaults() {
    std::lock_guard lock(g_faultMutex);
    g_faults.clear();
    g_anyFault = false;
}

VkResult injectedVkFault(const char* call) {
    if (!g_anyFault.load(std::memory_order_relaxed)) return VK_SUCCESS;
    std::lock_guard lock(g_faultMutex);
    for (auto it = g_faults.begin(); it != g_faults.end(); ++it) {
        if (std::string_view(call).find(it->call) == std::string_view::npos) continue;
        if (it->skip > 0) {
            --it->skip;
            return VK_SUCCESS;
        }
        const VkResult r = it->result;
        g_faults.erase(it);
        g_anyFault = !g_faults.empty();
        return r;
    }
    return VK_SUCCESS;
}

} // namespace lantern::gpu

namespace lantern::gpu {

void armFaultsFromEnvironment() {
#ifdef LANTERN_TESTING_HOOKS
    // LANTERN_TEST_VK_FAULT="call=RESULT[@N][;call=RESULT...]": the (N+1)th check of a call
    // whose text contains `call` reports RESULT. Compiled in only with LANTERN_TESTING_HOOKS
    // (dev and CI builds), so that tests can drive the command line into device loss.
    static std::once_flag once;
    std::call_once(once, [] {
        const char* env = std::getenv("LANTERN_TEST_VK_FAULT");
        if (!env) return;
        std::string spec(env);
        std::size_t start = 0;
        while (start < spec.size()) {
            std::size_t end = spec.find(';', start);
            if (end == std::string::npos) end = spec.size();
            const std::string item = spec.substr(start, end - start);
            start = end + 1;
            const auto eq = item.find('=');
            if (eq == std::string::npos) continue;
            std::string result = item.substr(eq + 1);
            int after = 0;
            if (const auto at = result.find('@'); at != std::string::npos) {
                after = std::atoi(result.c_str() + at + 1);
                result = result.substr(0, at);
            }
            VkResult r = VK_ERROR_UNKNOWN;
            for (VkResult candidate : {VK_ERROR_DEVICE_LOST, VK_ERROR_OUT_OF_DEVICE_MEMORY,
                                       VK_ERROR_OUT_OF_HOST_MEMORY, VK_ERROR_INITIALIZATION_FAILED})
                if (result == vkResultName(candidate)) r = candidate;
            injectVkFault(item.substr(0, eq), r, after);
        }
    });
#endif
}

} // namespace lantern::gpu
