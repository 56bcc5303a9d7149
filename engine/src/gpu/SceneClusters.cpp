// A scene's clusters: runs of consecutive triangles with meshoptimizer's bounds and normal
// cones (level 0 at upload), and the coarser levels of detail meshoptimizer's simplifier makes
// on first use (gpu/Clusters.h).
#include "gpu/Clusters.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace lantern::gpu {
namespace {

bool clusterable(const Primitive& p) {
    return p.topology == Topology::Triangles && p.indices.size() / 3 > LANTERN_CLUSTER_TRIANGLES &&
           p.targets.empty() && p.joints0.empty();
}

// The clusters of `indices` (a triangle list of `p`'s vertices): consecutive runs, each's
// index range counted from `base`.
void clustersOf(const Primitive& p, const std::uint32_t* indices, std::size_t count,
                std::uint32_t base, std::vector<ClusterData>& out) {
    constexpr std::size_t run = 3 * LANTERN_CLUSTER_TRIANGLES;
    const float* positions = &p.positions[0].x;
    for (std::size_t first = 0; first < count; first += run) {
        const std::size_t n = std::min(run, count - first);
        const meshopt_Bounds b =
            meshopt_computeClusterBounds(indices + first, n, positions, p.positions.size(), 12);
        ClusterData c;
        const glm::vec3 centre(b.center[0], b.center[1], b.center[2]);
        // Padded so that no vertex the rounding of the sphere's fit left outside it escapes.
        const float pad = 1e-5f * (b.radius + glm::length(centre)) + 1e-30f;
        c.sphere = {centre.x, centre.y, centre.z, b.radius * 1.0001f + pad};
        c.apex = {b.cone_apex[0], b.cone_apex[1], b.cone_apex[2], 0.0f};
        c.axis = {b.cone_axis[0], b.cone_axis[1], b.cone_axis[2], b.cone_cutoff};
        c.firstIndex = base + std::uint32_t(first);
        c.indexCount = std::uint32_t(n);
        out.push_back(c);
    }
}

// A sphere holding the clusters' spheres.
Vec4 enclosing(const ClusterData* clusters, std::size_t count) {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (std::size_t k = 0; k < count; ++k) {
        const Vec4& s = clusters[k].sphere;
        lo = glm::min(lo, glm::dvec3(s.x - s.w, s.y - s.w, s.z - s.w));
        hi = glm::max(hi, glm::dvec3(s.x + s.w, s.y + s.w, s.z + s.w));
    }
    const glm::dvec3 c = 0.5 * (lo + hi);
    double r = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
        const Vec4& s = clusters[k].sphere;
        r = std::max(r, glm::length(glm::dvec3(s.x, s.y, s.z) - c) + s.w);
    }
    return {float(c.x), float(c.y), float(c.z), float(r * (1.0 + 1e-6))};
}

} // namespace

Result<std::unique_ptr<SceneClusters>> SceneClusters::create(Context& ctx,
                                                             std::shared_ptr<const Scene> scene) {
    std::unique_ptr<SceneClusters> s(new SceneClusters(ctx));
    s->m_scene = std::move(scene);
    std::vector<ClusterData> clusters;
    for (const Mesh& mesh : s->m_scene->meshes) {
        s->m_meshFirst.push_back(s->m_primitives.size());
        for (const Primitive& p : mesh.primitives) {
            PrimitiveClusters pc;
            if (clusterable(p) && clusters.size() < std::numeric_limits<std::uint32_t>::max() / 2) {
                const std::size_t first = clusters.size();
                clustersOf(p, p.indices.data(), p.indices.size(), 0, clusters);
                pc.levelCount = 1;
                pc.levels[0] = {0.0f, std::uint32_t(first), std::uint32_t(clusters.size() - first), 0};
                pc.sphere = enclosing(clusters.data() + first, clusters.size() - first);
                pc.triangles = std::uint32_t(p.indices.size() / 3);
            }
            s->m_primitives.push_back(pc);
        }
    }
    if (!clusters.empty()) LANTERN_TRY(s->append(clusters));
    return s;
}

