// Recording one frame with Vulkan 1.3 dynamic rendering and synchronization2: the shadow maps'
// passes, attachment barriers, the scene pass (and, with MSAA and AOVs, a single-sampled AOV pass), one viewport
// per view, one draw per DrawCommand, the overlays, weighted transparency's pass and the
// transparency composite (gpu/Transparency.h), then the copies into the readback buffers
// (or, for planes read in place, only the transition that hands them to the host).
#include "gpu/FrameRing.h"

#include "gpu/ClearDraw.h"

#include <algorithm>
#include <cstring>

namespace lantern::gpu {
namespace {

struct FrameRecorder {
    VkCommandBuffer cmd;
    VkPipelineLayout layout;
    const OverlayPipelines* overlays;
    FrameRing::Slot& slot;
    const SceneBuffers& scene;
    const DrawList& list;
    const FrameRing::ArenaLayout& arena;

    void beginAttachments() const;
    void bindStreams(const DrawCommand& d, std::uint32_t flatJob, std::size_t index) const;
    void shadowMaps(const ShadowPass& shadows) const;
    void drawDepth(const DrawCommand& d) const;
    void drawViews(const std::vector<VkPipeline>& pipelines, bool overlaysToo) const;
    void beginRendering(const std::vector<VkRenderingAttachmentInfo>& colors,
                        const VkRenderingAttachmentInfo& depth) const;
    void pass(const std::vector<VkRenderingAttachmentInfo>& colors, const Image& depthImage,
              VkPipeline clear, const std::vector<VkPipeline>& pipelines, bool keepDepth) const;
    void weightedPass(const TransparencyPass& transparency, const std::vector<VkPipeline>& pipelines) const;
    void copyOut(const Image& img, const Buffer& buf, bool readback) const;
};

// Every attachment from UNDEFINED to its attachment layout (contents are cleared anyway).
void FrameRecorder::beginAttachments() const {
    const Target& t = slot.target;
    std::vector<VkImage> colorImages{t.color.get()};
    std::vector<VkImage> depthImages{t.depth.get()};
    if (t.multisampled()) colorImages.push_back(t.colorMsaa.get());
    if (t.aov) {
        colorImages.push_back(t.normalDepth.get());
        colorImages.push_back(t.ids.get());
    }
    if (t.surface) colorImages.push_back(t.surfaceUvRange.get());
    if (t.separateAovPass()) {
        colorImages.push_back(t.aovColor.get());
        depthImages.push_back(t.aovDepth.get());
    }
    for (VkImage img : colorImages)
        imageBarrier(cmd, img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
    for (VkImage img : depthImages)
        imageBarrier(cmd, img, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
}

// The primitive's streams, one binding per attribute location; absent colours, texture
// coordinates (either set) and tangents read a stride-0 default (white, zero, zero). `flatJob`: a flat draw lit by the
// per-triangle pass, which binds no streams: its index list, written by the pass at three
// times the draw's first record, names vertices whose corners flat.vert pulls from the job.
void FrameRecorder::bindStreams(const DrawCommand& d, std::uint32_t flatJob, std::size_t index) const {
    const PrimitiveBuffers& gp = scene.primitive(d.mesh, d.primitive);
    if (flatJob != kNoFlatJob) {
        vkCmdBindIndexBuffer(cmd, slot.flat.indices.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, 3u * FlatLighter::triangleCount(gp), 1,
                         3u * slot.flat.firstRecords[flatJob], 0, 0);
        return;
    }
    const VkBuffer geometry = scene.geometry();
    // A deformed draw reads its positions and normals (and flat centroids) from this frame's
    // pre-pass output.
    const bool deformed = d.deform >= 0 && slot.deforming;
    const DeformStreams* ds = deformed ? &slot.deform.streams[std::size_t(d.deform)] : nullptr;
    const VkBuffer moved = deformed ? slot.deform.output.get() : VK_NULL_HANDLE;
    if (d.pipeline.program == frame::Program::Flat) {
        const VkBuffer flat = scene.flatGeometry();
        const bool color = gp.flatColor != kNoStream, texcoord = gp.flatTexcoord != kNoStream;
        VkBuffer buffers[LANTERN_VERTEX_BINDINGS];
        VkDeviceSize offsets[LANTERN_VERTEX_BINDINGS], strides[LANTERN_VERTEX_BINDINGS];
        auto set = [&](int loc, VkBuffer b, VkDeviceSize o, VkDeviceSize s) {
            buffers[loc] = b, offsets[loc] = o, strides[loc] = s;
        };
        set(LANTERN_LOC_POSITION, ds ? moved : flat, ds ? ds->position : gp.flatPosition, 12);
        set(LANTERN_LOC_NORMAL, ds ? moved : flat, ds ? ds->normal : gp.flatNormal, 12);
        set(LANTERN_LOC_COLOR, color ? flat : geometry,
            color ? gp.flatColor : scene.defaultColorOffset(), color ? 16 : 0);
        set(LANTERN_LOC_TEXCOORD, texcoord ? flat : geometry,
            texcoord ? gp.flatTexcoord : scene.defaultTexcoordOffset(), texcoord ? 8 : 0);
        set(LANTERN_LOC_CENTROID, ds ? moved : flat, ds ? ds->centroid : gp.flatCentroid, 12);
        vkCmdBindVertexBuffers2(cmd, 0, LANTERN_VERTEX_BINDINGS, buffers, offsets, nullptr, strides);
        const bool texcoord1 = gp.flatTexcoord1 != kNoStream;
        const VkBuffer b1 = texcoord1 ? flat : geometry;
        const VkDeviceSize o1 = texcoord1 ? gp.flatTexcoord1 : scene.defaultTexcoordOffset();
        const VkDeviceSize s1 = texcoord1 ? 8 : 0;
        vkCmdBindVertexBuffers2(cmd, LANTERN_LOC_TEXCOORD1, 1, &b1, &o1, nullptr, &s1);
        vkCmdDraw(cmd, gp.flatVertexCount, 1, 0, 0);
        return;
    }
    // One call for every location up to the second texture set; the centroid's (flat only)
    // reads the zero default, unused. A deformed draw's tangents are not moved by the
    // pre-pass, so it takes the zero tangent (the frame from derivatives).
    constexpr std::uint32_t kBindings = LANTERN_LOC_TEXCOORD1 + 1;
    static_assert(LANTERN_LOC_CENTROID < kBindings && LANTERN_LOC_TANGENT < kBindings);
    VkBuffer buffers[kBindings];
    VkDeviceSize offsets[kBindings], strides[kBindings];
    for (VkBuffer& b : buffers) b = geometry;
    auto stream = [&](int loc, VkDeviceSize at, VkDeviceSize fallback, VkDeviceSize stride) {
        const bool present = at != kNoStream;
        offsets[loc] = present ? at : fallback;
        strides[loc] = present ? stride : 0;
    };
    stream(LANTERN_LOC_POSITION, ds ? ds->position : gp.position, 0, 12);
    stream(LANTERN_LOC_NORMAL, ds ? ds->normal : gp.normal, 0, 12);
    if (ds) buffers[LANTERN_LOC_POSITION] = buffers[LANTERN_LOC_NORMAL] = moved;
    stream(LANTERN_LOC_COLOR, gp.color, scene.defaultColorOffset(), 16);
    stream(LANTERN_LOC_TEXCOORD, gp.texcoord, scene.defaultTexcoordOffset(), 8);
    stream(LANTERN_LOC_CENTROID, kNoStream, scene.defaultTangentOffset(), 12);
    stream(LANTERN_LOC_TANGENT, ds ? kNoStream : gp.tangent, scene.defaultTangentOffset(), 16);
    stream(LANTERN_LOC_TEXCOORD1, gp.texcoord1, scene.defaultTexcoordOffset(), 8);
    vkCmdBindVertexBuffers2(cmd, 0, kBindings, buffers, offsets, nullptr, strides);
    // An instanced draw's instances read their transforms at gl_InstanceIndex, which starts at
    // firstInstance (shaders/include/instance.glsl).
    // A clustered draw draws the clusters the culling pass kept (gpu/Clusters.h).
    if (const CullSlot::Range* clusters = slot.cull.any() ? slot.cull.range(index) : nullptr) {
        drawClusters(cmd, slot.cull, *clusters, geometry);
    } else if (gp.indexCount > 0) {
        vkCmdBindIndexBuffer(cmd, geometry, gp.index, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, gp.indexCount, d.instanceCount, 0, 0, d.firstInstance);
    } else {
        vkCmdDraw(cmd, gp.vertexCount, d.instanceCount, 0, d.firstInstance);
    }
}

// The shadow maps: one depth-only pass per map over the first view's opaque triangles that can
// reach it (both faces: an open mesh casts too), with the map's frame block bound and a slope-scaled depth
// bias; then every layer to the lighting's reads.
void FrameRecorder::shadowMaps(const ShadowPass& shadows) const {
    const ShadowSlot& s = slot.shadow;
    ShadowPass::transition(cmd, s, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    const VkViewport viewport{0.0f, 0.0f, float(s.resolution), float(s.resolution), 0.0f, 1.0f};
    const VkRect2D area{{0, 0}, {s.resolution, s.resolution}};
    for (std::size_t k = 0; k < list.shadows.passes.size(); ++k) {
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = s.layerViews[k].get();
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil.depth = 0.0f;  // reversed Z: infinitely far
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = area;
        ri.layerCount = 1;
        ri.pDepthAttachment = &depth;
        vkCmdBeginRendering(cmd, &ri);
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &area);
        const FrameSetOffsets offsets = frameSetOffsets(arena.shadowFrameOffsets[k], arena.lightOffsets[0]);
        VkPipeline bound = VK_NULL_HANDLE;
        for (std::uint32_t index : list.shadows.passDraws[k]) {
            const DrawCommand& d = list.views[0].draws[index];
            const VkPipeline p = shadows.pipeline(d.pipeline.constants[LANTERN_SC_INSTANCED] != 0);
            if (p != bound) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
                if (bound == VK_NULL_HANDLE) {
                    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, LANTERN_SET_FRAME,
                                            1, &slot.frameSet, std::uint32_t(offsets.size()), offsets.data());
                    vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
                    vkCmdSetFrontFace(cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
                    vkCmdSetDepthBias(cmd, -1.0f, 0.0f, list.shadows.slopeBias);
                }
                bound = p;
            }
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                               0, sizeof(DrawBlock), &d.block);
            drawDepth(d);
        }
        vkCmdEndRendering(cmd);
    }
    ShadowPass::transition(cmd, s, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// A draw's positions alone, from its own streams or this frame's deformation (per corner for
// flat draws, whose deformation writes their de-indexed streams).
void FrameRecorder::drawDepth(const DrawCommand& d) const {
    const PrimitiveBuffers& gp = scene.primitive(d.mesh, d.primitive);
    const bool deformed = d.deform >= 0 && slot.deforming;
    const DeformStreams* ds = deformed ? &slot.deform.streams[std::size_t(d.deform)] : nullptr;
    const VkBuffer buffer = ds ? slot.deform.output.get() : scene.geometry();
    const VkDeviceSize offset = ds ? ds->position : gp.position, stride = 12;
    vkCmdBindVertexBuffers2(cmd, LANTERN_LOC_POSITION, 1, &buffer, &offset, nullptr, &stride);
    if (ds && d.pipeline.program == frame::Program::Flat) {
        vkCmdDraw(cmd, gp.flatVertexCount, d.instanceCount, 0, d.firstInstance);
    } else if (gp.indexCount > 0) {
        vkCmdBindIndexBuffer(cmd, scene.geometry(), gp.index, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, gp.indexCount, d.instanceCount, 0, 0, d.firstInstance);
    } else {
        vkCmdDraw(cmd, gp.vertexCount, d.instanceCount, 0, d.firstInstance);
    }
}

// Draws every view's list with the given pipelines (one per draw, in list order; a null one
// skips its draw), then each view's overlays when `overlaysToo`.
void FrameRecorder::drawViews(const std::vector<VkPipeline>& pipelines, bool overlaysToo) const {
    const int rows = int(slot.target.height);
    const int pictureHeight = list.pictureHeight > 0 ? int(list.pictureHeight) : rows;
    std::size_t counter = 0;
    for (std::size_t vi = 0; vi < list.views.size(); ++vi) {
        const ViewCommands& v = list.views[vi];
        // GL's viewport origin is the bottom-left corner; Vulkan's framebuffer starts at the top.
        // In a band the viewport keeps its place in the picture (above the target's first row
        // when the view starts above the band) and the scissor keeps the band's share of it.
        const int vy = pictureHeight - v.y - v.height - int(list.bandTop);
        const int top = std::max(vy, 0), bottom = std::min(vy + v.height, rows);
        if (bottom <= top) {  // the view lies outside this band
            counter += v.draws.size();
            continue;
        }
        const VkViewport viewport{float(v.x), float(vy), float(v.width), float(v.height), 0.0f, 1.0f};
        const VkRect2D scissor{{v.x, top}, {std::uint32_t(v.width), std::uint32_t(bottom - top)}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        const FrameSetOffsets dynamicOffsets =
            frameSetOffsets(arena.frameOffsets[vi], arena.lightOffsets[vi]);
        // The per-triangle flat draws' jobs and corners (bound per view: the overlays bind
        // their own layouts between views).
        if (slot.flat.any())
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, LANTERN_SET_FLAT,
                                    1, &slot.flat.set, 0, nullptr);
        VkPipeline bound = VK_NULL_HANDLE;
        VkDescriptorSet boundTexture = VK_NULL_HANDLE;
        for (const DrawCommand& d : v.draws) {
            const std::uint32_t flatJob =
                counter < slot.flat.drawJobs.size() ? slot.flat.drawJobs[counter] : kNoFlatJob;
            const std::size_t index = counter;
            const VkPipeline p = pipelines[counter++];
            if (p == VK_NULL_HANDLE) continue;
            if (p != bound) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
                if (bound == VK_NULL_HANDLE)
                    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout,
                                            LANTERN_SET_FRAME, 1, &slot.frameSet,
                                            std::uint32_t(dynamicOffsets.size()),
                                            dynamicOffsets.data());
                bound = p;
            }
            const VkDescriptorSet tex = scene.textureSet(d.textureSet);
            if (tex != boundTexture) {
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout,
                                        LANTERN_SET_TEXTURE, 1, &tex, 0, nullptr);
                boundTexture = tex;
            }
            vkCmdSetCullMode(cmd, d.cullBack ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE);
            if (d.pipeline.topology == Topology::Lines) vkCmdSetLineWidth(cmd, list.target.lineWidth);
            // The y flip in clipFromView keeps GL's counter-clockwise front faces
            // counter-clockwise on screen; a mirroring transform reverses them (glTF's rule).
            vkCmdSetFrontFace(cmd, d.frontClockwise ? VK_FRONT_FACE_CLOCKWISE
                                                    : VK_FRONT_FACE_COUNTER_CLOCKWISE);
            DrawBlock block = d.block;
            if (flatJob != kNoFlatJob) block.flatJob = flatJob;
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                               0, sizeof(DrawBlock), &block);
            bindStreams(d, flatJob, index);
        }
        // The display overlays never meet the AOV pass (they refuse AOVs).
        if (overlaysToo && slot.overlays.any())
            overlays->recordView(cmd, scene, v, slot.frameSet, dynamicOffsets, slot.overlays);
    }
}

