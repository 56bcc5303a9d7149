// The cluster-culling pre-pass: per frame, records for every (view, draw, instance) of the
// clustered draws, one dispatch over all their cluster slots, and the draws' indirect calls
// (gpu/Clusters.h).
#include "gpu/Clusters.h"

#include "gpu/SceneBuffers.h"

#include "ShaderBlobs.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lantern::gpu {
namespace {

constexpr VkDeviceSize kCommandBytes = sizeof(VkDrawIndexedIndirectCommand);

// Row r of a column-major matrix.
glm::dvec4 row(const Mat4& m, int r) { return {m.m[r], m.m[4 + r], m.m[8 + r], m.m[12 + r]}; }

Vec4 vec4(const glm::dvec4& v) { return {float(v.x), float(v.y), float(v.z), float(v.w)}; }

// Twice Vulkan's signed area of the view-space triangle (a, b, c) on screen (positive: front
// under counter-clockwise front faces), or 0 when a corner is behind the eye.
double screenArea(const Mat4& clip, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, double w, double h) {
    glm::dvec2 s[3];
    const glm::dvec3 corners[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
        const glm::dvec4 p(corners[k], 1.0);
        const double cw = glm::dot(row(clip, 3), p);
        if (!(cw > 0.0)) return 0.0;
        s[k] = {glm::dot(row(clip, 0), p) / cw * w, glm::dot(row(clip, 1), p) / cw * h};
    }
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) sum += s[k].x * s[(k + 1) % 3].y - s[(k + 1) % 3].x * s[k].y;
    return -sum;
}

// The view's clip volume (Vulkan's: -w <= x, y <= w, 0 <= z <= w) as view-space planes, and how
// its projection scales an object-space error into pixels.
CullView cullView(const ViewCommands& v, float lodError) {
    const Mat4& m = v.frame.clipFromView;
    const glm::dvec4 r0 = row(m, 0), r1 = row(m, 1), r2 = row(m, 2), r3 = row(m, 3);
    CullView out;
    const glm::dvec4 planes[6] = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2};
    for (int k = 0; k < 6; ++k) out.planes[k] = vec4(planes[k]);
    // w from depth alone, with the eye at the origin (perspective) or constant (orthographic).
    const double s = std::max({std::abs(r3.x), std::abs(r3.y), std::abs(r3.z), std::abs(r3.w)});
    const double eps = 1e-6 * s;
    const bool perspective = std::abs(r3.x) <= eps && std::abs(r3.y) <= eps && r3.z < -eps &&
                             std::abs(r3.w) <= eps && std::abs(r0.w) <= 1e-6 * std::abs(r0.x) &&
                             std::abs(r1.w) <= 1e-6 * std::abs(r1.y);
    const bool orthographic = std::abs(r3.x) <= eps && std::abs(r3.y) <= eps &&
                              std::abs(r3.z) <= eps && r3.w > eps;
    const double w = 0.5 * v.width, h = 0.5 * v.height;
    const double pixels = std::max(std::abs(r0.x) * w, std::abs(r1.y) * h) /
                          (perspective ? -r3.z : orthographic ? r3.w : 1.0);
    out.projection.x = float(pixels);
    out.projection.y = perspective ? 1.0f : 0.0f;
    // A triangle facing the eye (counter-clockwise seen from it) must come out front-facing.
    const bool glWinding = perspective && screenArea(m, {0, 0, -1}, {1, 0, -1}, {0, 1, -1}, w, h) > 0.0;
    out.projection.z = glWinding ? 1.0f : 0.0f;
    out.projection.w = (perspective || orthographic) && std::isfinite(pixels) ? lodError : 0.0f;
    return out;
}

// The record's transform, its radii's factor and whether the cone test holds for it: a
// similarity (normals keep their angles) whose handedness the draw's winding follows.
void placeRecord(CullRecord& r, const float* viewFromModel, const float* normalMatrix, const DrawCommand& d) {
    std::memcpy(r.viewFromModel.m, viewFromModel, sizeof r.viewFromModel.m);
    for (int c = 0; c < 3; ++c)
        r.normalMatrix[c] = {normalMatrix[4 * c], normalMatrix[4 * c + 1], normalMatrix[4 * c + 2], 0.0f};
    glm::dmat3 a;
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) a[c][k] = viewFromModel[c * 4 + k];
    const double l0 = glm::length(a[0]), l1 = glm::length(a[1]), l2 = glm::length(a[2]);
    const double longest = std::max({l0, l1, l2});
    r.scale = float(longest * (1.0 + 1e-6));
    const double tol = 1e-4 * longest;
    const bool similar = std::abs(l0 - l1) <= tol && std::abs(l1 - l2) <= tol &&
                         std::abs(glm::dot(a[0], a[1])) <= tol * longest &&
                         std::abs(glm::dot(a[1], a[2])) <= tol * longest &&
                         std::abs(glm::dot(a[0], a[2])) <= tol * longest;
    const bool mirrored = glm::determinant(a) < 0.0;
    r.flags = d.cullBack && similar && longest > 0.0 && mirrored == d.frontClockwise ? LANTERN_CULL_CONE : 0u;
}

