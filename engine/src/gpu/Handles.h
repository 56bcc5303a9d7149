// Handles.h: move-only RAII owners for Vulkan objects: one owner per object, destroyed in the
// destructor, with an explicit empty state and no reference counting.
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <utility>

namespace lantern::gpu {

/// Owns one device-level object `T`, destroyed with `Destroy(device, handle, nullptr)`.
template <typename T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
class DeviceHandle {
public:
    DeviceHandle() = default;
    DeviceHandle(VkDevice device, T handle) : m_device(device), m_handle(handle) {}
    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    DeviceHandle(DeviceHandle&& o) noexcept
        : m_device(o.m_device), m_handle(std::exchange(o.m_handle, VK_NULL_HANDLE)) {}
    DeviceHandle& operator=(DeviceHandle&& o) noexcept {
        if (this != &o) {
            reset();
            m_device = o.m_device;
            m_handle = std::exchange(o.m_handle, VK_NULL_HANDLE);
        }
        return *this;
    }
    ~DeviceHandle() { reset(); }

    void reset() {
        if (m_handle != VK_NULL_HANDLE) Destroy(m_device, m_handle, nullptr);
        m_handle = VK_NULL_HANDLE;
    }
    T get() const { return m_handle; }
    explicit operator bool() const { return m_handle != VK_NULL_HANDLE; }

private:
    VkDevice m_device = VK_NULL_HANDLE;
    T m_handle = VK_NULL_HANDLE;
};

using UniqueBuffer = DeviceHandle<VkBuffer, vkDestroyBuffer>;
using UniqueImage = DeviceHandle<VkImage, vkDestroyImage>;
using UniqueImageView = DeviceHandle<VkImageView, vkDestroyImageView>;
using UniqueMemory = DeviceHandle<VkDeviceMemory, vkFreeMemory>;
using UniqueSampler = DeviceHandle<VkSampler, vkDestroySampler>;
using UniqueFence = DeviceHandle<VkFence, vkDestroyFence>;
using UniqueSemaphore = DeviceHandle<VkSemaphore, vkDestroySemaphore>;
using UniqueCommandPool = DeviceHandle<VkCommandPool, vkDestroyCommandPool>;
using UniqueDescriptorPool = DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>;
using UniqueDescriptorSetLayout = DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using UniquePipelineLayout = DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>;
using UniquePipeline = DeviceHandle<VkPipeline, vkDestroyPipeline>;
using UniquePipelineCache = DeviceHandle<VkPipelineCache, vkDestroyPipelineCache>;
using UniqueShaderModule = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using UniqueRenderPass = DeviceHandle<VkRenderPass, vkDestroyRenderPass>;
using UniqueFramebuffer = DeviceHandle<VkFramebuffer, vkDestroyFramebuffer>;
using UniqueSwapchain = DeviceHandle<VkSwapchainKHR, vkDestroySwapchainKHR>;

/// An allocation's bytes in a running total (Context::deviceBytes): added when made, taken off
/// when the owner goes.
class CountedBytes {
public:
    CountedBytes() = default;
    CountedBytes(std::atomic<std::uint64_t>& total, std::uint64_t bytes)
        : m_total(&total), m_bytes(bytes) {
        total += bytes;
    }
    CountedBytes(const CountedBytes&) = delete;
    CountedBytes& operator=(const CountedBytes&) = delete;
    CountedBytes(CountedBytes&& o) noexcept
        : m_total(std::exchange(o.m_total, nullptr)), m_bytes(o.m_bytes) {}
    CountedBytes& operator=(CountedBytes&& o) noexcept {
        if (this != &o) {
            release();
            m_total = std::exchange(o.m_total, nullptr);
            m_bytes = o.m_bytes;
        }
        return *this;
    }
    ~CountedBytes() { release(); }

private:
    void release() {
        if (m_total) *m_total -= m_bytes;
        m_total = nullptr;
    }
    std::atomic<std::uint64_t>* m_total = nullptr;
    std::uint64_t m_bytes = 0;
};

} // namespace lantern::gpu
