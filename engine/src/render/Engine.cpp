// Pipelines, targets, frame slots: records a FramePlan with dynamic rendering, submits it and
// reads the picture (and AOVs) back.
#include "render/Engine.h"

#include "ShaderBlobs.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

namespace lantern::render {
namespace {

using shaders::ShaderId;

constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kNormalDepthFormat = VK_FORMAT_R32G32B32A32_UINT;
constexpr VkFormat kIdFormat = VK_FORMAT_R32G32_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

struct ProgramShaders {
    ShaderId vertex, fragment, fragmentAov;
};

ProgramShaders programShaders(Program p) {
    switch (p) {
    case Program::Phong: return {ShaderId::mesh_vert, ShaderId::phong_frag, ShaderId::phong_aov_frag};
    case Program::Gouraud:
        return {ShaderId::gouraud_vert, ShaderId::gouraud_frag, ShaderId::gouraud_aov_frag};
    case Program::Flat: return {ShaderId::flat_vert, ShaderId::flat_frag, ShaderId::flat_aov_frag};
    case Program::GlFlat: return {ShaderId::glflat_vert, ShaderId::flat_frag, ShaderId::flat_aov_frag};
    case Program::Floor: return {ShaderId::mesh_vert, ShaderId::floor_frag, ShaderId::floor_aov_frag};
    }
    return {ShaderId::mesh_vert, ShaderId::phong_frag, ShaderId::phong_aov_frag};
}

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

std::uint32_t floatBits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
float bitsFloat(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

} // namespace

Result<std::unique_ptr<Engine>> Engine::create(std::shared_ptr<gpu::Context> ctx,
                                               std::uint32_t framesInFlight) {
    std::unique_ptr<Engine> e(new Engine());
    e->m_ctx = std::move(ctx);
    gpu::Context& c = *e->m_ctx;
    const VkDevice dev = c.device();

    const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    VkDescriptorSetLayoutBinding frameBindings[3] = {
        {LANTERN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, both, nullptr},
        {LANTERN_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 1, both, nullptr},
        {LANTERN_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, both, nullptr},
    };
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = 3;
    lci.pBindings = frameBindings;
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &layout));
    e->m_frameLayout = gpu::UniqueDescriptorSetLayout(dev, layout);

    VkDescriptorSetLayoutBinding textureBinding{LANTERN_BINDING_BASE_COLOR,
                                                VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                                VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    lci.bindingCount = 1;
    lci.pBindings = &textureBinding;
    LANTERN_VK_TRY(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &layout));
    e->m_textureLayout = gpu::UniqueDescriptorSetLayout(dev, layout);

    VkDescriptorSetLayout setLayouts[2] = {e->m_frameLayout.get(), e->m_textureLayout.get()};
    VkPushConstantRange push{both, 0, sizeof(DrawBlock)};
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = 2;
    plci.pSetLayouts = setLayouts;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &push;
    VkPipelineLayout pl = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreatePipelineLayout(dev, &plci, nullptr, &pl));
    e->m_pipelineLayout = gpu::UniquePipelineLayout(dev, pl);

    e->m_shaders.resize(shaders::kShaderCount);

    std::uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(c.physicalDevice(), &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(c.physicalDevice(), &nq, families.data());
    e->m_timestamps = families[c.queueFamily()].timestampValidBits > 0 &&
                      c.properties().limits.timestampPeriod > 0;

    e->m_slots.resize(std::max<std::uint32_t>(framesInFlight, 1));
    for (std::size_t i = 0; i < e->m_slots.size(); ++i) {
        Slot& s = e->m_slots[i];
        VkCommandPoolCreateInfo cpci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        cpci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        cpci.queueFamilyIndex = c.queueFamily();
        VkCommandPool pool = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateCommandPool(dev, &cpci, nullptr, &pool));
        s.pool = gpu::UniqueCommandPool(dev, pool);
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        LANTERN_VK_TRY(vkAllocateCommandBuffers(dev, &ai, &s.cmd));
        c.setName(VK_OBJECT_TYPE_COMMAND_BUFFER, s.cmd, "frame slot " + std::to_string(i));

        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence fence = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateFence(dev, &fci, nullptr, &fence));
        s.fence = gpu::UniqueFence(dev, fence);

        VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 1},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
        VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpci.maxSets = 1;
        dpci.poolSizeCount = 3;
        dpci.pPoolSizes = sizes;
        VkDescriptorPool dp = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateDescriptorPool(dev, &dpci, nullptr, &dp));
        s.descriptorPool = gpu::UniqueDescriptorPool(dev, dp);
        VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        dsai.descriptorPool = dp;
        dsai.descriptorSetCount = 1;
        VkDescriptorSetLayout fl = e->m_frameLayout.get();
        dsai.pSetLayouts = &fl;
        LANTERN_VK_TRY(vkAllocateDescriptorSets(dev, &dsai, &s.frameSet));

        if (e->m_timestamps) {
            VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
            qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qci.queryCount = 2;
            LANTERN_VK_TRY(vkCreateQueryPool(dev, &qci, nullptr, &s.queries));
        }
    }
    return e;
}

