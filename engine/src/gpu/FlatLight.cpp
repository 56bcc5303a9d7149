// The per-triangle flat-lighting pre-pass: compute pipelines specialised like their draws,
// per-slot job and record buffers, one dispatch per flat triangle draw.
#include "gpu/FlatLight.h"

#include "ShaderBlobs.h"

#include <algorithm>
#include <cstring>

namespace lantern::gpu {
namespace {

std::uint64_t triangles(const PrimitiveBuffers& gp) {
    return (gp.indexCount > 0 ? gp.indexCount : gp.vertexCount) / 3u;
}

// 16-byte vectors per triangle record (shaders/include/flat.glsl): per side one, two when the
// variant samples a base-colour texture; two sides with two-sided lighting.
std::uint64_t recordVectors(const PipelineKey& key) {
    return (key.constants[LANTERN_SC_TEXTURE] ? 2u : 1u) *
           (key.constants[LANTERN_SC_TWO_SIDED] ? 2u : 1u);
}

// The pre-pass's constants: it loops over the lights, never unrolled (flatlight.comp is built
// with the loop alone, shaders/include/lighting.glsl), so the unrolled light count and kinds
// are cleared and frames that differ only in them share one pipeline. On lavapipe unrolling
// them in this compute shader made the first frame slower and the others no faster
// (docs/performance.md).
std::array<std::uint32_t, LANTERN_SC_COUNT> prePassConstants(std::array<std::uint32_t, LANTERN_SC_COUNT> c) {
    // It loops, so it reads the lights from the uniform buffer wherever there are few enough:
    // a draw's variant does for 9 to LANTERN_UNIFORM_LIGHTS, and an unrolled one has at most 8.
    c[LANTERN_SC_LIGHTS_UNIFORM] = c[LANTERN_SC_UNROLLED_LIGHTS] != 0 || c[LANTERN_SC_LIGHTS_UNIFORM];
    c[LANTERN_SC_UNROLLED_LIGHTS] = 0;
    c[LANTERN_SC_LIGHT_KINDS] = 0;
    return c;
}

Error tooLarge() {
    return makeError(ErrorCode::OutOfMemory,
                     "the frame's flat-shaded triangles exceed the addressable size");
}

// The job of one flat triangle draw: its DrawBlock, where its triangles, positions and
// colours are, how it culls.
FlatJob planJob(const DrawCommand& d, const PrimitiveBuffers& gp, const DeformStreams* moved,
                const ViewCommands& view, std::uint32_t base, bool aovs) {
    FlatJob j;
    std::memcpy(j.viewFromModel, d.block.viewFromModel, sizeof j.viewFromModel);
    std::memcpy(j.normalMatrix, d.block.normalMatrix, sizeof j.normalMatrix);
    j.materialIndex = d.block.materialIndex;
    j.drawIndex = d.block.drawIndex;
    j.flags = d.block.flags;
    j.flatBase = base;
    j.count = std::uint32_t(triangles(gp));
    j.indices = gp.indexCount > 0 ? std::uint32_t(gp.index / 4) : LANTERN_DEFORM_NONE;
    j.deformed = moved ? 1u : 0u;
    j.positions = std::uint32_t((moved ? moved->position : gp.position) / 4);
    j.colors = gp.color != kNoStream ? std::uint32_t(gp.color / 4) : LANTERN_DEFORM_NONE;
    j.texcoords = gp.texcoord != kNoStream ? std::uint32_t(gp.texcoord / 4) : LANTERN_DEFORM_NONE;
    j.texcoords1 = gp.texcoord1 != kNoStream ? std::uint32_t(gp.texcoord1 / 4) : LANTERN_DEFORM_NONE;
    j.cull = (d.cullBack ? LANTERN_FLAT_CULL_BACK : 0u) |
             (d.frontClockwise ? LANTERN_FLAT_FRONT_CLOCKWISE : 0u);
    j.writeNormals = aovs ? 1u : 0u;
    j.viewport = {0.5f * float(view.width), 0.5f * float(view.height), 0.0f, 0.0f};
    return j;
}

} // namespace

Result<std::unique_ptr<FlatLighter>> FlatLighter::create(Context& ctx, Pipelines& pipelines) {
    std::unique_ptr<FlatLighter> f(new FlatLighter(ctx, pipelines));
    const VkDevice dev = ctx.device();
    // The sets of the graphics layout: the frame, the textures and the flat set its draws'
    // vertex stage reads too.
    VkDescriptorSetLayout sets[3] = {};
    sets[LANTERN_SET_FRAME] = pipelines.frameSetLayout();
    sets[LANTERN_SET_TEXTURE] = pipelines.textureSetLayout();
    sets[LANTERN_SET_FLAT] = pipelines.flatSetLayout();
    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(std::uint32_t)};
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = 3;
    plci.pSetLayouts = sets;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreatePipelineLayout(dev, &plci, nullptr, &layout));
    f->m_layout = UniquePipelineLayout(dev, layout);
    return f;
}

