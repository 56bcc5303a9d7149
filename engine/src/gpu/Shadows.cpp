// The shadow maps' image, views, comparison sampler and depth-only pipelines. The passes are
// recorded with the frame (gpu/Recorder.cpp).
#include "gpu/Shadows.h"

#include "gpu/Pipeline.h"

#include "ShaderBlobs.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace lantern::gpu {

namespace {

// Refuses, before anything is allocated, maps the device cannot hold: more layers than an image
// may have, a side longer than it allows, or more than half its largest device-local heap (each
// frame slot holds its own maps).
Result<void> checkFits(const Context& ctx, std::uint32_t layers, std::uint32_t resolution) {
    const auto& lim = ctx.properties().limits;
    const std::string what = std::to_string(layers) + " shadow map" + (layers == 1 ? "" : "s") +
                             " of " + std::to_string(resolution) + "x" + std::to_string(resolution);
    if (layers > lim.maxImageArrayLayers)
        return makeError(ErrorCode::OutOfMemory,
                         what + ": the device holds at most " +
                             std::to_string(lim.maxImageArrayLayers) +
                             " (a point light has six; fewer lights cast shadows)",
                         "--shadows");
    if (resolution > lim.maxImageDimension2D)
        return makeError(ErrorCode::OutOfMemory,
                         what + ": the device's images are at most " +
                             std::to_string(lim.maxImageDimension2D) + " texels a side",
                         "--shadow-resolution");
    const VkDeviceSize heap = ctx.largestDeviceLocalHeap();
    const double bytes = double(layers) * double(resolution) * double(resolution) * 4.0;
    if (heap > 0 && bytes > 0.5 * double(heap))
        return makeError(ErrorCode::OutOfMemory,
                         what + " need " + std::to_string(std::llround(bytes / 1048576.0)) +
                             " MiB of device memory; the device has " +
                             std::to_string(heap / 1048576) + " MiB: lower --shadow-resolution",
                         "--shadow-resolution");
    return {};
}

} // namespace

Result<std::unique_ptr<ShadowPass>> ShadowPass::create(Context& ctx, Pipelines& pipelines) {
    std::unique_ptr<ShadowPass> p(new ShadowPass(ctx, pipelines));
    // Reversed Z: lit where the point's depth is at least the map's (as near or nearer). Linear
    // filtering compares the four nearest texels and blends the results (the device's PCF);
    // outside the map the border is depth 0, infinitely far: lit.
    VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;
    sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    sci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    sci.compareEnable = VK_TRUE;
    sci.compareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;
    sci.maxLod = 0.0f;
    VkSampler sampler = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateSampler(ctx.device(), &sci, nullptr, &sampler));
    p->m_sampler = UniqueSampler(ctx.device(), sampler);
    ctx.setName(VK_OBJECT_TYPE_SAMPLER, sampler, "shadow comparison sampler");
    // PCSS's blocker search reads the depths themselves, texel by texel.
    sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
    sci.compareEnable = VK_FALSE;
    LANTERN_VK_TRY(vkCreateSampler(ctx.device(), &sci, nullptr, &sampler));
    p->m_depthSampler = UniqueSampler(ctx.device(), sampler);
    ctx.setName(VK_OBJECT_TYPE_SAMPLER, sampler, "shadow depth sampler");
    return p;
}

void ShadowPass::writeDescriptors(VkDescriptorSet set, const ShadowSlot& slot) const {
    const VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    writeImageDescriptors(
        m_ctx, set,
        {{LANTERN_BINDING_SHADOW_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
          {m_sampler.get(), slot.image.view.get(), layout}},
         {LANTERN_BINDING_SHADOW_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
          {m_depthSampler.get(), slot.image.view.get(), layout}}});
}

Result<void> ShadowPass::makePipelines() {
    auto vs = m_programs.shader(std::uint32_t(shaders::ShaderId::shadow_vert));
    if (!vs) return std::move(vs).error();
    for (int instanced = 0; instanced < 2; ++instanced) {
        GraphicsPipelineDesc d;
        d.layout = m_programs.layout();
        d.vertex = *vs;
        d.fragment = VK_NULL_HANDLE;  // depth only
        for (std::uint32_t i = 0; i < LANTERN_SC_COUNT; ++i) {
            d.specEntries.push_back({i, i * 4u, 4u});
            d.specData.push_back(i == LANTERN_SC_INSTANCED ? std::uint32_t(instanced) : 0u);
        }
        d.bindings = {{LANTERN_LOC_POSITION, 12, VK_VERTEX_INPUT_RATE_VERTEX}};
        d.attributes = {{LANTERN_LOC_POSITION, LANTERN_LOC_POSITION, VK_FORMAT_R32G32B32_SFLOAT, 0}};
        d.depthFormat = VK_FORMAT_D32_SFLOAT;
        d.depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed Z
        d.depthBias = true;
        d.name = instanced ? "shadow map (instanced)" : "shadow map";
        auto pipeline = createGraphicsPipeline(m_ctx, d);
        if (!pipeline) return std::move(pipeline).error();
        m_pipelines[instanced] = std::move(*pipeline);
    }
    return {};
}

Result<void> ShadowPass::prepare(ShadowSlot& slot, const DrawList& list) {
    const ShadowCommands& s = list.shadows;
    slot.rendering = s.any();
    if (slot.rendering && !m_pipelines[0]) LANTERN_TRY(makePipelines());
    const std::uint32_t layers = slot.rendering ? std::uint32_t(s.passes.size()) : 1u;
    const std::uint32_t resolution = slot.rendering ? s.resolution : 1u;
    if (slot.image.get() && slot.layers == layers && slot.resolution == resolution) return {};
    LANTERN_TRY(checkFits(m_ctx, layers, resolution));
    slot.layerViews.clear();
    slot.image = Image{};
    ImageDesc d;
    d.format = VK_FORMAT_D32_SFLOAT;
    d.width = d.height = resolution;
    d.layers = layers;
    d.arrayView = true;
    d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    d.name = "shadow maps";
    auto image = createImage(m_ctx, d);
    if (!image) return std::move(image).error();
    slot.image = std::move(*image);
    for (std::uint32_t layer = 0; layer < layers; ++layer) {
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = slot.image.get();
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = d.format;
        vci.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, layer, 1};
        VkImageView view = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateImageView(m_ctx.device(), &vci, nullptr, &view));
        slot.layerViews.emplace_back(m_ctx.device(), view);
    }
    slot.layers = layers;
    slot.resolution = resolution;
    return {};
}

void ShadowPass::transition(VkCommandBuffer cmd, const ShadowSlot& slot, VkImageLayout from,
                            VkImageLayout to) {
    const bool toRead = to == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    const VkPipelineStageFlags2 shaders = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                          VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    const VkPipelineStageFlags2 tests = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                        VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    // Into the passes: after the previous frame's reads. Out of them: their writes before the
    // lighting's reads in any stage.
    b.srcStageMask = toRead ? tests : shaders;
    b.srcAccessMask = toRead ? VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_2_NONE;
    b.dstStageMask = toRead ? shaders : tests;
    b.dstAccessMask = toRead ? VK_ACCESS_2_SHADER_SAMPLED_READ_BIT
                             : VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = slot.image.get();
    b.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

} // namespace lantern::gpu
