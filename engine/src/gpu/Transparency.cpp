// Order-independent transparency's buffers, images, composite pipelines and commands
// (gpu/Transparency.h). The scene pass and the weighted pass are recorded by gpu/Recorder.cpp.
#include "gpu/Transparency.h"

#include "gpu/Pipeline.h"

#include "ShaderBlobs.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace lantern::gpu {

namespace {

constexpr VkDeviceSize kWord = 4;
constexpr VkDeviceSize kHeaderBytes = LANTERN_OIT_HEADER_WORDS * kWord;

// The most nodes one binding can hold beside `pixels` heads: the device's storage-buffer range,
// its largest allocation and half its largest device-local heap bound it (each frame slot
// holds its own lists).
std::uint64_t maxNodes(const Context& ctx, std::uint64_t pixels) {
    VkDeviceSize bytes = ctx.properties().limits.maxStorageBufferRange;
    if (ctx.maxAllocation() != 0) bytes = std::min(bytes, ctx.maxAllocation());
    if (const VkDeviceSize heap = ctx.largestDeviceLocalHeap(); heap > 0) bytes = std::min(bytes, heap / 2);
    const VkDeviceSize fixed = kHeaderBytes + pixels * kWord;
    if (bytes <= fixed) return 0;
    // Node indices are 32-bit words with LANTERN_OIT_END reserved.
    return std::min<std::uint64_t>((bytes - fixed) / (LANTERN_OIT_NODE_WORDS * kWord),
                                   LANTERN_OIT_END / LANTERN_OIT_NODE_WORDS - 1);
}

ImageDesc weightedImage(VkFormat format, std::uint32_t width, std::uint32_t height,
                        std::uint32_t samples, const char* name) {
    ImageDesc d;
    d.format = format;
    d.width = width;
    d.height = height;
    d.samples = VkSampleCountFlagBits(samples);
    d.usage = samples > 1 ? VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT
                          : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
    d.name = name;
    return d;
}

} // namespace

Result<std::unique_ptr<TransparencyPass>> TransparencyPass::create(Context& ctx, Pipelines& pipelines) {
    std::unique_ptr<TransparencyPass> p(new TransparencyPass(ctx, pipelines.layout()));
    // Tests start the lists this small to make a frame overflow them (gpu/Transparency.h).
    if (const char* nodes = std::getenv("LANTERN_TEST_FRAGMENT_LIST_NODES"))
        p->m_firstNodes = std::strtoull(nodes, nullptr, 10);
    using shaders::ShaderId;
    for (auto [id, module] : {std::pair{ShaderId::clear_vert, &p->m_vertex},
                              std::pair{ShaderId::oit_resolve_frag, &p->m_listResolve},
                              std::pair{ShaderId::weighted_resolve_frag, &p->m_weightedResolve}}) {
        auto m = pipelines.shader(std::uint32_t(id));
        if (!m) return std::move(m).error();
        *module = *m;
    }
    return p;
}

Result<VkPipeline> TransparencyPass::compositePipeline(bool weighted) {
    UniquePipeline& made = weighted ? m_weightedPipeline : m_listPipeline;
    if (made) return made.get();
    GraphicsPipelineDesc d;
    d.layout = m_layout;
    d.vertex = m_vertex;  // one triangle over the target (clear.vert)
    d.fragment = weighted ? m_weightedResolve : m_listResolve;
    d.colorFormats = {kColorFormat};
    d.depthFormat = VK_FORMAT_UNDEFINED;
    d.depthTest = d.depthWrite = false;
    d.premultiplied = true;
    d.name = weighted ? "weighted transparency composite" : "exact transparency composite";
    auto p = createGraphicsPipeline(m_ctx, d);
    if (!p) return std::move(p).error();
    made = std::move(*p);
    return made.get();
}

Result<void> TransparencyPass::prepareLists(TransparencySlot& slot, const TargetDesc& target) {
    const std::uint64_t pixels = std::uint64_t(target.width) * target.height;
    const std::uint64_t most = maxNodes(m_ctx, pixels);
    if (most == 0)
        return makeError(ErrorCode::OutOfMemory,
                         "exact transparency's fragment lists for " + std::to_string(target.width) +
                             "x" + std::to_string(target.height) +
                             " pixels do not fit the device's storage buffers: use "
                             "--transparency sorted or a smaller image",
                         "--transparency");
    // Two fragments a pixel to start with; a frame that asks for more grows it (readCounts).
    const std::uint64_t first = m_firstNodes > 0 ? m_firstNodes : std::max<std::uint64_t>(2 * pixels, 1024);
    const std::uint64_t wanted = std::min(std::max(m_wantedNodes, first), most);
    const VkDeviceSize fixed = kHeaderBytes + pixels * kWord;
    const VkDeviceSize nodeBytes = LANTERN_OIT_NODE_WORDS * kWord;
    const VkDeviceSize bytes = fixed + wanted * nodeBytes;
    if (slot.lists.buffer && slot.lists.size >= bytes) {
        // Large enough for this target (after a resize, too): every node past the heads.
        slot.capacity = std::uint32_t(std::min<std::uint64_t>((slot.lists.size - fixed) / nodeBytes, most));
    } else {
        auto lists = createBuffer(m_ctx, bytes,
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  MemoryUsage::DeviceLocal, "fragment lists");
        if (!lists) return std::move(lists).error();
        slot.lists = std::move(*lists);
        slot.capacity = std::uint32_t(wanted);
    }
    if (!slot.header.buffer) {
        auto header = createBuffer(m_ctx, kHeaderBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   MemoryUsage::Readback, "fragment lists' header");
        if (!header) return std::move(header).error();
        slot.header = std::move(*header);
    }
    auto p = compositePipeline(false);
    if (!p) return std::move(p).error();
    return {};
}

