// The frame slots: creation, submission (pipelines, uniform arena, descriptors, recording,
// queue submit) and collection (fence wait, timestamps, readback).
#include "gpu/FrameRing.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <future>

namespace lantern::gpu {
namespace {

// The lights' uniform binding: LANTERN_UNIFORM_LIGHTS of them (shaders/include/uniforms.glsl).
constexpr VkDeviceSize kUniformLightBytes = LANTERN_UNIFORM_LIGHTS * sizeof(LightData);

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

// Whether draw `k`'s colours are checked where they are made (shaders/include/guard.glsl):
// lit by the flat pre-pass (which always checks), the floor's constant, or lit in the vertex
// stage by a guarded variant when `vertexGuard` (the device lets that stage store and the
// frame has few enough vertices: vertexGuardPays). Phong lights per fragment and is
// never guarded, nor is a draw with an emissive map, which the fragment stage adds.
bool guardable(const PipelineKey& k, bool vertexGuard) {
    if (k.program == frame::Program::Floor) return true;
    if ((k.constants[LANTERN_SC_MAPS] & LANTERN_MAP_EMISSIVE) != 0u) return false;
    if (k.flatPerTriangle) return true;
    return vertexGuard && k.program != frame::Program::Phong;
}

// Whether checking in the vertex stage costs less than the host's pass over the picture. On
// llvmpipe the guarded vertex variant made the teapot grid's Gouraud frame 2-7 ms slower at
// 1 and 8 lights alike (71,160 vertices: about 40 ns per vertex, whatever the lights; the
// store, not the comparisons, seems to cost), while the host's pass costs about 1.3 ns per
// pixel (2.5-3 ms at 1920x1080 on two threads). So the vertex stage checks when the frame's
// vertices are fewer than a 32nd of its pixels: the peer sphere (2,145 vertices at 1080p) is
// guarded, the teapot grid at 720p is not. docs/performance.md has the measurements.
bool vertexGuardPays(const DrawList& list, const SceneBuffers& scene, bool flatPerTriangle) {
    std::uint64_t vertices = 0;
    for (const ViewCommands& v : list.views)
        for (const DrawCommand& d : v.draws) {
            const frame::Program p = d.pipeline.program;
            if (p == frame::Program::Phong || p == frame::Program::Floor ||
                FlatLighter::perTriangle(d.pipeline, flatPerTriangle))
                continue;
            const PrimitiveBuffers& gp = scene.primitive(d.mesh, d.primitive);
            // The per-corner flat streams are de-indexed: a vertex per corner.
            vertices += std::uint64_t(d.instanceCount) *
                        (p == frame::Program::Flat && gp.indexCount > 0 ? gp.indexCount
                                                                        : gp.vertexCount);
        }
    return vertices * 32 <= std::uint64_t(list.target.width) * list.target.height;
}

// A clear colour the guard's argument covers: finite, within the bound, alpha in [0, 1].
bool clearWithinGuard(const glm::vec4& c) {
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(c[i]) <= float(LANTERN_GUARD_BOUND))) return false;
    return c.a >= 0.0f && c.a <= 1.0f;
}

} // namespace

Result<std::unique_ptr<FrameRing>> FrameRing::create(Context& ctx, Pipelines& pipelines,
                                                     std::uint32_t slots) {
    std::unique_ptr<FrameRing> ring(new FrameRing(ctx, pipelines));
    std::uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &nq, families.data());
    ring->m_timestamps = families[ctx.queueFamily()].timestampValidBits > 0 &&
                         ctx.properties().limits.timestampPeriod > 0;
#ifdef LANTERN_TESTING_HOOKS
    // LANTERN_TEST_CLEAR=draw or load (tests only): clear by drawing, or with LOAD_OP_CLEAR,
    // whatever the device prefers, so that the two can be compared on one device.
    if (const char* env = std::getenv("LANTERN_TEST_CLEAR"))
        ring->m_clearByDraw = std::strcmp(env, "draw") == 0;
    // LANTERN_TEST_READBACK=staged (tests only), read when the renderer is made: every plane
    // staged, whatever the device allows, so that the two paths can be compared on one device.
    if (const char* env = std::getenv("LANTERN_TEST_READBACK"))
        ring->m_inPlace = std::strcmp(env, "staged") != 0;