bool clustered(const DrawCommand& d, const PrimitiveBuffers& gp) {
    return d.pipeline.program != frame::Program::Flat && d.pipeline.topology == Topology::Triangles &&
           d.deform < 0 && gp.indexCount > 0;
}

} // namespace

Result<std::unique_ptr<Culler>> Culler::create(Context& ctx, Pipelines& pipelines) {
    static_assert(LANTERN_BINDING_CULL_CLUSTERS == 0 && LANTERN_BINDING_CULL_VIEWS == 4);
    std::unique_ptr<Culler> c(new Culler(ctx));
    auto pass = pipelines.computePass(std::uint32_t(shaders::ShaderId::cull_comp), 5,
                                      sizeof(std::uint32_t), "cluster culling pre-pass");
    if (!pass) return std::move(pass).error();
    c->m_setLayout = std::move(pass->setLayout);
    c->m_layout = std::move(pass->layout);
    c->m_pipeline = std::move(pass->pipeline);
    return c;
}

// One record per (view, draw, instance) of the clustered draws; each draw's commands at most
// one per cluster of each instance (kept runs merge), its coarser levels' at most one per
// cluster of level 1.
Result<void> Culler::prepare(CullSlot& slot, const DrawList& list, const SceneBuffers& scene) {
    slot.draws.clear();
    slot.recordCount = 0;
    slot.triangles = 0;
    SceneClusters* clusters = scene.clusters();
    // Each indirect draw counts gl_PrimitiveID from 0: a frame that reads the ids (the probe,
    // the id planes; set on the target after the list was built) draws whole.
    if (!list.clusterCulling || list.target.readIds() || !clusters || !clusters->any() ||
        !m_ctx.capabilities().multiDrawIndirect)
        return {};
    if (list.lodError > 0.0f) LANTERN_TRY(clusters->ensureLevels());
    const bool lod = list.lodError > 0.0f && clusters->lodIndices() != VK_NULL_HANDLE;
    std::vector<CullView> views;
    std::vector<CullRecord> records;
    std::uint64_t commands = 0, lodCommands = 0;
    std::uint32_t clusteredDraws = 0;
    for (std::uint32_t vi = 0; vi < list.views.size(); ++vi) {
        views.push_back(cullView(list.views[vi], list.lodError));
        for (const DrawCommand& d : list.views[vi].draws) {
            const PrimitiveClusters* pc = clusters->primitive(d.mesh, d.primitive);
            const PrimitiveBuffers& gp = scene.primitive(d.mesh, d.primitive);
            const std::uint64_t slots = pc ? pc->levels[0].clusterCount : 0u;
            const std::uint64_t lodSlots = pc && lod && pc->levelCount > 1 ? pc->levels[1].clusterCount : 0u;
            const std::uint64_t most = m_ctx.properties().limits.maxDrawIndirectCount;
            if (!pc || !clustered(d, gp) || gp.index / 4 > ~0u - gp.indexCount ||
                std::max(slots, lodSlots) * d.instanceCount > most ||
                commands + lodCommands + (slots + lodSlots) * d.instanceCount > ~0u / 2) {
                slot.draws.push_back({});
                continue;
            }
            const bool instanced = d.pipeline.constants[LANTERN_SC_INSTANCED] != 0;
            slot.draws.push_back({std::uint32_t(commands), std::uint32_t(d.instanceCount * slots),
                                  lodSlots > 0 ? std::uint32_t(lodCommands) : ~0u,
                                  std::uint32_t(d.instanceCount * lodSlots), clusteredDraws});
            for (std::uint32_t k = 0; k < d.instanceCount; ++k) {
                CullRecord r;
                const InstanceData* in = instanced ? &list.instances[d.firstInstance + k] : nullptr;
                placeRecord(r, in ? in->viewFromModel : d.block.viewFromModel,
                            in ? in->normalMatrix : d.block.normalMatrix, d);
                r.sphere = pc->sphere;
                r.view = vi;
                r.firstCommand = std::uint32_t(commands);
                r.slots = std::uint32_t(slots);
                r.firstInstance = d.firstInstance + k;
                r.levelCount = lodSlots > 0 ? pc->levelCount : 1u;
                r.lodCommand = lodSlots > 0 ? std::uint32_t(lodCommands) : ~0u;  // after the full lists' below
                r.lodSlots = std::uint32_t(lodSlots);
                r.drawRecords = k == 0 ? d.instanceCount : 0u;
                r.countIndex = clusteredDraws;
                r.levels = pc->levels;
                r.indexBase = std::uint32_t(gp.index / 4);
                records.push_back(r);
                slot.triangles += pc->triangles;
            }
            commands += slots * d.instanceCount;
            lodCommands += lodSlots * d.instanceCount;
            ++clusteredDraws;
        }
    }
    if (records.empty()) return {};
    for (CullRecord& r : records)
        if (r.lodCommand != ~0u) r.lodCommand += std::uint32_t(commands);
    for (CullSlot::Range& range : slot.draws)
        if (range.lodFirst != ~0u) range.lodFirst += std::uint32_t(commands);
    slot.recordCount = std::uint32_t(records.size());
    slot.lodIndices = lod ? clusters->lodIndices() : VK_NULL_HANDLE;
    return upload(slot, records, views, (commands + lodCommands) * kCommandBytes,
                  (1 + 2 * VkDeviceSize(clusteredDraws)) * 4, *clusters);
}

