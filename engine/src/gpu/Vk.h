// Vk.h: Vulkan include, VkResult -> lantern::Error conversion, and LANTERN_VK_TRY.
#pragma once

#include <lantern/Result.h>

#include <vulkan/vulkan.h>

#include <string>
#include <utility>

namespace lantern::gpu {

/// "VK_ERROR_DEVICE_LOST", ...
const char* vkResultName(VkResult result) noexcept;

/// An Error for a failed Vulkan call: DeviceLost, OutOfMemory or Internal by result.
Error vkError(VkResult result, const char* call);

/// Fault injection (tests only, LANTERN_TESTING_HOOKS): when armed, the next check of a call
/// whose text contains `callSubstring` reports `result` instead of the driver's answer.
void injectVkFault(const std::string& callSubstring, VkResult result, int afterCalls = 0);
void clearVkFaults();
/// Returns the injected result for `call`, or VK_SUCCESS when none is armed for it.
VkResult injectedVkFault(const char* call);
/// Arms the faults named by the LANTERN_TEST_VK_FAULT environment variable (once per process;
/// only in builds with LANTERN_TESTING_HOOKS).
void armFaultsFromEnvironment();

} // namespace lantern::gpu

/// Calls a VkResult-returning expression; on failure returns vkError(...) from the enclosing
/// function (whose return type must be constructible from lantern::Error).
#define LANTERN_VK_TRY(call)                                                                       \
    do {                                                                                           \
        VkResult lanternVkResult_ = (call);                                                        \
        if (lanternVkResult_ == VK_SUCCESS)                                                        \
            lanternVkResult_ = ::lantern::gpu::injectedVkFault(#call);                             \
        if (lanternVkResult_ < 0) return ::lantern::gpu::vkError(lanternVkResult_, #call);         \
    } while (false)