Result<void> TransparencyPass::prepareWeighted(TransparencySlot& slot, const TargetDesc& target) {
    const double bytes = double(target.width) * target.height * 20.0 * double(target.samples + 1);
    if (const VkDeviceSize heap = m_ctx.largestDeviceLocalHeap(); heap > 0 && bytes > 0.5 * double(heap))
        return makeError(ErrorCode::OutOfMemory,
                         "weighted transparency's images need " +
                             std::to_string(std::llround(bytes / 1048576.0)) +
                             " MiB; the device has " + std::to_string(heap / 1048576) + " MiB",
                         "--transparency");
    const std::uint32_t samples = slot.accumMsaa.image ? std::uint32_t(slot.accumMsaa.desc.samples) : 1u;
    if (slot.accum.desc.width != target.width || slot.accum.desc.height != target.height ||
        samples != target.samples) {
        const std::uint32_t w = target.width, h = target.height, s = target.samples;
        auto accum = createImage(m_ctx, weightedImage(kWeightedAccumFormat, w, h, 1, "weighted sums"));
        if (!accum) return std::move(accum).error();
        auto reveal = createImage(m_ctx, weightedImage(kWeightedRevealFormat, w, h, 1, "revealage"));
        if (!reveal) return std::move(reveal).error();
        slot.accum = std::move(*accum);
        slot.reveal = std::move(*reveal);
        slot.accumMsaa = {};
        slot.revealMsaa = {};
        if (s > 1) {
            auto a = createImage(m_ctx, weightedImage(kWeightedAccumFormat, w, h, s, "weighted sums (MSAA)"));
            if (!a) return std::move(a).error();
            auto r = createImage(m_ctx, weightedImage(kWeightedRevealFormat, w, h, s, "revealage (MSAA)"));
            if (!r) return std::move(r).error();
            slot.accumMsaa = std::move(*a);
            slot.revealMsaa = std::move(*r);
        }
    }
    auto p = compositePipeline(true);
    if (!p) return std::move(p).error();
    return {};
}

Result<void> TransparencyPass::prepare(TransparencySlot& slot, const TargetDesc& target) {
    slot.method = target.transparency;
    if (slot.method == TransparencyMethod::Exact) LANTERN_TRY(prepareLists(slot, target));
    if (slot.method == TransparencyMethod::Weighted) {
        LANTERN_TRY(prepareWeighted(slot, target));
    } else if (!slot.accum.image) {  // the stand-ins the frame set binds
        auto accum = createImage(m_ctx, weightedImage(kWeightedAccumFormat, 1, 1, 1, "weighted sums (unused)"));
        if (!accum) return std::move(accum).error();
        auto reveal = createImage(m_ctx, weightedImage(kWeightedRevealFormat, 1, 1, 1, "revealage (unused)"));
        if (!reveal) return std::move(reveal).error();
        slot.accum = std::move(*accum);
        slot.reveal = std::move(*reveal);
    }
    slot.samples = target.samples;
    slot.width = target.width;
    slot.height = target.height;
    return {};
}

void TransparencyPass::writeDescriptors(VkDescriptorSet set, const TransparencySlot& slot,
                                        VkDescriptorBufferInfo standIn) const {
    const bool lists = slot.method == TransparencyMethod::Exact;
    writeBufferDescriptors(m_ctx, set,
                           {{LANTERN_BINDING_FRAGMENT_LISTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                             lists ? VkDescriptorBufferInfo{slot.lists.get(), 0, slot.lists.size}
                                   : standIn}});
    writeImageDescriptors(
        m_ctx, set,
        {{LANTERN_BINDING_WEIGHTED_ACCUM, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
          {VK_NULL_HANDLE, slot.accum.view.get(), VK_IMAGE_LAYOUT_GENERAL}},
         {LANTERN_BINDING_WEIGHTED_REVEAL, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
          {VK_NULL_HANDLE, slot.reveal.view.get(), VK_IMAGE_LAYOUT_GENERAL}}});
}