#endif
    ring->m_slots.resize(std::max<std::uint32_t>(slots, 1));
    for (std::size_t i = 0; i < ring->m_slots.size(); ++i)
        LANTERN_TRY(ring->createSlot(ring->m_slots[i], i));
    return ring;
}

Result<void> FrameRing::createSlot(Slot& s, std::size_t index) {
    const VkDevice dev = m_ctx.device();
    VkCommandPoolCreateInfo cpci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cpci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    cpci.queueFamilyIndex = m_ctx.queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateCommandPool(dev, &cpci, nullptr, &pool));
    s.pool = UniqueCommandPool(dev, pool);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    LANTERN_VK_TRY(vkAllocateCommandBuffers(dev, &ai, &s.cmd));
    m_ctx.setName(VK_OBJECT_TYPE_COMMAND_BUFFER, s.cmd, "frame slot " + std::to_string(index));

    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateFence(dev, &fci, nullptr, &fence));
    s.fence = UniqueFence(dev, fence);

    VkDescriptorPoolSize sizes[5] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 2},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 1},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 7},
                                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}};
    VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpci.maxSets = 1;
    dpci.poolSizeCount = 5;
    dpci.pPoolSizes = sizes;
    VkDescriptorPool dp = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorPool(dev, &dpci, nullptr, &dp));
    s.descriptorPool = UniqueDescriptorPool(dev, dp);
    VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    dsai.descriptorPool = dp;
    dsai.descriptorSetCount = 1;
    VkDescriptorSetLayout fl = m_pipelines.frameSetLayout();
    dsai.pSetLayouts = &fl;
    LANTERN_VK_TRY(vkAllocateDescriptorSets(dev, &dsai, &s.frameSet));

    if (m_timestamps) {
        VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qci.queryCount = 2;
        LANTERN_VK_TRY(vkCreateQueryPool(dev, &qci, nullptr, &s.queries));
    }
    return {};
}

FrameRing::~FrameRing() {
    retireViews();
    m_ctx.waitIdle();
    for (Slot& s : m_slots)
        if (s.queries) vkDestroyQueryPool(m_ctx.device(), s.queries, nullptr);
}

// Pipelines (created on first use) and the flat-shading streams the per-corner path needs
// before recording. `flatPerTriangle`: flat triangles are lit by the pre-pass this frame.
// `guarded`: every draw of the colour pass is guarded (guardable()).
Result<void> FrameRing::preparePipelines(const DrawList& list, SceneBuffers& scene,
                                         bool flatPerTriangle, FramePipelines& out,
                                         bool& guarded) {
    const bool vertexGuard =
        m_ctx.capabilities().vertexStores &&
        (list.outputGuard == OutputGuard::Always ||
         (list.outputGuard == OutputGuard::Auto && vertexGuardPays(list, scene, flatPerTriangle)));
    guarded = list.outputGuard != OutputGuard::Never;
    const bool aovPass = list.target.aovs.any() && list.target.samples > 1;
    // The variants the draws use (and only those), the missing ones compiled together.
    const bool weightedPass = list.target.transparency == TransparencyMethod::Weighted;
    std::vector<PipelineKey> mainKeys, aovKeys, weightedKeys;
    std::vector<bool> mainDrawn, weightedDrawn;  // per draw: whether that pass draws it
    bool needFlat = false, needFlatTriangles = false;
    for (const ViewCommands& v : list.views)
        for (const DrawCommand& d : v.draws) {
            PipelineKey key = d.pipeline;
            key.flatPerTriangle = FlatLighter::perTriangle(d.pipeline, flatPerTriangle);
            PipelineKey single = key;
            single.blendPath = BlendPath::Over;  // the AOV pass's colour is not the picture
            if (aovPass) key.aov = key.aovSurface = false;
            key.guard = list.outputGuard != OutputGuard::Never && guardable(key, vertexGuard);
            guarded &= key.guard;
            // A weighted draw writes in the scene pass only its AOVs (its colour goes to the
            // weighted pass): without AOVs there, it is not drawn in it.
            const bool weighted = key.blend && key.blendPath == BlendPath::Weighted;
            mainDrawn.push_back(!weighted || key.aov);
            if (mainDrawn.back()) mainKeys.push_back(key);
            weightedDrawn.push_back(weightedPass && weighted);
            if (weightedDrawn.back()) {
                PipelineKey w = key;
                w.aov = w.aovSurface = false;
                w.weightedPass = true;
                weightedKeys.push_back(w);
            }
            if (aovPass) {
                single.samples = 1;
                single.aov = true;
                aovKeys.push_back(single);
            }
            const bool corners = d.pipeline.program == frame::Program::Flat && !key.flatPerTriangle;
            needFlat |= corners;
            needFlatTriangles |= corners && d.pipeline.topology == Topology::Triangles;
        }
    std::vector<PipelineKey> all = mainKeys;
    all.insert(all.end(), aovKeys.begin(), aovKeys.end());
    all.insert(all.end(), weightedKeys.begin(), weightedKeys.end());
    LANTERN_TRY(m_pipelines.prepare(all));
    // Per draw, in list order; a pass that does not draw it gets a null pipeline.
    auto resolve = [&](const std::vector<PipelineKey>& keys, const std::vector<bool>* drawn,
                       std::vector<VkPipeline>& pipelines) -> Result<void> {
        std::size_t k = 0;
        const std::size_t draws = drawn ? drawn->size() : keys.size();
        for (std::size_t i = 0; i < draws; ++i) {
            if (drawn && !(*drawn)[i]) {
                pipelines.push_back(VK_NULL_HANDLE);
                continue;
            }
            auto p = m_pipelines.pipeline(keys[k++]);
            if (!p) return std::move(p).error();
            pipelines.push_back(*p);
        }
        return {};
    };
    LANTERN_TRY(resolve(mainKeys, &mainDrawn, out.main));
    LANTERN_TRY(resolve(aovKeys, nullptr, out.aov));
    if (weightedPass) LANTERN_TRY(resolve(weightedKeys, &weightedDrawn, out.weighted));
    if (needFlat) LANTERN_TRY(scene.ensureFlatStreams(needFlatTriangles));
    return {};
}