Engine::~Engine() {
    if (!m_ctx) return;
    m_ctx->waitIdle();
    for (Slot& s : m_slots)
        if (s.queries) vkDestroyQueryPool(m_ctx->device(), s.queries, nullptr);
}

Result<void> Engine::checkOptions(const RenderOptions& o) const {
    const auto& lim = m_ctx->properties().limits;
    if (o.width < 1 || o.height < 1)
        return makeError(ErrorCode::InvalidInput,
                         "image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             " is empty",
                         "--width/--height");
    if (std::uint32_t(o.width) > lim.maxImageDimension2D ||
        std::uint32_t(o.height) > lim.maxImageDimension2D)
        return makeError(ErrorCode::InvalidInput,
                         "image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             " exceeds the device's maximum of " +
                             std::to_string(lim.maxImageDimension2D) + " pixels per side",
                         "--width/--height");
    if (o.msaa != 1 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8)
        return makeError(ErrorCode::InvalidInput,
                         "sample count " + std::to_string(o.msaa) + " is not 1, 2, 4 or 8", "--msaa");
    if (!(m_ctx->capabilities().colorDepthSampleCounts & std::uint32_t(o.msaa)))
        return makeError(ErrorCode::Unsupported,
                         "the device does not support " + std::to_string(o.msaa) +
                             " samples per pixel for float colour and depth",
                         "--msaa");
    if (o.aovs.any() && !m_ctx->capabilities().primitiveIdInFragment)
        return makeError(ErrorCode::Unsupported,
                         "the device lacks the geometryShader feature that the AOV shaders "
                         "need (gl_PrimitiveID in the fragment stage)",
                         "--aov");
    // Memory estimate for one frame slot, refused before anything is allocated.
    const double pixels = double(o.width) * double(o.height);
    double perPixel = 16 + 16 + 4 * o.msaa;              // colour, readback, depth
    if (o.msaa > 1) perPixel += 16.0 * o.msaa;           // multisampled colour
    if (o.aovs.any()) perPixel += (16 + 8) * 2.0 + (o.msaa > 1 ? 16 + 4 : 0);  // + AOV pass scratch
    const double bytes = pixels * perPixel * double(m_slots.size());
    VkDeviceSize heap = 0;
    const auto& mem = m_ctx->memoryProperties();
    for (std::uint32_t i = 0; i < mem.memoryHeapCount; ++i)
        if (mem.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            heap = std::max(heap, mem.memoryHeaps[i].size);
    if (heap > 0 && bytes > double(heap) * 0.9)
        return makeError(ErrorCode::OutOfMemory,
                         "a " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             " image needs about " + std::to_string(std::llround(bytes / 1048576.0)) +
                             " MiB of device memory; the device has " +
                             std::to_string(heap / 1048576) + " MiB",
                         "--width/--height");
    return DebugDraw::checkOptions(*m_ctx, o);
}

Result<VkShaderModule> Engine::shader(std::uint32_t id) {
    if (!m_shaders[id]) {
        const shaders::ShaderBlob blob = shaders::shaderBlob(ShaderId(id));
        auto module = gpu::createShaderModule(*m_ctx, {blob.words, blob.wordCount},
                                              std::string(blob.name));
        if (!module) return std::move(module).error();
        m_shaders[id] = std::move(*module);
    }
    return m_shaders[id].get();
}

Result<VkPipeline> Engine::pipeline(const VariantKey& key) {
    if (auto it = m_pipelines.find(key); it != m_pipelines.end()) return it->second.get();
    const ProgramShaders ps = programShaders(key.program);
    auto vs = shader(std::uint32_t(ps.vertex));
    if (!vs) return std::move(vs).error();
    auto fs = shader(std::uint32_t(key.aov ? ps.fragmentAov : ps.fragment));
    if (!fs) return std::move(fs).error();

    gpu::GraphicsPipelineDesc d;
    d.layout = m_pipelineLayout.get();
    d.vertex = *vs;
    d.fragment = *fs;
    for (std::uint32_t i = 0; i < LANTERN_SC_COUNT; ++i) {
        d.specEntries.push_back({i, i * 4u, 4u});
        d.specData.push_back(key.constants[i]);
    }
    const std::uint32_t bindings = key.program == Program::Flat ? 5u : 4u;
    const VkFormat formats[5] = {VK_FORMAT_R32G32B32_SFLOAT, VK_FORMAT_R32G32B32_SFLOAT,
                                 VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32_SFLOAT,
                                 VK_FORMAT_R32G32B32_SFLOAT};
    const std::uint32_t strides[5] = {12, 12, 16, 8, 12};
    for (std::uint32_t b = 0; b < bindings; ++b) {
        d.bindings.push_back({b, strides[b], VK_VERTEX_INPUT_RATE_VERTEX});
        d.attributes.push_back({b, b, formats[b], 0});
    }
    d.colorFormats = {kColorFormat};
    if (key.aov) {
        d.colorFormats.push_back(kNormalDepthFormat);
        d.colorFormats.push_back(kIdFormat);
    }
    d.depthFormat = kDepthFormat;
    d.samples = VkSampleCountFlagBits(key.samples);
    d.blend = key.blend;
    d.depthWrite = !key.blend;
    // GL's default depth test is strict: the first of two equal depths wins.
    d.depthCompare = key.reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
    d.provokingLast = key.program == Program::GlFlat;
    d.name = key.describe();
    auto p = gpu::createGraphicsPipeline(*m_ctx, d);
    if (!p) return std::move(p).error();
    const VkPipeline handle = p->get();
    m_pipelines.emplace(key, std::move(*p));
    m_ctx->log(LogLevel::Debug, "pipeline variant created: " + key.describe());
    return handle;
}

Result<void> Engine::ensureTarget(Slot& slot, const RenderOptions& o) {
    Target& t = slot.target;
    const std::uint32_t w = std::uint32_t(o.width), h = std::uint32_t(o.height),
                        samples = std::uint32_t(o.msaa);
    const bool aov = o.aovs.any();
    if (t.width == w && t.height == h && t.samples == samples && t.aov == aov) return {};
    t = Target{};
    auto make = [&](gpu::Image& img, VkFormat format, VkSampleCountFlagBits s, VkImageUsageFlags usage,
                    VkImageAspectFlags aspect, const char* name) -> Result<void> {
        gpu::ImageDesc d;
        d.format = format;
        d.width = w;
        d.height = h;
        d.samples = s;
        d.usage = usage;
        d.aspect = aspect;
        d.name = name;
        auto r = gpu::createImage(*m_ctx, d);
        if (!r) return std::move(r).error();
        img = std::move(*r);
        return {};
    };
    const auto ms = VkSampleCountFlagBits(samples);
    const VkImageUsageFlags single = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const VkImageUsageFlags multi = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    LANTERN_TRY(make(t.color, kColorFormat, VK_SAMPLE_COUNT_1_BIT, single, VK_IMAGE_ASPECT_COLOR_BIT, "colour"));
    if (samples > 1)
        LANTERN_TRY(make(t.colorMsaa, kColorFormat, ms, multi, VK_IMAGE_ASPECT_COLOR_BIT, "colour msaa"));
    LANTERN_TRY(make(t.depth, kDepthFormat, ms, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                     VK_IMAGE_ASPECT_DEPTH_BIT, "depth"));
    const VkDeviceSize pixels = VkDeviceSize(w) * h;
    auto readback = [&](gpu::Buffer& b, VkDeviceSize bytes, const char* name) -> Result<void> {
        auto r = gpu::createBuffer(*m_ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   gpu::MemoryUsage::Readback, name);
        if (!r) return std::move(r).error();
        b = std::move(*r);
        return {};
    };
    LANTERN_TRY(readback(t.readColor, pixels * 16, "colour readback"));
    if (aov) {
        LANTERN_TRY(make(t.normalDepth, kNormalDepthFormat, VK_SAMPLE_COUNT_1_BIT, single,
                         VK_IMAGE_ASPECT_COLOR_BIT, "aov normal+depth"));
        LANTERN_TRY(make(t.ids, kIdFormat, VK_SAMPLE_COUNT_1_BIT, single, VK_IMAGE_ASPECT_COLOR_BIT,
                         "aov ids"));
        if (samples > 1) {
            // The single-sampled AOV pass draws into these (its colour output is discarded).
            LANTERN_TRY(make(t.aovColor, kColorFormat, VK_SAMPLE_COUNT_1_BIT,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                             "aov pass colour"));
            LANTERN_TRY(make(t.aovDepth, kDepthFormat, VK_SAMPLE_COUNT_1_BIT,
                             VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
                             "aov pass depth"));
        }
        LANTERN_TRY(readback(t.readNormalDepth, pixels * 16, "aov normal+depth readback"));
        LANTERN_TRY(readback(t.readIds, pixels * 8, "aov ids readback"));
    }
    t.width = w;
    t.height = h;
    t.samples = samples;
    t.aov = aov;
    return {};
}

Result<std::uint32_t> Engine::submit(const std::shared_ptr<GpuScene>& scene, const FramePlan& plan,
                                     const RenderOptions& o, const SubmitHooks& hooks) {
    if (scene->context() != m_ctx.get())
        return makeError(ErrorCode::Usage, "the scene was prepared by another Renderer (a "
                                           "PreparedScene lives on its renderer's device)");
    const std::uint32_t index = m_next;
    Slot& slot = m_slots[index];
    if (slot.busy)
        return makeError(ErrorCode::Usage, "frame slot " + std::to_string(index) +
                                               " is still in flight; collect it first");
    LANTERN_TRY(ensureTarget(slot, o));

    // Pipelines (created on first use) and flat streams before recording.
    // With MSAA the AOVs are drawn in a second, single-sampled pass: integer attachments cannot
    // be multisampled on every device (lavapipe), and an AOV is one value per pixel anyway.
    const bool aovPass = o.aovs.any() && o.msaa > 1;
    std::vector<VkPipeline> pipelines, aovPipelines;
    bool needFlat = false;
    for (const ViewPlan& v : plan.views)
        for (const DrawItem& d : v.draws) {
            VariantKey main = d.key;
            if (aovPass) main.aov = false;
            auto p = pipeline(main);
            if (!p) return std::move(p).error();
            pipelines.push_back(*p);
            if (aovPass) {
                VariantKey aov = d.key;
                aov.samples = 1;
                aov.aov = true;
                auto a = pipeline(aov);
                if (!a) return std::move(a).error();
                aovPipelines.push_back(*a);
            }
            needFlat |= d.key.program == Program::Flat;
        }
    if (needFlat) LANTERN_TRY(scene->ensureFlatStreams());
    slot.debug = {};
    if (o.wireframe || o.normals) {
        if (!m_debug) m_debug = std::make_unique<DebugDraw>(*m_ctx, m_pipelineLayout.get());
        auto debug = m_debug->prepare(o, *scene, plan);
        if (!debug) return std::move(debug).error();
        slot.debug = *debug;
    }

    // The uniform arena: materials, then per view its FrameBlock and its lights.
    const auto& lim = m_ctx->properties().limits;
    const VkDeviceSize uboAlign = std::max<VkDeviceSize>(lim.minUniformBufferOffsetAlignment, 16);
    const VkDeviceSize ssboAlign = std::max<VkDeviceSize>(lim.minStorageBufferOffsetAlignment, 16);
    const VkDeviceSize materialBytes = plan.materials.size() * sizeof(MaterialData);
    VkDeviceSize size = alignUp(materialBytes, std::max(uboAlign, ssboAlign));
    std::vector<VkDeviceSize> frameOffsets, lightOffsets;
    std::size_t maxLights = 1;
    for (const ViewPlan& v : plan.views) {
        size = alignUp(size, uboAlign);
        frameOffsets.push_back(size);
        size += sizeof(FrameBlock);
        size = alignUp(size, ssboAlign);
        lightOffsets.push_back(size);
        size += std::max<std::size_t>(v.lights.size(), 1) * sizeof(LightData);
        maxLights = std::max(maxLights, v.lights.size());
    }
    const VkDeviceSize lightRange = maxLights * sizeof(LightData);
    size = std::max(size, lightOffsets.back() + lightRange);
    if (slot.arena.size < size) {
        auto arena = gpu::createBuffer(*m_ctx, size * 2,
                                       VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       gpu::MemoryUsage::Upload, "frame arena");
        if (!arena) return std::move(arena).error();
        slot.arena = std::move(*arena);
    }
    char* base = static_cast<char*>(slot.arena.mapped);
    std::memcpy(base, plan.materials.data(), materialBytes);
    for (std::size_t i = 0; i < plan.views.size(); ++i) {
        std::memcpy(base + frameOffsets[i], &plan.views[i].frame, sizeof(FrameBlock));
        std::memcpy(base + lightOffsets[i], plan.views[i].lights.data(),
                    plan.views[i].lights.size() * sizeof(LightData));
    }
    LANTERN_TRY(gpu::flush(*m_ctx, slot.arena));

    VkDescriptorBufferInfo infos[3] = {
        {slot.arena.get(), 0, sizeof(FrameBlock)},
        {slot.arena.get(), 0, lightRange},
        {slot.arena.get(), 0, std::max<VkDeviceSize>(materialBytes, sizeof(MaterialData))},
    };
    VkWriteDescriptorSet writes[3]{};
    const VkDescriptorType types[3] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
                                       VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC,
                                       VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    for (std::uint32_t i = 0; i < 3; ++i) {
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = slot.frameSet;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = types[i];
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(m_ctx->device(), 3, writes, 0, nullptr);

    LANTERN_VK_TRY(vkResetCommandPool(m_ctx->device(), slot.pool.get(), 0));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    LANTERN_VK_TRY(vkBeginCommandBuffer(slot.cmd, &bi));
    slot.clearColor[0] = o.background.r;
    slot.clearColor[1] = o.background.g;
    slot.clearColor[2] = o.background.b;
    slot.clearColor[3] = o.background.a;
    // Reversed-Z clears to 0 (infinitely far), standard depth to 1.
    slot.clearDepth = o.depth == DepthMode::ReversedZ ? 0.0f : 1.0f;
    record(slot, *scene, plan, frameOffsets, lightOffsets, pipelines, aovPipelines, hooks);
    LANTERN_VK_TRY(vkEndCommandBuffer(slot.cmd));

    VkFence fence = slot.fence.get();
    LANTERN_VK_TRY(vkResetFences(m_ctx->device(), 1, &fence));
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
    {
        std::lock_guard lock(m_ctx->queueMutex());
        LANTERN_VK_TRY(vkQueueSubmit2(m_ctx->queue(), 1, &si, fence));
    }
    slot.scene = scene;
    slot.busy = true;
    slot.readback = hooks.readback;
    slot.draws = pipelines.size();
    m_next = (m_next + 1) % std::uint32_t(m_slots.size());
    return index;
}

void Engine::record(Slot& slot, GpuScene& scene, const FramePlan& plan,
                    const std::vector<VkDeviceSize>& frameOffsets,
                    const std::vector<VkDeviceSize>& lightOffsets,
                    const std::vector<VkPipeline>& pipelines,
                    const std::vector<VkPipeline>& aovPipelines, const SubmitHooks& hooks) {
    const VkCommandBuffer cmd = slot.cmd;
    Target& t = slot.target;
    const bool msaa = t.samples > 1;
    const bool aovPass = t.aov && msaa;

    if (slot.queries) vkCmdResetQueryPool(cmd, slot.queries, 0, 2);

    std::vector<VkImage> colorImages{t.color.get()};
    std::vector<VkImage> depthImages{t.depth.get()};
    if (msaa) colorImages.push_back(t.colorMsaa.get());
    if (t.aov) {
        colorImages.push_back(t.normalDepth.get());
        colorImages.push_back(t.ids.get());
    }
    if (aovPass) {
        colorImages.push_back(t.aovColor.get());
        depthImages.push_back(t.aovDepth.get());
    }
    for (VkImage img : colorImages)
        gpu::imageBarrier(cmd, img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
    for (VkImage img : depthImages)
        gpu::imageBarrier(cmd, img, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                          VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                          VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
    if (slot.queries)
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, slot.queries, 0);

    auto attachment = [](const gpu::Image& target, const gpu::Image* multisampled, VkClearValue clear) {
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
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
    };
    VkClearValue colorClear{};
    std::memcpy(colorClear.color.float32, slot.clearColor, sizeof slot.clearColor);
    VkClearValue normalDepthClear{};
    normalDepthClear.color.uint32[3] = floatBits(FLT_MAX);  // background depth: the largest float

    const VkBuffer geometry = scene.geometry();
    // Draws every view's list with the given pipelines (one per draw, in plan order).
    auto drawViews = [&](const std::vector<VkPipeline>& drawPipelines) {
        std::size_t drawCounter = 0;
        for (std::size_t vi = 0; vi < plan.views.size(); ++vi) {
            const ViewPlan& v = plan.views[vi];
            // GL's viewport origin is the bottom-left corner; Vulkan's framebuffer starts at the top.
            const float vy = float(int(t.height) - v.y - v.height);
            VkViewport viewport{float(v.x), vy, float(v.width), float(v.height), 0.0f, 1.0f};
            VkRect2D scissor{{v.x, int(vy)}, {std::uint32_t(v.width), std::uint32_t(v.height)}};
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            const std::uint32_t dynamicOffsets[2] = {std::uint32_t(frameOffsets[vi]),
                                                     std::uint32_t(lightOffsets[vi])};
            VkPipeline bound = VK_NULL_HANDLE;
            VkDescriptorSet boundTexture = VK_NULL_HANDLE;
            for (const DrawItem& d : v.draws) {
                const VkPipeline p = drawPipelines[drawCounter++];
                if (p != bound) {
                    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
                    if (bound == VK_NULL_HANDLE)
                        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_pipelineLayout.get(),
                                                0, 1, &slot.frameSet, 2, dynamicOffsets);
                    bound = p;
                }
                const VkDescriptorSet tex = scene.textureSet(d.texture);
                if (tex != boundTexture) {
                    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_pipelineLayout.get(),
                                            1, 1, &tex, 0, nullptr);
                    boundTexture = tex;
                }
                vkCmdSetCullMode(cmd, d.cullBack ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE);
                // The y flip in clipFromView keeps GL's counter-clockwise front faces
                // counter-clockwise on screen; a mirroring transform reverses them (glTF's rule).
                vkCmdSetFrontFace(cmd, d.mirrored ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE);
                vkCmdPushConstants(cmd, m_pipelineLayout.get(),
                                   VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                   sizeof(DrawBlock), &d.block);
                const GpuPrimitive& gp = scene.primitive(d.mesh, d.primitive);
                if (d.key.program == Program::Flat) {
                    const VkBuffer flat = scene.flatGeometry();
                    VkBuffer buffers[5] = {flat, flat, gp.flatColor != kNoStream ? flat : geometry,
                                           gp.flatTexcoord != kNoStream ? flat : geometry, flat};
                    VkDeviceSize offsets[5] = {
                        gp.flatPosition, gp.flatNormal,
                        gp.flatColor != kNoStream ? gp.flatColor : scene.defaultColorOffset(),
                        gp.flatTexcoord != kNoStream ? gp.flatTexcoord : scene.defaultTexcoordOffset(),
                        gp.flatCentroid};
                    VkDeviceSize strides[5] = {12, 12, gp.flatColor != kNoStream ? 16u : 0u,
                                               gp.flatTexcoord != kNoStream ? 8u : 0u, 12};
                    vkCmdBindVertexBuffers2(cmd, 0, 5, buffers, offsets, nullptr, strides);
                    vkCmdDraw(cmd, gp.flatVertexCount, 1, 0, 0);
                } else {
                    VkBuffer buffers[4] = {geometry, geometry, geometry, geometry};
                    VkDeviceSize offsets[4] = {
                        gp.position, gp.normal,
                        gp.color != kNoStream ? gp.color : scene.defaultColorOffset(),
                        gp.texcoord != kNoStream ? gp.texcoord : scene.defaultTexcoordOffset()};
                    VkDeviceSize strides[4] = {12, 12, gp.color != kNoStream ? 16u : 0u,
                                               gp.texcoord != kNoStream ? 8u : 0u};
                    vkCmdBindVertexBuffers2(cmd, 0, 4, buffers, offsets, nullptr, strides);
                    if (gp.indexCount > 0) {
                        vkCmdBindIndexBuffer(cmd, geometry, gp.index, VK_INDEX_TYPE_UINT32);
                        vkCmdDrawIndexed(cmd, gp.indexCount, 1, 0, 0, 0);
                    } else {
                        vkCmdDraw(cmd, gp.vertexCount, 1, 0, 0);
                    }
                }
            }
            // The display overlays never meet the AOV pass (they refuse AOVs).
            if (slot.debug.any())
                m_debug->recordView(cmd, scene, v, slot.frameSet, dynamicOffsets, slot.debug);
        }
    };
    auto pass = [&](const std::vector<VkRenderingAttachmentInfo>& colors, const gpu::Image& depthImage,
                    const std::vector<VkPipeline>& drawPipelines) {
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = depthImage.view.get();
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        depth.clearValue.depthStencil.depth = slot.clearDepth;
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, {t.width, t.height}};
        ri.layerCount = 1;
        ri.colorAttachmentCount = std::uint32_t(colors.size());
        ri.pColorAttachments = colors.data();
        ri.pDepthAttachment = &depth;
        vkCmdBeginRendering(cmd, &ri);
        drawViews(drawPipelines);
        vkCmdEndRendering(cmd);
    };

    std::vector<VkRenderingAttachmentInfo> colors{attachment(t.color, msaa ? &t.colorMsaa : nullptr, colorClear)};
    if (t.aov && !msaa) {
        colors.push_back(attachment(t.normalDepth, nullptr, normalDepthClear));
        colors.push_back(attachment(t.ids, nullptr, VkClearValue{}));
    }
    pass(colors, t.depth, pipelines);
    if (aovPass)
        pass({attachment(t.aovColor, nullptr, colorClear), attachment(t.normalDepth, nullptr, normalDepthClear),
              attachment(t.ids, nullptr, VkClearValue{})},
             t.aovDepth, aovPipelines);
    if (slot.queries)
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, slot.queries, 1);

    auto copyOut = [&](const gpu::Image& img, const gpu::Buffer& buf) {
        // To the whole transfer stage: a window frame blits the colour image afterwards.
        gpu::imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT,
                          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_READ_BIT);
        if (!hooks.readback) return;
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {t.width, t.height, 1};
        vkCmdCopyImageToBuffer(cmd, img.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.get(), 1,
                               &region);
    };
    copyOut(t.color, t.readColor);
    if (t.aov) {
        copyOut(t.normalDepth, t.readNormalDepth);
        copyOut(t.ids, t.readIds);
    }
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    if (hooks.afterRender) hooks.afterRender(cmd, t.color.get(), t.width, t.height);
}

