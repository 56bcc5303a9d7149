// Buffers, images, memory types and barriers.
#include "gpu/Resources.h"

#include "gpu/ReadbackPath.h"

#include <cstring>
#include <vector>

namespace lantern::gpu {

Result<Buffer> createBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                            MemoryUsage memory, const std::string& name) {
    // Sizes come from scenes (flat streams, geometry): refused before anything is created when
    // the device could never hold them, with the sizes named, instead of a driver failure.
    if (ctx.maxAllocation() != 0 && size > ctx.maxAllocation())
        return makeError(ErrorCode::OutOfMemory,
                         "buffer " + name + " needs " + std::to_string(size) +
                             " bytes, more than the device's largest allocation (" +
                             std::to_string(ctx.maxAllocation()) + " bytes)");
    Buffer b;
    b.size = size;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = size > 0 ? size : 16;
    bci.usage = usage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateBuffer(ctx.device(), &bci, nullptr, &buffer));
    b.buffer = UniqueBuffer(ctx.device(), buffer);
    ctx.setName(VK_OBJECT_TYPE_BUFFER, buffer, name);

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device(), buffer, &req);
    int type = -1;
    switch (memory) {
    case MemoryUsage::DeviceLocal:
        // Prefer memory that is also host-visible (CPU devices, resizable BAR): no staging.
        type = ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                      VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        if (type < 0) type = ctx.findMemoryType(req.memoryTypeBits, 0);
        break;
    case MemoryUsage::Upload:
        type = ctx.findMemoryType(req.memoryTypeBits,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                      VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                  VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        break;
    case MemoryUsage::Readback:
        type = ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
                                  VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        break;
    }
    if (type < 0)
        return makeError(ErrorCode::Unsupported, "no suitable memory type for buffer " + name);
    const VkMemoryPropertyFlags flags = ctx.memoryProperties().memoryTypes[type].propertyFlags;
    const VkMemoryHeap& heap =
        ctx.memoryProperties().memoryHeaps[ctx.memoryProperties().memoryTypes[type].heapIndex];
    if (req.size > heap.size)
        return makeError(ErrorCode::OutOfMemory, "buffer " + name + " needs " +
                                                     std::to_string(req.size) +
                                                     " bytes, more than its memory heap (" +
                                                     std::to_string(heap.size) + " bytes)");

    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = std::uint32_t(type);
    VkDeviceMemory mem = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkAllocateMemory(ctx.device(), &mai, nullptr, &mem));
    b.memory = UniqueMemory(ctx.device(), mem);
    b.counted = CountedBytes(ctx.deviceBytesCounter(), req.size);
    LANTERN_VK_TRY(vkBindBufferMemory(ctx.device(), buffer, mem, 0));
    if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        LANTERN_VK_TRY(vkMapMemory(ctx.device(), mem, 0, VK_WHOLE_SIZE, 0, &b.mapped));
        b.coherent = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    }
    return b;
}

Result<void> flush(Context& ctx, const Buffer& buffer) {
    if (buffer.coherent || !buffer.mapped) return {};
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = buffer.memory.get();
    range.size = VK_WHOLE_SIZE;
    LANTERN_VK_TRY(vkFlushMappedMemoryRanges(ctx.device(), 1, &range));
    return {};
}

Result<void> invalidate(Context& ctx, const Buffer& buffer) {
    if (buffer.coherent || !buffer.mapped) return {};
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = buffer.memory.get();
    range.size = VK_WHOLE_SIZE;
    LANTERN_VK_TRY(vkInvalidateMappedMemoryRanges(ctx.device(), 1, &range));
    return {};
}