// The compute pre-passes: skinning and morphing, then the per-triangle flat lighting, which
// reads the deformed positions.
Result<void> FrameRing::preparePrePasses(Slot& slot, const DrawList& list,
                                         const SceneBuffers& scene, bool flatPerTriangle) {
    slot.deforming = !list.deforms.empty();
    if (slot.deforming) {
        if (!scene.deformInput())
            return makeError(ErrorCode::Internal,
                             "a draw list deforms a scene uploaded without deformation inputs");
        if (!m_deformer) {
            auto deformer = Deformer::create(m_ctx, m_pipelines);
            if (!deformer) return std::move(deformer).error();
            m_deformer = std::move(*deformer);
        }
        LANTERN_TRY(m_deformer->prepare(slot.deform, list, scene, flatPerTriangle));
    }
    bool litPerTriangle = false;
    for (const ViewCommands& v : list.views)
        for (const DrawCommand& d : v.draws)
            litPerTriangle |= FlatLighter::perTriangle(d.pipeline, flatPerTriangle);
    if (litPerTriangle && !m_flatLighter) {
        auto lighter = FlatLighter::create(m_ctx, m_pipelines);
        if (!lighter) return std::move(lighter).error();
        m_flatLighter = std::move(*lighter);
    }
    if (m_flatLighter)
        LANTERN_TRY(m_flatLighter->prepare(slot.flat, list, scene,
                                           slot.deforming ? &slot.deform : nullptr, flatPerTriangle));
    if (list.clusterCulling && scene.clusters() && !m_culler) {
        auto culler = Culler::create(m_ctx, m_pipelines);
        if (!culler) return std::move(culler).error();
        m_culler = std::move(*culler);
    }
    slot.cull.recordCount = 0;
    if (m_culler) LANTERN_TRY(m_culler->prepare(slot.cull, list, scene));
    if (!m_shadowPass) {
        auto shadows = ShadowPass::create(m_ctx, m_pipelines);
        if (!shadows) return std::move(shadows).error();
        m_shadowPass = std::move(*shadows);
    }
    LANTERN_TRY(m_shadowPass->prepare(slot.shadow, list));
    if (!m_transparency) {
        auto transparency = TransparencyPass::create(m_ctx, m_pipelines);
        if (!transparency) return std::move(transparency).error();
        m_transparency = std::move(*transparency);
    }
    return m_transparency->prepare(slot.transparency, list.target);
}