// Begins rendering over the whole target into `colors` and `depth`.
void FrameRecorder::beginRendering(const std::vector<VkRenderingAttachmentInfo>& colors,
                                   const VkRenderingAttachmentInfo& depth) const {
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {slot.target.width, slot.target.height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = std::uint32_t(colors.size());
    ri.pColorAttachments = colors.data();
    ri.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &ri);
}

// `clear`: the pipeline that clears the colour attachments by drawing (gpu/ClearDraw.h), which
// are then not loaded; null: they clear themselves (LOAD_OP_CLEAR). `keepDepth`: a later pass
// (weighted transparency's) tests against the depth.
void FrameRecorder::pass(const std::vector<VkRenderingAttachmentInfo>& colors,
                         const Image& depthImage, VkPipeline clear,
                         const std::vector<VkPipeline>& pipelines, bool keepDepth) const {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = depthImage.view.get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = keepDepth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    // Reversed-Z clears to 0 (infinitely far), standard depth to 1.
    depth.clearValue.depthStencil.depth = list.target.reversedZ ? 0.0f : 1.0f;
    beginRendering(colors, depth);
    if (clear != VK_NULL_HANDLE)
        ClearDraw::record(cmd, layout, clear, slot.target.width, slot.target.height,
                          colors[LANTERN_OUT_COLOR].clearValue.color.float32);
    drawViews(pipelines, true);
    vkCmdEndRendering(cmd);
}