Result<FrameResult> Engine::collect(std::uint32_t index, const RenderOptions& o) {
    Slot& slot = m_slots[index];
    if (!slot.busy)
        return makeError(ErrorCode::Usage, "frame slot " + std::to_string(index) + " holds no frame");
    VkFence fence = slot.fence.get();
    slot.busy = false;
    const VkResult wait = vkWaitForFences(m_ctx->device(), 1, &fence, VK_TRUE, UINT64_MAX);
    const VkResult injected = gpu::injectedVkFault("vkWaitForFences");
    slot.scene.reset();
    if (wait != VK_SUCCESS) return gpu::vkError(wait, "vkWaitForFences");
    if (injected != VK_SUCCESS) return gpu::vkError(injected, "vkWaitForFences");

    FrameResult r;
    r.draws = slot.draws;
    if (slot.queries) {
        std::uint64_t ts[2] = {0, 0};
        if (vkGetQueryPoolResults(m_ctx->device(), slot.queries, 0, 2, sizeof ts, ts, 8,
                                  VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
            r.gpuMs = double(ts[1] - ts[0]) * m_ctx->properties().limits.timestampPeriod * 1e-6;
    }
    if (!slot.readback) return r;
    const Target& t = slot.target;
    LANTERN_TRY(gpu::invalidate(*m_ctx, t.readColor));
    Image& img = r.image;
    img.width = int(t.width);
    img.height = int(t.height);
    const std::size_t n = std::size_t(t.width) * t.height;
    img.rgba.resize(n * 4);
    std::memcpy(img.rgba.data(), t.readColor.mapped, n * 16);
    // The last line of defence: no NaN or Inf leaves the renderer. The shaders are written so
    // none arises; any found is counted (tests assert zero) and replaced by 0.
    for (float& v : img.rgba)
        if (!std::isfinite(v)) {
            v = 0.0f;
            ++r.nonFinite;
        }
    if (t.aov) {
        LANTERN_TRY(gpu::invalidate(*m_ctx, t.readNormalDepth));
        const auto* nd = static_cast<const std::uint32_t*>(t.readNormalDepth.mapped);
        if (o.aovs.depth) img.depth.resize(n);
        if (o.aovs.normal) img.normal.resize(n * 3);
        for (std::size_t i = 0; i < n; ++i) {
            if (o.aovs.normal)
                for (int c = 0; c < 3; ++c) {
                    float v = bitsFloat(nd[i * 4 + c]);
                    if (!std::isfinite(v)) {
                        v = 0.0f;
                        ++r.nonFinite;
                    }
                    img.normal[i * 3 + c] = v;
                }
            if (o.aovs.depth) {
                float z = bitsFloat(nd[i * 4 + 3]);
                if (!std::isfinite(z)) {
                    z = FLT_MAX;
                    ++r.nonFinite;
                }
                img.depth[i] = z;
            }
        }
    }
    if (t.aov) {
        LANTERN_TRY(gpu::invalidate(*m_ctx, t.readIds));
        const auto* ids = static_cast<const std::uint32_t*>(t.readIds.mapped);
        r.ids.assign(ids, ids + n * 2);
    }
    if (r.nonFinite > 0)
        m_ctx->log(LogLevel::Error, std::to_string(r.nonFinite) +
                                        " non-finite values were produced and replaced by 0");
    return r;
}

} // namespace lantern::render