// The uniform arena: materials, then per view its FrameBlock and its lights, at the device's
// offset alignments (the frame set points into them with dynamic offsets), the output guard,
// the instanced draws' transforms, the shadow passes' FrameBlocks and the shadow lookups.
Result<FrameRing::ArenaLayout> FrameRing::fillArena(Slot& slot, const DrawList& list) {
    const auto& lim = m_ctx.properties().limits;
    const VkDeviceSize uboAlign = std::max<VkDeviceSize>(lim.minUniformBufferOffsetAlignment, 16);
    const VkDeviceSize ssboAlign = std::max<VkDeviceSize>(lim.minStorageBufferOffsetAlignment, 16);
    ArenaLayout a;
    a.materialBytes = list.materials.size() * sizeof(MaterialData);
    VkDeviceSize size = alignUp(a.materialBytes, std::max(uboAlign, ssboAlign));
    std::size_t maxLights = 1;
    for (const ViewCommands& v : list.views) {
        size = alignUp(size, uboAlign);
        a.frameOffsets.push_back(size);
        size += sizeof(FrameBlock);
        size = alignUp(size, std::max(uboAlign, ssboAlign));  // read as either (uniforms.glsl)
        a.lightOffsets.push_back(size);
        size += std::max<std::size_t>(v.lights.size(), 1) * sizeof(LightData);
        maxLights = std::max(maxLights, v.lights.size());
    }
    a.lightRange = maxLights * sizeof(LightData);
    // The uniform binding always spans LANTERN_UNIFORM_LIGHTS lights, the block's size; a
    // variant reads it only with at most that many (render/Variants.cpp).
    a.guardOffset = alignUp(std::max({size, a.lightOffsets.back() + a.lightRange,
                                      a.lightOffsets.back() + kUniformLightBytes}),
                            ssboAlign);
    a.instanceOffset = a.guardOffset + ssboAlign;
    a.instanceBytes = list.instances.size() * sizeof(InstanceData);
    size = a.instanceOffset + std::max<VkDeviceSize>(a.instanceBytes, sizeof(InstanceData));
    for (std::size_t i = 0; i < list.shadows.passes.size(); ++i) {
        size = alignUp(size, uboAlign);
        a.shadowFrameOffsets.push_back(size);
        size += sizeof(FrameBlock);
    }
    a.shadowOffset = alignUp(size, ssboAlign);
    a.shadowBytes = list.shadows.lookups.size() * sizeof(ShadowData);
    a.size = a.shadowOffset + std::max<VkDeviceSize>(a.shadowBytes, sizeof(ShadowData));
    if (slot.arena.size < a.size) {
        auto arena = createBuffer(m_ctx, a.size * 2,
                                  VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  MemoryUsage::Upload, "frame arena");
        if (!arena) return std::move(arena).error();
        slot.arena = std::move(*arena);
    }
    char* base = static_cast<char*>(slot.arena.mapped);
    std::memcpy(base, list.materials.data(), a.materialBytes);
    for (std::size_t i = 0; i < list.views.size(); ++i) {
        std::memcpy(base + a.frameOffsets[i], &list.views[i].frame, sizeof(FrameBlock));
        std::memcpy(base + a.lightOffsets[i], list.views[i].lights.data(),
                    list.views[i].lights.size() * sizeof(LightData));
    }
    std::memset(base + a.guardOffset, 0, 16);  // the output guard, cleared (guard.glsl)
    if (a.instanceBytes > 0)
        std::memcpy(base + a.instanceOffset, list.instances.data(), a.instanceBytes);
    for (std::size_t i = 0; i < a.shadowFrameOffsets.size(); ++i)
        std::memcpy(base + a.shadowFrameOffsets[i], &list.shadows.passes[i], sizeof(FrameBlock));
    if (a.shadowBytes > 0)
        std::memcpy(base + a.shadowOffset, list.shadows.lookups.data(), a.shadowBytes);
    slot.guardOffset = a.guardOffset;
    LANTERN_TRY(flush(m_ctx, slot.arena));
    writeFrameSet(slot, a);
    return a;
}