// A buffer of the clusters there are and `added` after them: the old ones copied on the device
// (not computed again), the old buffer kept for the frames in flight.
Result<void> SceneClusters::append(const std::vector<ClusterData>& added) {
    const VkDeviceSize kept = VkDeviceSize(m_clusterCount) * sizeof(ClusterData);
    const VkDeviceSize bytes = added.size() * sizeof(ClusterData);
    auto buffer = createBuffer(m_ctx, kept + bytes,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               MemoryUsage::DeviceLocal, "scene clusters");
    if (!buffer) return std::move(buffer).error();
    if (kept > 0)
        LANTERN_TRY(m_ctx.submitAndWait([&](VkCommandBuffer cmd) {
            const VkBufferCopy region{0, 0, kept};
            vkCmdCopyBuffer(cmd, m_clusters.get(), buffer->get(), 1, &region);
            memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
        }));
    if (m_clusters.get()) m_retired.push_back(std::move(m_clusters));
    m_clusters = std::move(*buffer);
    m_clusterCount += std::uint32_t(added.size());
    return uploadToBuffer(m_ctx, m_clusters, kept, added.data(), bytes);
}

// Each level simplifies the one before to half its triangles (meshopt_simplify keeps
// the order of the triangles it keeps, so the runs stay coherent); its error is the sum of the
// steps' (an upper bound of its distance from the full mesh). The chain stops where a step
// cannot remove a fifth, or a level would have under 16 triangles.
Result<void> SceneClusters::ensureLevels() {
    std::lock_guard lock(m_mutex);
    if (m_levelsBuilt) return {};
    m_levelsBuilt = true;
    std::vector<ClusterData> clusters;
    std::vector<std::uint32_t> lod;
    std::size_t k = 0;
    for (const Mesh& mesh : m_scene->meshes)
        for (const Primitive& p : mesh.primitives) {
            PrimitiveClusters& pc = m_primitives[k++];
            if (pc.levelCount == 0) continue;
            pc.levelCount = 1;  // level 0's clusters are on the device already
            const float* positions = &p.positions[0].x;
            const float scale = meshopt_simplifyScale(positions, p.positions.size(), 12);
            std::vector<std::uint32_t> current = p.indices, next(p.indices.size());
            double error = 0.0;
            while (pc.levelCount < LANTERN_CULL_MAX_LEVELS && lod.size() < (1u << 30)) {
                const std::size_t target = current.size() / 6 * 3;
                if (target < 3 * 16) break;
                float stepError = 0.0f;
                const std::size_t n = meshopt_simplify(next.data(), current.data(), current.size(), positions,
                                                       p.positions.size(), 12, target, 1.0f, 0, &stepError);
                if (n == 0 || n * 5 > current.size() * 4) break;
                error += double(stepError) * scale;
                const std::size_t at = m_clusterCount + clusters.size();
                clustersOf(p, next.data(), n, std::uint32_t(lod.size()), clusters);
                lod.insert(lod.end(), next.begin(), next.begin() + std::ptrdiff_t(n));
                pc.levels[pc.levelCount++] = {float(error * 1.0001), std::uint32_t(at),
                                              std::uint32_t(m_clusterCount + clusters.size() - at), 0};
                current.assign(next.begin(), next.begin() + std::ptrdiff_t(n));
            }
        }
    if (clusters.empty()) return {};
    LANTERN_TRY(append(clusters));
    if (lod.empty()) return {};
    const VkDeviceSize bytes = lod.size() * 4;
    auto buffer = createBuffer(m_ctx, bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               MemoryUsage::DeviceLocal, "levels of detail");
    if (!buffer) return std::move(buffer).error();
    m_lodIndices = std::move(*buffer);
    return uploadToBuffer(m_ctx, m_lodIndices, 0, lod.data(), bytes);
}

Result<void> SceneClusters::update(std::uint32_t mesh, std::uint32_t prim) {
    std::lock_guard lock(m_mutex);
    PrimitiveClusters& pc = m_primitives[m_meshFirst[mesh] + prim];
    if (pc.levelCount == 0) return {};
    const Primitive& p = m_scene->meshes[mesh].primitives[prim];
    std::vector<ClusterData> clusters;
    clustersOf(p, p.indices.data(), p.indices.size(), 0, clusters);
    pc.levelCount = 1;
    pc.sphere = enclosing(clusters.data(), clusters.size());
    return uploadToBuffer(m_ctx, m_clusters, pc.levels[0].firstCluster * sizeof(ClusterData),
                          clusters.data(), clusters.size() * sizeof(ClusterData));
}

} // namespace lantern::gpu