// Weighted transparency's pass: the blended draws into the weighted sums and the revealage
// (multisampled like the scene, resolved), tested against the scene pass's depth, not writing it.
void FrameRecorder::weightedPass(const TransparencyPass& transparency,
                                 const std::vector<VkPipeline>& pipelines) const {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
    const std::vector<VkRenderingAttachmentInfo> colors = transparency.weightedAttachments(slot.transparency);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = slot.target.depth.view.get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    beginRendering(colors, depth);
    drawViews(pipelines, false);
    vkCmdEndRendering(cmd);
}

void FrameRecorder::copyOut(const Image& img, const Buffer& buf, bool readback) const {
    if (img.mapped) {
        // Read in place: GENERAL is the layout in which the host may read a linear image; the
        // fence that collect() waits for then makes the writes visible. A window frame blits
        // from GENERAL.
        imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
        return;
    }
    // To the whole transfer stage: a window frame blits the colour image afterwards.
    imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
    if (!readback) return;
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {slot.target.width, slot.target.height, 1};
    vkCmdCopyImageToBuffer(cmd, img.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.get(), 1,
                           &region);
}

// `drawn`: the pass clears it by drawing (gpu/ClearDraw.h), so its contents are not loaded.
VkRenderingAttachmentInfo attachment(const Image& target, const Image* multisampled,
                                     VkClearValue clear, bool drawn) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    a.loadOp = drawn ? VK_ATTACHMENT_LOAD_OP_DONT_CARE : VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.clearValue = clear;
    if (multisampled) {
        a.imageView = multisampled->view.get();
        a.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        a.resolveImageView = target.view.get();
        a.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    } else {
        a.imageView = target.view.get();
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    }
    return a;
}