std::uint32_t FlatLighter::triangleCount(const PrimitiveBuffers& gp) {
    return std::uint32_t(triangles(gp));
}

bool FlatLighter::available(const Context& ctx, const SceneBuffers& scene, const DrawList& list) {
    const VkDeviceSize range = ctx.properties().limits.maxStorageBufferRange;
    std::uint64_t records = 0;
    for (const ViewCommands& v : list.views)
        for (const DrawCommand& d : v.draws)
            if (perTriangle(d.pipeline, true))
                records += triangles(scene.primitive(d.mesh, d.primitive)) * recordVectors(d.pipeline);
    return scene.geometryBytes() <= range && records * 16 <= range;
}

Result<VkPipeline> FlatLighter::pipeline(const std::array<std::uint32_t, LANTERN_SC_COUNT>& constants) {
    if (auto it = m_variants.find(constants); it != m_variants.end()) return it->second.get();
    auto module = m_pipelines.shader(std::uint32_t(shaders::ShaderId::flatlight_comp));
    if (!module) return std::move(module).error();
    std::vector<VkSpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < LANTERN_SC_COUNT; ++i) entries.push_back({i, i * 4u, 4u});
    VkSpecializationInfo spec{};
    spec.mapEntryCount = LANTERN_SC_COUNT;
    spec.pMapEntries = entries.data();
    spec.dataSize = sizeof constants;
    spec.pData = constants.data();
    VkComputePipelineCreateInfo cpci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cpci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    cpci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cpci.stage.module = *module;
    cpci.stage.pName = "main";
    cpci.stage.pSpecializationInfo = &spec;
    cpci.layout = m_layout.get();
    VkPipeline pipeline = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateComputePipelines(m_ctx.device(), m_ctx.pipelineCache(), 1, &cpci,
                                            nullptr, &pipeline));
    m_ctx.setName(VK_OBJECT_TYPE_PIPELINE, pipeline, "flat per-triangle pre-pass");
    m_variants.emplace(constants, UniquePipeline(m_ctx.device(), pipeline));
    m_ctx.log(LogLevel::Debug, "pipeline variant created: flat per-triangle pre-pass");
    return pipeline;
}

