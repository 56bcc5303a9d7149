// Resources.h: buffers and images with their memory (one dedicated allocation each; Lantern
// packs a scene's geometry into a few large buffers, so allocation counts stay small), and the
// barrier helper used around them.
#pragma once

#include "gpu/Context.h"
#include "gpu/Handles.h"

#include <lantern/Result.h>

#include <cstdint>
#include <initializer_list>
#include <string>

namespace lantern::gpu {

enum class MemoryUsage {
    DeviceLocal,  ///< GPU-only; filled by copies
    Upload,       ///< host-visible, coherent, written by the CPU each frame
    Readback,     ///< host-visible, preferably cached, read by the CPU
};

struct Buffer {
    UniqueBuffer buffer;
    UniqueMemory memory;
    CountedBytes counted;  ///< the memory's bytes in Context::deviceBytes
    VkDeviceSize size = 0;
    void* mapped = nullptr;  ///< persistently mapped for Upload/Readback (and host-visible DeviceLocal)
    bool coherent = true;

    VkBuffer get() const { return buffer.get(); }
};

Result<Buffer> createBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                            MemoryUsage memory, const std::string& name);

/// Makes CPU writes visible to the device (no-op for coherent memory).
Result<void> flush(Context& ctx, const Buffer& buffer);
/// Makes device writes visible to the CPU (no-op for coherent memory).
Result<void> invalidate(Context& ctx, const Buffer& buffer);

struct ImageDesc {
    VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
    std::uint32_t width = 1, height = 1, mipLevels = 1;
    std::uint32_t layers = 1;  ///< array layers (the view covers them all)
    bool arrayView = false;    ///< the view is a 2D array (also for one layer)
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    VkImageUsageFlags usage = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    std::string name;
    /// Linear tiling in device-local, host-visible, host-cached memory, mapped for the host to
    /// read in place (gpu/ReadbackPath.h; single-sampled, one mip level).
    bool hostReadable = false;
};

struct Image {
    UniqueImage image;
    UniqueMemory memory;
    CountedBytes counted;  ///< the memory's bytes in Context::deviceBytes
    UniqueImageView view;
    ImageDesc desc;
    /// A host-readable image: its pixels (mip 0) in the persistently mapped memory, and the
    /// bytes from one row to the next (vkGetImageSubresourceLayout).
    const void* mapped = nullptr;
    VkDeviceSize rowPitch = 0;
    bool coherent = true;

    VkImage get() const { return image.get(); }
};

Result<Image> createImage(Context& ctx, const ImageDesc& desc);

/// Makes device writes to a host-readable image visible to the CPU (no-op for coherent memory).
Result<void> invalidate(Context& ctx, const Image& image);

/// Records one image layout transition / memory dependency (synchronization2).
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess, std::uint32_t baseMip = 0,
                  std::uint32_t mipCount = VK_REMAINING_MIP_LEVELS);

/// Records a global memory dependency (synchronization2).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

/// One buffer descriptor of a set to write: its binding, type and buffer range.
struct BufferBinding {
    std::uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    VkDescriptorBufferInfo info{};
};

/// Points each binding of `set` at its buffer range (the set must not be in use by the device).
void writeBufferDescriptors(Context& ctx, VkDescriptorSet set, std::initializer_list<BufferBinding> bindings);

/// One image descriptor of a set to write: its binding, type and image (sampler, view, layout).
struct ImageBinding {
    std::uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    VkDescriptorImageInfo info{};
};

/// Points each binding of `set` at its image (the set must not be in use by the device).
void writeImageDescriptors(Context& ctx, VkDescriptorSet set, std::initializer_list<ImageBinding> bindings);

/// Replaces `buffer` with one of twice `bytes` when it holds fewer (its contents are not kept).
Result<void> ensureSize(Context& ctx, Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                        MemoryUsage memory, const char* name);

/// Makes `pool`, holding one set of `layout` whose bindings are `storageBuffers` storage
/// buffers, and allocates that set into `set`; does nothing when `pool` already exists.
Result<void> ensureStorageSet(Context& ctx, VkDescriptorSetLayout layout, std::uint32_t storageBuffers,
                              UniqueDescriptorPool& pool, VkDescriptorSet& set);

/// Copies `size` bytes from host memory into a device-local buffer at `offset`, through a
/// temporary staging buffer (or directly when the buffer is host-visible).
Result<void> uploadToBuffer(Context& ctx, Buffer& dst, VkDeviceSize offset, const void* data,
                            VkDeviceSize size);

} // namespace lantern::gpu