// Points the slot's frame set at this frame's arena, shadow maps and flat records.
void FrameRing::writeFrameSet(Slot& slot, const ArenaLayout& a) {
    writeBufferDescriptors(
        m_ctx, slot.frameSet,
        {{LANTERN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
          {slot.arena.get(), 0, sizeof(FrameBlock)}},
         {LANTERN_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC,
          {slot.arena.get(), 0, a.lightRange}},
         {LANTERN_BINDING_LIGHTS_UNIFORM, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
          {slot.arena.get(), 0, kUniformLightBytes}},
         {LANTERN_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
          {slot.arena.get(), 0, std::max<VkDeviceSize>(a.materialBytes, sizeof(MaterialData))}},
         {LANTERN_BINDING_GUARD, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
          {slot.arena.get(), a.guardOffset, 16}},
         {LANTERN_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
          {slot.arena.get(), a.instanceOffset, a.shadowOffset - a.instanceOffset}},
         {LANTERN_BINDING_SHADOWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
          {slot.arena.get(), a.shadowOffset, a.size - a.shadowOffset}}});
    m_shadowPass->writeDescriptors(slot.frameSet, slot.shadow);
    // The per-triangle flat records; a frame without them points the bindings at the arena
    // (never read).
    const FlatSlot& f = slot.flat;
    const VkDescriptorBufferInfo colors = f.any()
        ? VkDescriptorBufferInfo{f.records.get(), 0, f.recordBytes}
        : VkDescriptorBufferInfo{slot.arena.get(), 0, 16};
    const VkDescriptorBufferInfo normals = f.any()
        ? VkDescriptorBufferInfo{f.records.get(), f.normalOffset, f.normalBytes}
        : VkDescriptorBufferInfo{slot.arena.get(), 0, 16};
    writeBufferDescriptors(m_ctx, slot.frameSet,
                           {{LANTERN_BINDING_FLAT_COLORS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, colors},
                            {LANTERN_BINDING_FLAT_NORMALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, normals}});
    m_transparency->writeDescriptors(slot.frameSet, slot.transparency, {slot.arena.get(), 0, 16});
}

Result<void> FrameRing::queueSubmit(Slot& slot, const SubmitHooks& hooks) {
    VkFence fence = slot.fence.get();
    LANTERN_VK_TRY(vkResetFences(m_ctx.device(), 1, &fence));
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = slot.cmd;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cbi;
    VkSemaphoreSubmitInfo waitInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    waitInfo.semaphore = hooks.wait;
    waitInfo.stageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    VkSemaphoreSubmitInfo signalInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signalInfo.semaphore = hooks.signal;
    signalInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    si.waitSemaphoreInfoCount = hooks.wait ? 1 : 0;
    si.pWaitSemaphoreInfos = &waitInfo;
    si.signalSemaphoreInfoCount = hooks.signal ? 1 : 0;
    si.pSignalSemaphoreInfos = &signalInfo;
    std::lock_guard lock(m_ctx.queueMutex());
    LANTERN_VK_TRY(vkQueueSubmit2(m_ctx.queue(), 1, &si, fence));
    return {};
}