namespace {

// Maps a host-readable image's memory for good and finds where mip 0 lies in it.
Result<void> mapImage(Context& ctx, Image& img, std::uint32_t type) {
    void* base = nullptr;
    LANTERN_VK_TRY(vkMapMemory(ctx.device(), img.memory.get(), 0, VK_WHOLE_SIZE, 0, &base));
    const VkImageSubresource sub{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0};
    VkSubresourceLayout layout{};
    vkGetImageSubresourceLayout(ctx.device(), img.get(), &sub, &layout);
    img.mapped = static_cast<const char*>(base) + layout.offset;
    img.rowPitch = layout.rowPitch;
    img.coherent = (ctx.memoryProperties().memoryTypes[type].propertyFlags &
                    VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    return {};
}

} // namespace

Result<Image> createImage(Context& ctx, const ImageDesc& desc) {
    Image img;
    img.desc = desc;
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = desc.format;
    ici.extent = {desc.width, desc.height, 1};
    ici.mipLevels = desc.mipLevels;
    ici.arrayLayers = desc.layers;
    ici.samples = desc.samples;
    ici.tiling = desc.hostReadable ? VK_IMAGE_TILING_LINEAR : VK_IMAGE_TILING_OPTIMAL;
    ici.usage = desc.usage;
    ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateImage(ctx.device(), &ici, nullptr, &image));
    img.image = UniqueImage(ctx.device(), image);
    ctx.setName(VK_OBJECT_TYPE_IMAGE, image, desc.name);

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device(), image, &req);
    const int type =
        desc.hostReadable
            ? inPlaceMemoryType(ctx.memoryProperties(), req.memoryTypeBits)
            : ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0)
        return makeError(ErrorCode::Unsupported,
                         std::string(desc.hostReadable ? "no device-local memory the host reads "
                                                         "in place"
                                                       : "no device-local memory") +
                             " for image " + desc.name);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = std::uint32_t(type);
    VkDeviceMemory mem = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkAllocateMemory(ctx.device(), &mai, nullptr, &mem));
    img.memory = UniqueMemory(ctx.device(), mem);
    img.counted = CountedBytes(ctx.deviceBytesCounter(), req.size);
    LANTERN_VK_TRY(vkBindImageMemory(ctx.device(), image, mem, 0));
    if (desc.hostReadable) LANTERN_TRY(mapImage(ctx, img, std::uint32_t(type)));

    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = image;
    vci.viewType = desc.arrayView ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    vci.format = desc.format;
    vci.subresourceRange = {desc.aspect, 0, desc.mipLevels, 0, desc.layers};
    VkImageView view = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateImageView(ctx.device(), &vci, nullptr, &view));
    img.view = UniqueImageView(ctx.device(), view);
    ctx.setName(VK_OBJECT_TYPE_IMAGE_VIEW, view, desc.name + " view");
    return img;
}

Result<void> invalidate(Context& ctx, const Image& image) {
    if (image.coherent || !image.mapped) return {};
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = image.memory.get();
    range.size = VK_WHOLE_SIZE;
    LANTERN_VK_TRY(vkInvalidateMappedMemoryRanges(ctx.device(), 1, &range));
    return {};
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess, std::uint32_t baseMip, std::uint32_t mipCount) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStage;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, baseMip, mipCount, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStage;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

Result<void> uploadToBuffer(Context& ctx, Buffer& dst, VkDeviceSize offset, const void* data,
                            VkDeviceSize size) {
    if (size == 0) return {};
    if (dst.mapped) {
        std::memcpy(static_cast<char*>(dst.mapped) + offset, data, size);
        return flush(ctx, dst);
    }
    auto staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload,
                                "staging");
    if (!staging) return std::move(staging).error();
    std::memcpy(staging->mapped, data, size);
    LANTERN_TRY(flush(ctx, *staging));
    return ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, offset, size};
        vkCmdCopyBuffer(cmd, staging->get(), dst.get(), 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
    });
}

Result<void> ensureSize(Context& ctx, Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                        MemoryUsage memory, const char* name) {
    if (buffer.size >= bytes) return {};
    auto b = createBuffer(ctx, bytes * 2, usage, memory, name);
    if (!b) return std::move(b).error();
    buffer = std::move(*b);
    return {};
}

Result<void> ensureStorageSet(Context& ctx, VkDescriptorSetLayout layout, std::uint32_t storageBuffers,
                              UniqueDescriptorPool& pool, VkDescriptorSet& set) {
    if (pool) return {};
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storageBuffers};
    VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpci.maxSets = 1;
    dpci.poolSizeCount = 1;
    dpci.pPoolSizes = &size;
    VkDescriptorPool handle = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorPool(ctx.device(), &dpci, nullptr, &handle));
    pool = UniqueDescriptorPool(ctx.device(), handle);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = handle;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &layout;
    LANTERN_VK_TRY(vkAllocateDescriptorSets(ctx.device(), &ai, &set));
    return {};
}

namespace {

// One write per binding, each pointed at its info by `point`.
template <typename Binding, typename Point>
void writeDescriptors(Context& ctx, VkDescriptorSet set, std::initializer_list<Binding> bindings,
                      Point point) {
    std::vector<VkWriteDescriptorSet> writes(bindings.size());
    std::size_t i = 0;
    for (const Binding& b : bindings) {
        VkWriteDescriptorSet& w = writes[i++];
        w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        w.dstSet = set;
        w.dstBinding = b.binding;
        w.descriptorCount = 1;
        w.descriptorType = b.type;
        point(w, b);
    }
    vkUpdateDescriptorSets(ctx.device(), std::uint32_t(writes.size()), writes.data(), 0, nullptr);
}

} // namespace

void writeBufferDescriptors(Context& ctx, VkDescriptorSet set, std::initializer_list<BufferBinding> bindings) {
    writeDescriptors(ctx, set, bindings,
                     [](VkWriteDescriptorSet& w, const BufferBinding& b) { w.pBufferInfo = &b.info; });
}

void writeImageDescriptors(Context& ctx, VkDescriptorSet set, std::initializer_list<ImageBinding> bindings) {
    writeDescriptors(ctx, set, bindings,
                     [](VkWriteDescriptorSet& w, const ImageBinding& b) { w.pImageInfo = &b.info; });
}

} // namespace lantern::gpu