// The AOV attachments of one pass, after the colour: normal+depth, ids and, when the frame asks
// for uv or range, the surface plane (otherwise the pass has one attachment fewer and the
// shader's writes to that location are discarded).
// (clear.frag writes the same background when the pass clears by drawing.)
void aovAttachments(const Target& t, bool drawn, std::vector<VkRenderingAttachmentInfo>& colors) {
    colors.resize(t.surface ? LANTERN_OUT_COUNT_AOV : LANTERN_OUT_SURFACE);
    VkClearValue normalDepthClear{};
    normalDepthClear.color.uint32[3] = LANTERN_FLT_MAX_BITS;  // background depth: the largest float
    VkClearValue surfaceClear{};
    surfaceClear.color.uint32[2] = LANTERN_FLT_MAX_BITS;  // background range; uv 0
    colors[LANTERN_OUT_NORMAL_DEPTH] = attachment(t.normalDepth, nullptr, normalDepthClear, drawn);
    colors[LANTERN_OUT_ID] = attachment(t.ids, nullptr, VkClearValue{}, drawn);
    if (t.surface)
        colors[LANTERN_OUT_SURFACE] = attachment(t.surfaceUvRange, nullptr, surfaceClear, drawn);
}

} // namespace

void recordFrame(VkPipelineLayout layout, const FramePasses& passes, FrameRing::Slot& slot,
                 const SceneBuffers& scene, const DrawList& list,
                 const FrameRing::ArenaLayout& arena, const FramePipelines& pipelines,
                 const SubmitHooks& hooks) {
    const FrameRecorder r{slot.cmd, layout, passes.overlays, slot, scene, list, arena};
    const VkCommandBuffer cmd = slot.cmd;
    Target& t = slot.target;
    if (slot.queries) vkCmdResetQueryPool(cmd, slot.queries, 0, 2);
    r.beginAttachments();
    if (slot.queries) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, slot.queries, 0);
    if (slot.deforming && passes.deformer) passes.deformer->record(cmd, slot.deform);
    if (slot.cull.any() && passes.culler) passes.culler->record(cmd, slot.cull);
    // The maps before anything that lights (the flat pass and the scene pass read them); a
    // frame without them makes its 1 x 1 stand-in readable, never read.
    if (slot.shadow.rendering)
        r.shadowMaps(*passes.shadows);
    else
        ShadowPass::transition(cmd, slot.shadow, VK_IMAGE_LAYOUT_UNDEFINED,
                               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    if (slot.flat.any() && passes.flatLighter)
        passes.flatLighter->record(cmd, slot.flat, slot.frameSet, arena.frameOffsets, arena.lightOffsets);
    const TransparencyMethod transparency = slot.transparency.method;
    passes.transparency->begin(cmd, slot.transparency, list.target.reversedZ);

    VkClearValue colorClear{};
    std::memcpy(colorClear.color.float32, &list.target.clear[0], 4 * sizeof(float));
    std::vector<VkRenderingAttachmentInfo> colors(
        t.aov && !t.multisampled() ? LANTERN_OUT_COUNT_AOV : 1);
    const bool drawn = slot.clear.scene != VK_NULL_HANDLE;
    colors[LANTERN_OUT_COLOR] =
        attachment(t.color, t.multisampled() ? &t.colorMsaa : nullptr, colorClear, drawn);
    if (t.aov && !t.multisampled()) aovAttachments(t, drawn, colors);
    const bool weighted = transparency == TransparencyMethod::Weighted;
    r.pass(colors, t.depth, slot.clear.scene, pipelines.main, weighted);
    if (weighted) r.weightedPass(*passes.transparency, pipelines.weighted);
    if (t.separateAovPass()) {
        // With MSAA the AOVs come from this single-sampled pass: each plane holds the surface
        // at the pixel centre, never a resolve of several samples.
        const bool aovDrawn = slot.clear.aov != VK_NULL_HANDLE;
        std::vector<VkRenderingAttachmentInfo> aov(LANTERN_OUT_COUNT_AOV);
        aov[LANTERN_OUT_COLOR] = attachment(t.aovColor, nullptr, colorClear, aovDrawn);
        aovAttachments(t, aovDrawn, aov);
        r.pass(aov, t.aovDepth, slot.clear.aov, pipelines.aov, false);
    }
    if (transparency != TransparencyMethod::Sorted)
        passes.transparency->composite(cmd, layout, slot.frameSet,
                                       frameSetOffsets(arena.frameOffsets[0], arena.lightOffsets[0]),
                                       slot.transparency, t);
    if (slot.queries)
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, slot.queries, 1);

    r.copyOut(t.color, t.readColor, hooks.readback);
    if (t.aov) {
        r.copyOut(t.normalDepth, t.readNormalDepth, hooks.readback);
        r.copyOut(t.ids, t.readIds, hooks.readback && list.target.readIds());
    }
    if (t.surface) r.copyOut(t.surfaceUvRange, t.readSurface, hooks.readback);
    // The copies, and the guard word the vertex stage or the flat pre-pass may have set, to
    // the host.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                           VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    if (hooks.afterRender)
        hooks.afterRender(cmd, t.color.get(),
                          t.color.mapped ? VK_IMAGE_LAYOUT_GENERAL
                                         : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          t.width, t.height);
}

} // namespace lantern::gpu