Result<std::uint32_t> FrameRing::submit(const DrawList& list,
                                        const std::shared_ptr<SceneBuffers>& scene,
                                        const SubmitHooks& hooks) {
    if (scene->context() != &m_ctx)
        return makeError(ErrorCode::Usage, "the scene was prepared by another Renderer (a "
                                           "PreparedScene lives on its renderer's device)");
    const std::uint32_t index = m_next;
    Slot& slot = m_slots[index];
    retireViews();  // this frame may rewrite (or reallocate) what a view reads
    if (slot.busy)
        return makeError(ErrorCode::Usage, "frame slot " + std::to_string(index) +
                                               " is still in flight; collect it first");
    if (list.target.transparency == TransparencyMethod::Exact && !m_ctx.capabilities().fragmentStores)
        return makeError(ErrorCode::Unsupported,
                         "the device lacks fragmentStoresAndAtomics, which exact transparency (the "
                         "default for blended materials) needs: use --transparency sorted",
                         "--transparency");
    if (list.target.transparency == TransparencyMethod::Weighted && !m_ctx.capabilities().independentBlend)
        return makeError(ErrorCode::Unsupported,
                         "the device lacks independentBlend, which weighted transparency needs: "
                         "use --transparency sorted or exact",
                         "--transparency");
    LANTERN_TRY(ensureTarget(m_ctx, slot.target, list.target, m_inPlace));
    slot.desc = list.target;
    FramePipelines pipelines;
    const bool flatPerTriangle = FlatLighter::available(m_ctx, *scene, list);
    bool guardedDraws = false;
    // Clearing by drawing (gpu/ClearDraw.h): a missing clear pipeline is compiled on a thread
    // of its own while this one makes the scene's, so on a first frame the two JIT compiles
    // overlap.
    slot.clear = {};
    std::future<Result<ClearFrame>> clear;
    if (m_clearByDraw.value_or(ClearDraw::preferred(m_ctx, slot.target.width, slot.target.height,
                                                    !m_submittedOnce))) {
        if (!m_clearDraw) {
            auto made = ClearDraw::create(m_ctx, m_pipelines);
            if (!made) return std::move(made).error();
            m_clearDraw = std::move(*made);
        }
        clear = std::async(m_clearDraw->ready(slot.target) ? std::launch::deferred : std::launch::async,
                           [this, &slot] { return m_clearDraw->prepare(slot.target); });
    }
    LANTERN_TRY(preparePipelines(list, *scene, flatPerTriangle, pipelines, guardedDraws));
    if (clear.valid()) {
        auto made = clear.get();
        if (!made) return std::move(made).error();
        slot.clear = *made;
    }
    slot.overlays = {};
    if (list.overlays.any()) {
        if (!m_overlays) m_overlays = std::make_unique<OverlayPipelines>(m_ctx, m_pipelines);
        auto overlays = m_overlays->prepare(list.overlays, list.target);
        if (!overlays) return std::move(overlays).error();
        slot.overlays = *overlays;
    }
    LANTERN_TRY(preparePrePasses(slot, list, *scene, flatPerTriangle));
    auto arena = fillArena(slot, list);
    if (!arena) return std::move(arena).error();

    LANTERN_VK_TRY(vkResetCommandPool(m_ctx.device(), slot.pool.get(), 0));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    LANTERN_VK_TRY(vkBeginCommandBuffer(slot.cmd, &bi));
    const FramePasses passes{m_overlays.get(), m_deformer.get(), m_flatLighter.get(),
                             m_shadowPass.get(), m_transparency.get(), m_culler.get()};
    recordFrame(m_pipelines.layout(), passes, slot, *scene, list, *arena, pipelines, hooks);
    LANTERN_VK_TRY(vkEndCommandBuffer(slot.cmd));
    LANTERN_TRY(queueSubmit(slot, hooks));
    m_submittedOnce = true;
    slot.scene = scene;
    slot.busy = true;
    slot.readback = hooks.readback;
    slot.draws = pipelines.main.size();
    // The overlays' constant colours are not guarded: a frame with them is checked on the host;
    // nor are the weighted sums, which divide (shaders/weighted_resolve.frag).
    slot.guarded = guardedDraws && !list.overlays.any() && clearWithinGuard(list.target.clear) &&
                   list.target.transparency != TransparencyMethod::Weighted;
    m_next = (m_next + 1) % std::uint32_t(m_slots.size());
    return index;
}

void FrameRing::retireViews() {
    if (m_viewsLive.use_count() == 1) return;  // no view holds it: nothing to tell
    *m_viewsLive = false;
    m_viewsLive = std::make_shared<std::atomic<bool>>(true);
}

Result<FrameReadback> FrameRing::collect(std::uint32_t index, lantern::Image storage,
                                         bool inPlace) {
    Slot& slot = m_slots[index];
    if (!slot.busy)
        return makeError(ErrorCode::Usage, "frame slot " + std::to_string(index) + " holds no frame");
    VkFence fence = slot.fence.get();
    slot.busy = false;
    const VkResult wait = vkWaitForFences(m_ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX);
    const VkResult injected = injectedVkFault("vkWaitForFences");
    slot.scene.reset();
    if (wait != VK_SUCCESS) return vkError(wait, "vkWaitForFences");
    if (injected != VK_SUCCESS) return vkError(injected, "vkWaitForFences");
    HostView view;
    view.live = m_viewsLive;
    auto frame = readBack(m_ctx, slot, std::move(storage), inPlace ? &view : nullptr);
    if (frame && m_transparency) m_transparency->readCounts(slot.transparency, *frame);
    return frame;
}

} // namespace lantern::gpu