Result<void> Culler::upload(CullSlot& slot, const std::vector<CullRecord>& records,
                            const std::vector<CullView>& views, VkDeviceSize commandBytes,
                            VkDeviceSize countBytes, const SceneClusters& clusters) {
    const VkDeviceSize recordBytes = records.size() * sizeof(CullRecord);
    const VkDeviceSize viewBytes = views.size() * sizeof(CullView);
    LANTERN_TRY(ensureSize(m_ctx, slot.records, recordBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           MemoryUsage::Upload, "cluster culling records"));
    LANTERN_TRY(ensureSize(m_ctx, slot.views, viewBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           MemoryUsage::Upload, "cluster culling views"));
    LANTERN_TRY(ensureSize(m_ctx, slot.commands, std::max<VkDeviceSize>(commandBytes, kCommandBytes),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                           MemoryUsage::DeviceLocal, "cluster indirect draws"));
    LANTERN_TRY(ensureSize(m_ctx, slot.counts, countBytes,
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           MemoryUsage::Readback, "cluster culling counts"));
    std::memcpy(slot.records.mapped, records.data(), recordBytes);
    std::memcpy(slot.views.mapped, views.data(), viewBytes);
    LANTERN_TRY(flush(m_ctx, slot.records));
    LANTERN_TRY(flush(m_ctx, slot.views));
    LANTERN_TRY(ensureStorageSet(m_ctx, m_setLayout.get(), 5, slot.pool, slot.set));
    constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writeBufferDescriptors(m_ctx, slot.set,
                           {{LANTERN_BINDING_CULL_CLUSTERS, kStorage, {clusters.clusters(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_CULL_RECORDS, kStorage, {slot.records.get(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_CULL_COMMANDS, kStorage, {slot.commands.get(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_CULL_COUNTS, kStorage, {slot.counts.get(), 0, VK_WHOLE_SIZE}},
                            {LANTERN_BINDING_CULL_VIEWS, kStorage, {slot.views.get(), 0, VK_WHOLE_SIZE}}});
    return {};
}

void Culler::record(VkCommandBuffer cmd, const CullSlot& slot) const {
    // The counters from zero; this slot's previous indirect reads are behind its fence.
    vkCmdFillBuffer(cmd, slot.counts.get(), 0, VK_WHOLE_SIZE, 0);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), 0, 1, &slot.set, 0, nullptr);
    vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof slot.recordCount,
                       &slot.recordCount);
    vkCmdDispatch(cmd, (slot.recordCount + LANTERN_CULL_GROUP - 1) / LANTERN_CULL_GROUP, 1, 1);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

void drawClusters(VkCommandBuffer cmd, const CullSlot& slot, const CullSlot::Range& range,
                  VkBuffer geometry) {
    const VkDeviceSize counts = (1 + 2 * VkDeviceSize(range.countIndex)) * 4;
    vkCmdBindIndexBuffer(cmd, geometry, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexedIndirectCount(cmd, slot.commands.get(), range.first * kCommandBytes, slot.counts.get(),
                                  counts, range.count, std::uint32_t(kCommandBytes));
    if (range.lodFirst == ~0u || slot.lodIndices == VK_NULL_HANDLE) return;
    vkCmdBindIndexBuffer(cmd, slot.lodIndices, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexedIndirectCount(cmd, slot.commands.get(), range.lodFirst * kCommandBytes, slot.counts.get(),
                                  counts + 4, range.lodCount, std::uint32_t(kCommandBytes));
}

} // namespace lantern::gpu