void TransparencyPass::begin(VkCommandBuffer cmd, const TransparencySlot& slot, bool reversedZ) const {
    if (slot.method == TransparencyMethod::Exact) {
        // The previous frame in this slot read the lists (its fence was waited for; the
        // barrier keeps the order explicit).
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                          VK_ACCESS_2_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
        const std::uint64_t pixels = std::uint64_t(slot.width) * slot.height;
        std::uint32_t header[LANTERN_OIT_HEADER_WORDS] = {};
        header[LANTERN_OIT_WIDTH] = slot.width;
        header[LANTERN_OIT_CAPACITY] = slot.capacity;
        header[LANTERN_OIT_NEARER_GREATER] = reversedZ ? 1u : 0u;
        header[LANTERN_OIT_SAMPLES] = slot.samples;
        header[LANTERN_OIT_NODES] = std::uint32_t(LANTERN_OIT_HEADER_WORDS + pixels);
        vkCmdUpdateBuffer(cmd, slot.lists.get(), 0, kHeaderBytes, header);
        vkCmdFillBuffer(cmd, slot.lists.get(), kHeaderBytes, pixels * kWord, LANTERN_OIT_END);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
    const bool weighted = slot.method == TransparencyMethod::Weighted;
    for (const Image* img : {&slot.accum, &slot.reveal, &slot.accumMsaa, &slot.revealMsaa}) {
        if (!img->image) continue;
        imageBarrier(cmd, img->get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     weighted ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                     weighted ? VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT
                              : VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     weighted ? VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT
                              : VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    }
}

std::vector<VkRenderingAttachmentInfo> TransparencyPass::weightedAttachments(
    const TransparencySlot& slot) const {
    std::vector<VkRenderingAttachmentInfo> a(2, {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO});
    const Image* single[2] = {&slot.accum, &slot.reveal};
    const Image* multi[2] = {&slot.accumMsaa, &slot.revealMsaa};
    for (int i = 0; i < 2; ++i) {
        a[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a[i].clearValue.color.float32[0] = i == 0 ? 0.0f : 1.0f;  // sums 0, revealage 1
        if (multi[i]->image) {
            a[i].imageView = multi[i]->view.get();
            a[i].resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
            a[i].resolveImageView = single[i]->view.get();
            a[i].resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            a[i].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        } else {
            a[i].imageView = single[i]->view.get();
            a[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        }
    }
    return a;
}

void TransparencyPass::composite(VkCommandBuffer cmd, VkPipelineLayout layout,
                                 VkDescriptorSet frameSet, const FrameSetOffsets& offsets,
                                 const TransparencySlot& slot, const Target& target) const {
    const bool weighted = slot.method == TransparencyMethod::Weighted;
    if (weighted) {
        for (const Image* img : {&slot.accum, &slot.reveal})
            imageBarrier(cmd, img->get(), VK_IMAGE_ASPECT_COLOR_BIT,
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                         VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    } else {
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
    // The scene pass wrote (or resolved into) the colour: the composite blends over it.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = target.color.view.get();
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {target.width, target.height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = 1;
    ri.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &ri);
    const VkViewport viewport{0.0f, 0.0f, float(target.width), float(target.height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {target.width, target.height}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      weighted ? m_weightedPipeline.get() : m_listPipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, LANTERN_SET_FRAME, 1,
                            &frameSet, std::uint32_t(offsets.size()), offsets.data());
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    if (weighted) return;
    // The header (fragments asked for, pixels truncated) to the host; the frame's last barrier
    // makes the copy visible to it.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    const VkBufferCopy region{0, 0, kHeaderBytes};
    vkCmdCopyBuffer(cmd, slot.lists.get(), slot.header.get(), 1, &region);
}

void TransparencyPass::readCounts(const TransparencySlot& slot, FrameReadback& frame) {
    if (slot.method != TransparencyMethod::Exact || !slot.header.mapped) return;
    if (!invalidate(m_ctx, slot.header)) return;
    const auto* words = static_cast<const std::uint32_t*>(slot.header.mapped);
    frame.listFragments = words[LANTERN_OIT_COUNT];
    frame.listCapacity = slot.capacity;
    frame.listTruncatedPixels = words[LANTERN_OIT_TRUNCATED];
    const std::uint64_t most = maxNodes(m_ctx, std::uint64_t(slot.width) * slot.height);
    if (frame.listFragments > slot.capacity) {
        // A quarter more than asked for, so a frame that grows a little does not overflow again.
        m_wantedNodes = std::min(most, std::max(m_wantedNodes, frame.listFragments + frame.listFragments / 4));
        frame.listsGrow = m_wantedNodes > slot.capacity;
        if (!frame.listsGrow)
            m_ctx.log(LogLevel::Warning,
                      "exact transparency: the frame made " + std::to_string(frame.listFragments) +
                          " blended fragments; one storage buffer of this device holds " +
                          std::to_string(slot.capacity) +
                          ", so the pixels of the rest miss layers (--transparency sorted or "
                          "weighted, or a smaller image, avoids it)");
    }
    if (frame.listTruncatedPixels > 0)
        m_ctx.log(LogLevel::Warning,
                  "exact transparency: " + std::to_string(frame.listTruncatedPixels) +
                      " pixels have more than " + std::to_string(LANTERN_OIT_MAX_LAYERS) +
                      " blended layers; each composites its nearest " +
                      std::to_string(LANTERN_OIT_MAX_LAYERS));
}

} // namespace lantern::gpu
