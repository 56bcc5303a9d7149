// The deformation pre-pass: a compute pipeline, per-slot parameter and output buffers, one
// dispatch per deformed primitive, then a barrier to the vertex-input stage.
#include "gpu/Deform.h"

#include "ShaderBlobs.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace lantern::gpu {
namespace {

VkDeviceSize align16(VkDeviceSize v) { return (v + 15) & ~VkDeviceSize(15); }

Error tooLarge() {
    return makeError(ErrorCode::OutOfMemory,
                     "the frame's skinned and morphing vertices exceed the addressable size");
}

} // namespace

Result<std::unique_ptr<Deformer>> Deformer::create(Context& ctx, Pipelines& pipelines) {
    static_assert(LANTERN_BINDING_DEFORM_INPUT == 0 && LANTERN_BINDING_DEFORM_PARAMS == 1 &&
                  LANTERN_BINDING_DEFORM_OUTPUT == 2);
    std::unique_ptr<Deformer> d(new Deformer(ctx));
    auto pass = pipelines.computePass(std::uint32_t(shaders::ShaderId::deform_comp), 3,
                                      sizeof(DeformJob), "deform pre-pass");
    if (!pass) return std::move(pass).error();
    d->m_setLayout = std::move(pass->setLayout);
    d->m_layout = std::move(pass->layout);
    d->m_pipeline = std::move(pass->pipeline);
    return d;
}

namespace {

// One command's job: where its inputs are, its parameters appended to `params` (joint
// matrices, then morph weights), its output streams at 16-byte-aligned offsets from `out`.
DeformJob planJob(const DeformCommand& c, const PrimitiveBuffers& gp, bool flatPerTriangle,
                  std::vector<float>& params, VkDeviceSize& out, DeformStreams& st) {
    const bool flat = c.flat && !(flatPerTriangle && gp.corners == 3);
    DeformJob job;
    job.flatMode = flat ? gp.corners : 0u;
    job.vertexCount = gp.vertexCount;
    job.count = flat ? gp.flatVertexCount / gp.corners : gp.vertexCount;
    job.position = gp.deformPosition;
    job.normal = gp.deformNormal;
    job.joints = gp.deformJoints;
    job.weights = gp.deformWeights;
    job.influences = c.joints.empty() ? 0u : gp.influences;
    job.targets = gp.deformTargets;
    job.targetCount = c.weights.empty() ? 0u : std::min<std::uint32_t>(gp.targetCount,
                                                                std::uint32_t(c.weights.size()));
    job.indices = gp.deformIndices;
    job.matrices = std::uint32_t(params.size());
    for (const Mat4& m : c.joints) params.insert(params.end(), m.m, m.m + 16);
    job.morphWeights = std::uint32_t(params.size());
    params.insert(params.end(), c.weights.begin(), c.weights.end());
    const VkDeviceSize corners = flat ? VkDeviceSize(gp.flatVertexCount) : gp.vertexCount;
    st.position = out;
    out = align16(out + corners * 12);
    st.normal = out;
    out = align16(out + corners * 12);
    st.centroid = st.normal;
    if (flat) {
        st.centroid = out;
        out = align16(out + corners * 12);
    }
    job.outPosition = std::uint32_t(st.position / 4);
    job.outNormal = std::uint32_t(st.normal / 4);
    job.outCentroid = std::uint32_t(st.centroid / 4);
    return job;
}

} // namespace

Result<void> Deformer::prepare(DeformSlot& slot, const DrawList& list, const SceneBuffers& scene,
                               bool flatPerTriangle) {
    slot.jobs.clear();
    slot.streams.clear();
    std::vector<float> params;
    VkDeviceSize out = 0;
    for (const DeformCommand& c : list.deforms) {
        DeformStreams st;
        slot.jobs.push_back(
            planJob(c, scene.primitive(c.mesh, c.primitive), flatPerTriangle, params, out, st));
        slot.streams.push_back(st);
        if (out / 4 >= LANTERN_DEFORM_NONE) return tooLarge();
    }
    params.push_back(0.0f);  // never empty
    const VkDeviceSize paramBytes = params.size() * sizeof(float);
    LANTERN_TRY(ensureSize(m_ctx, slot.params, paramBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           MemoryUsage::Upload, "deform parameters"));
    LANTERN_TRY(ensureSize(m_ctx, slot.output, std::max<VkDeviceSize>(out, 16),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                           MemoryUsage::DeviceLocal, "deformed streams"));
    std::memcpy(slot.params.mapped, params.data(), paramBytes);
    LANTERN_TRY(flush(m_ctx, slot.params));
    LANTERN_TRY(ensureDescriptorSet(slot));
    // The slot is not in flight (its fence was waited for): its set may be rewritten.
    constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writeBufferDescriptors(m_ctx, slot.set,
                           {{LANTERN_BINDING_DEFORM_INPUT, kStorage, {scene.deformInput(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_DEFORM_PARAMS, kStorage, {slot.params.get(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_DEFORM_OUTPUT, kStorage, {slot.output.get(), 0, VK_WHOLE_SIZE}}});
    return {};
}

Result<void> Deformer::ensureDescriptorSet(DeformSlot& slot) {
    return ensureStorageSet(m_ctx, m_setLayout.get(), 3, slot.pool, slot.set);
}

void Deformer::record(VkCommandBuffer cmd, const DeformSlot& slot) const {
    // The previous frame of this slot read the output as vertices (and in the flat pass):
    // finish that before writing.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), 0, 1, &slot.set,
                            0, nullptr);
    for (const DeformJob& job : slot.jobs) {
        if (job.count == 0) continue;
        vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(DeformJob),
                           &job);
        vkCmdDispatch(cmd, (job.count + LANTERN_DEFORM_GROUP - 1) / LANTERN_DEFORM_GROUP, 1, 1);
    }
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT,
                  VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT);
}

} // namespace lantern::gpu