Result<void> FlatLighter::prepare(FlatSlot& slot, const DrawList& list, const SceneBuffers& scene,
                                  const DeformSlot* deform, bool available) {
    slot.dispatches.clear();
    slot.drawJobs.clear();
    slot.firstRecords.clear();
    slot.triangles = 0;
    std::vector<FlatJob> jobs;
    std::uint64_t vectors = 0, count = 0;
    const bool aovs = list.target.aovs.any();
    for (std::uint32_t vi = 0; vi < list.views.size(); ++vi)
        for (const DrawCommand& d : list.views[vi].draws) {
            if (!perTriangle(d.pipeline, available)) {
                slot.drawJobs.push_back(kNoFlatJob);
                continue;
            }
            const PrimitiveBuffers& gp = scene.primitive(d.mesh, d.primitive);
            const DeformStreams* moved =
                d.deform >= 0 && deform ? &deform->streams[std::size_t(d.deform)] : nullptr;
            const std::uint64_t vectorsPerTriangle = recordVectors(d.pipeline);
            // The base counts triangles: the shaders read record vectors from base * size and
            // normals from base, so it is past both the records and the normals before it.
            const std::uint64_t base =
                std::max((vectors + vectorsPerTriangle - 1) / vectorsPerTriangle, count);
            if (base + count >= kNoFlatJob) return tooLarge();
            FlatJob job = planJob(d, gp, moved, list.views[vi], std::uint32_t(base), aovs);
            job.view = vi;
            vectors = (base + job.count) * vectorsPerTriangle;
            count = std::max<std::uint64_t>(count, base + job.count);
            slot.drawJobs.push_back(std::uint32_t(jobs.size()));
            slot.triangles += job.count;
            auto p = pipeline(prePassConstants(d.pipeline.constants));
            if (!p) return std::move(p).error();
            slot.dispatches.push_back({std::uint32_t(jobs.size()), vi,
                                       (job.count + LANTERN_FLAT_GROUP - 1) / LANTERN_FLAT_GROUP, *p});
            slot.firstRecords.push_back(job.flatBase);
            jobs.push_back(job);
        }
    if (jobs.empty()) return {};
    slot.recordBytes = std::max<VkDeviceSize>(vectors * 16, 16);
    // The normals are bound at an offset: the device's storage-buffer offset alignment.
    const VkDeviceSize alignment =
        std::max<VkDeviceSize>(m_ctx.properties().limits.minStorageBufferOffsetAlignment, 16);
    slot.normalOffset = (slot.recordBytes + alignment - 1) / alignment * alignment;
    slot.normalBytes = aovs ? std::max<VkDeviceSize>(count * 16, 16) : 16;
    LANTERN_TRY(ensureSize(m_ctx, slot.records, slot.normalOffset + slot.normalBytes,
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::DeviceLocal,
                           "flat per-triangle records"));
    // Three indices per triangle at three times its record (the gaps between draws unused).
    LANTERN_TRY(ensureSize(m_ctx, slot.indices, std::max<VkDeviceSize>(count * 12, 12),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                           MemoryUsage::DeviceLocal, "flat per-triangle index lists"));
    const VkDeviceSize jobBytes = jobs.size() * sizeof(FlatJob);
    LANTERN_TRY(ensureSize(m_ctx, slot.jobs, jobBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           MemoryUsage::Upload, "flat per-triangle jobs"));
    std::memcpy(slot.jobs.mapped, jobs.data(), jobBytes);
    LANTERN_TRY(flush(m_ctx, slot.jobs));
    LANTERN_TRY(ensureDescriptorSet(slot));
    // A scene without deformation binds its geometry in the deformed slot (never read).
    const bool moving = deform && deform->output.get();
    const VkBuffer moved = moving ? deform->output.get() : scene.geometry();
    constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writeBufferDescriptors(m_ctx, slot.set,
                           {{LANTERN_BINDING_FLAT_GEOMETRY, kStorage, {scene.geometry(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_FLAT_DEFORMED, kStorage, {moved, 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_FLAT_JOBS, kStorage, {slot.jobs.get(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_FLAT_INDICES, kStorage, {slot.indices.get(), 0, VK_WHOLE_SIZE}}});
    return {};
}

Result<void> FlatLighter::ensureDescriptorSet(FlatSlot& slot) {
    return ensureStorageSet(m_ctx, m_pipelines.flatSetLayout(), 4, slot.pool, slot.set);
}

void FlatLighter::record(VkCommandBuffer cmd, const FlatSlot& slot, VkDescriptorSet frameSet,
                         const std::vector<VkDeviceSize>& frameOffsets,
                         const std::vector<VkDeviceSize>& lightOffsets) const {
    // The deformed positions written before, and the previous frame's fragment reads of this
    // slot's records, come first.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT |
                           VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), LANTERN_SET_FLAT,
                            1, &slot.set, 0, nullptr);
    VkPipeline bound = VK_NULL_HANDLE;
    std::uint32_t boundView = ~0u;
    for (const FlatSlot::Dispatch& d : slot.dispatches) {
        if (d.view != boundView) {
            const FrameSetOffsets offsets = frameSetOffsets(frameOffsets[d.view], lightOffsets[d.view]);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(),
                                    LANTERN_SET_FRAME, 1, &frameSet, std::uint32_t(offsets.size()),
                                    offsets.data());
            boundView = d.view;
        }
        if (d.pipeline != bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, d.pipeline);
            bound = d.pipeline;
        }
        vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                           sizeof(std::uint32_t), &d.job);
        if (d.groups > 0) vkCmdDispatch(cmd, d.groups, 1, 1);
    }
    // The draws read the index lists, their vertex stage the deformed positions (written by
    // the deformation pass before), their fragment stage the records.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

} // namespace lantern::gpu
