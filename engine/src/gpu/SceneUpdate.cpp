// Moving vertices of an uploaded scene: the host edits a primitive's positions and normals in
// its Scene and asks for that primitive's streams to be written again, rather than uploading
// the whole scene (pyrender issue 43: "moving vertices without re-creating the renderer").
// Only the primitive's own ranges of the geometry buffer (and of the deformation inputs, and
// the per-corner flat streams when they exist) are rewritten; buffers keep their size.
#include "gpu/SceneBuffers.h"

#include <cmath>
#include <cstring>

namespace lantern::gpu {
namespace {

bool allFinite(const std::vector<glm::vec3>& v) {
    for (const glm::vec3& p : v)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    return true;
}

} // namespace

Result<void> SceneBuffers::writeRange(Buffer& target, VkDeviceSize offset, const void* data,
                                      VkDeviceSize bytes, VkPipelineStageFlags2 dstStage,
                                      VkAccessFlags2 dstAccess) {
    if (bytes == 0) return {};
    if (target.mapped) {
        std::memcpy(static_cast<char*>(target.mapped) + offset, data, bytes);
        return flush(*m_ctx, target);
    }
    auto staging = createBuffer(*m_ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                MemoryUsage::Upload, "vertex update staging");
    if (!staging) return std::move(staging).error();
    std::memcpy(staging->mapped, data, bytes);
    LANTERN_TRY(flush(*m_ctx, *staging));
    return m_ctx->submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, offset, bytes};
        vkCmdCopyBuffer(cmd, staging->get(), target.get(), 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      dstStage, dstAccess);
    });
}

Result<void> SceneBuffers::updateVertices(std::uint32_t mesh, std::uint32_t prim) {
    const Scene& s = *m_scene;
    const std::string object = "mesh " + std::to_string(mesh) + " primitive " +
                               std::to_string(prim);
    if (mesh >= s.meshes.size() || prim >= s.meshes[mesh].primitives.size())
        return makeError(ErrorCode::Usage, "the scene has no such primitive", object);
    const Primitive& p = s.meshes[mesh].primitives[prim];
    PrimitiveBuffers& gp = m_primitives[m_meshFirst[mesh] + prim];
    if (p.positions.size() != gp.vertexCount)
        return makeError(ErrorCode::InvalidInput,
                         "has " + std::to_string(p.positions.size()) +
                             " positions, was uploaded with " + std::to_string(gp.vertexCount) +
                             " (the vertex count cannot change: prepare the scene again)",
                         object);
    if (!p.normals.empty() && p.normals.size() != p.positions.size())
        return makeError(ErrorCode::InvalidInput,
                         "has " + std::to_string(p.normals.size()) + " normals for " +
                             std::to_string(p.positions.size()) + " positions",
                         object);
    if (!allFinite(p.positions) || !allFinite(p.normals))
        return makeError(ErrorCode::InvalidInput, "a position or normal is not finite", object);

    // No frame may read the ranges while they change (a sequence or window keeps frames in
    // flight; render() has none left by the time it returns).
    m_ctx->waitIdle();
    const VkDeviceSize n = p.positions.size();
    const VkPipelineStageFlags2 drawStages =
        VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    const VkAccessFlags2 drawAccess =
        VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    LANTERN_TRY(writeRange(m_geometry, gp.position, p.positions.data(), n * 12, drawStages,
                           drawAccess));
    // Zero normals stand for none (unlit lines and points), as at upload.
    const std::vector<glm::vec3> zeros(p.normals.empty() ? n : 0, glm::vec3(0.0f));
    const void* normals = p.normals.empty() ? zeros.data() : p.normals.data();
    LANTERN_TRY(writeRange(m_geometry, gp.normal, normals, n * 12, drawStages, drawAccess));
    if (gp.deformable) {
        LANTERN_TRY(writeRange(m_deformInput, VkDeviceSize(gp.deformPosition) * 4,
                               p.positions.data(), n * 12, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                               VK_ACCESS_2_SHADER_STORAGE_READ_BIT));
        LANTERN_TRY(writeRange(m_deformInput, VkDeviceSize(gp.deformNormal) * 4, normals, n * 12,
                               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                               VK_ACCESS_2_SHADER_STORAGE_READ_BIT));
    }
    if (m_clusters) LANTERN_TRY(m_clusters->update(mesh, prim));
    std::lock_guard lock(m_flatMutex);
    if (m_flatGeometry.get() && gp.flatVertexCount > 0) LANTERN_TRY(fillFlatStreams());
    return {};
}

} // namespace lantern::gpu
