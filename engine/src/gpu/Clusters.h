// Clusters.h: large triangle meshes split into clusters, and the compute pass that drops the
// clusters a frame cannot see before its draws (shaders/cull.comp).
//
// A cluster is a run of LANTERN_CLUSTER_TRIANGLES consecutive triangles of a primitive's index
// list (the last one shorter), in the file's order, with a bounding sphere and a normal cone
// from meshoptimizer (meshopt_computeClusterBounds). Because the runs keep the order, the
// clusters a frame keeps, drawn as indirect draws in order, rasterise exactly the triangles
// (and in the order) of the whole draw minus those that make no fragment: the picture is
// bit-identical to drawing everything (tests/integration/ClusterCullingTest.cpp).
//
// Per frame, one record per (view, draw, instance) of each clustered draw; one invocation per
// draw walks its instances' clusters in order, testing each against the view's clip volume
// (the sphere wholly beyond one plane) and, where the draw culls back faces under a
// perspective view and a similarity transform, against its normal cone with a margin the
// rasteriser's snapping cannot cross. Kept neighbours merge into one indirect draw (their
// index ranges touch), written compacted with their count: the draw is one
// vkCmdDrawIndexedIndirectCount (lavapipe pays per indirect draw, empty ones too, so none is
// written). With a level-of-detail bound (RenderOptions::lodError) a record first picks the
// coarsest level of its mesh (meshopt_simplify, built on first use) whose error, projected at
// the mesh's nearest depth, stays under the bound, and culls that level's clusters.
#pragma once

#include "gpu/Context.h"
#include "gpu/DrawList.h"
#include "gpu/Handles.h"
#include "gpu/Pipelines.h"
#include "gpu/Resources.h"

#include <lantern/Scene.h>

#include <array>
#include <memory>
#include <mutex>
#include <vector>

namespace lantern::gpu {

class SceneBuffers;

/// One cluster as the pass reads it (Cluster in shaders/cull.comp).
struct ClusterData {
    Vec4 sphere;  ///< model-space centre and radius (padded: no rounding lets a vertex out)
    Vec4 apex;    ///< the normal cone's apex (xyz)
    Vec4 axis;    ///< the cone's axis (xyz) and cutoff (w; 1: no cone)
    std::uint32_t firstIndex = 0, indexCount = 0;  ///< into its level's index list
    std::uint32_t padding[2] = {};
};
static_assert(sizeof(ClusterData) == 64);

/// One level of detail of a mesh (Level in cull.comp).
struct CullLevel {
    float error = 0.0f;  ///< object-space distance from the full mesh (0 for level 0)
    std::uint32_t firstCluster = 0, clusterCount = 0, padding = 0;
};
static_assert(sizeof(CullLevel) == 16);

/// One (view, draw, instance) of the frame (Record in cull.comp).
struct CullRecord {
    Mat4 viewFromModel;
    Vec4 normalMatrix[3];
    Vec4 sphere;  ///< the whole mesh's bounds (model space): the level's projected error
    std::uint32_t view = 0, flags = 0;
    std::uint32_t firstCommand = 0;  ///< the draw's commands from the geometry's index list
    std::uint32_t slots = 0;         ///< level 0's cluster count
    std::uint32_t firstInstance = 0, levelCount = 1;
    std::uint32_t lodCommand = ~0u;  ///< the draw's commands from the coarser levels' list; ~0u: none
    std::uint32_t drawRecords = 0;   ///< on a draw's first record: its records; 0 on the others
    float scale = 1.0f;              ///< the longest axis of viewFromModel (the radii's factor)
    /// Level 0's first index in the geometry buffer, which its draws bind at offset 0 (lavapipe
    /// ignores the offset of an index buffer bound for indirect draws)
    std::uint32_t indexBase = 0;
    std::uint32_t lodSlots = 0;  ///< the coarser levels' commands per record: level 1's cluster count
    std::uint32_t countIndex = 0;  ///< the draw's counts in the counts buffer (1 + 2 countIndex)
    std::array<CullLevel, LANTERN_CULL_MAX_LEVELS> levels{};
};
static_assert(sizeof(CullRecord) == 304);

/// One view's clip volume and projection (View in cull.comp).
struct CullView {
    Vec4 planes[6];  ///< view space: a point p is inside when dot(xyz, p) + w >= 0 for all
    /// x: pixels per unit at depth 1 (perspective) or per unit (orthographic); y: 1 perspective
    /// with the eye at the origin, 0 orthographic; z: 1 when the cone test holds (perspective,
    /// GL's winding); w: the level-of-detail bound in pixels (0: level 0 always)
    Vec4 projection;
};
static_assert(sizeof(CullView) == 112);

/// A primitive's clusters: its levels (level 0 the full index list); levelCount 0: not
/// clustered (too small, not triangles, not indexed).
struct PrimitiveClusters {
    std::uint32_t levelCount = 0;
    std::array<CullLevel, LANTERN_CULL_MAX_LEVELS> levels{};
    Vec4 sphere;  ///< the whole primitive's bounds (model space)
    std::uint32_t triangles = 0;  ///< level 0's
};

/// A scene's clusters on the device: built with its SceneBuffers (level 0), the coarser levels
/// on first use (ensureLevels). No host copy is kept: the scene's own lists are read again.
class SceneClusters {
public:
    static Result<std::unique_ptr<SceneClusters>> create(Context& ctx, std::shared_ptr<const Scene> scene);
    const PrimitiveClusters* primitive(std::uint32_t mesh, std::uint32_t prim) const {
        const PrimitiveClusters& p = m_primitives[m_meshFirst[mesh] + prim];
        return p.levelCount > 0 ? &p : nullptr;
    }
    bool any() const { return m_clusters.get() != VK_NULL_HANDLE; }
    VkBuffer clusters() const { return m_clusters.get(); }
    /// The coarser levels' index lists (null before ensureLevels, or when no mesh simplified).
    VkBuffer lodIndices() const { return m_lodIndices.get(); }
    /// Builds every clustered primitive's coarser levels, once (thread-safe).
    Result<void> ensureLevels();
    bool levelsBuilt() const { return m_levelsBuilt; }
    /// Primitive `prim` of mesh `mesh` has new positions: its clusters' bounds again, and its
    /// coarser levels dropped (the device is idle: SceneBuffers::updateVertices).
    Result<void> update(std::uint32_t mesh, std::uint32_t prim);
    std::size_t bytes() const { return std::size_t(m_clusters.size + m_lodIndices.size); }

private:
    explicit SceneClusters(Context& ctx) : m_ctx(ctx) {}
    Result<void> append(const std::vector<ClusterData>& added);
    Context& m_ctx;
    std::shared_ptr<const Scene> m_scene;
    std::vector<PrimitiveClusters> m_primitives;
    std::vector<std::size_t> m_meshFirst;
    Buffer m_clusters, m_lodIndices;
    std::uint32_t m_clusterCount = 0;  ///< in m_clusters
    std::vector<Buffer> m_retired;  ///< replaced while a frame in flight may read them
    std::mutex m_mutex;
    bool m_levelsBuilt = false;
};

/// One frame slot's culling pass.
struct CullSlot {
    Buffer records, views, commands, counts;
    UniqueDescriptorPool pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
    std::uint32_t recordCount = 0;
    /// Per draw, in list order across the views: its indirect draws (count 0: drawn directly).
    struct Range {
        std::uint32_t first = 0, count = 0;  ///< the full list's commands (at most `count`)
        std::uint32_t lodFirst = ~0u, lodCount = 0;  ///< the coarser levels'; ~0u: none
        std::uint32_t countIndex = 0;  ///< their counts: counts[1 + 2 countIndex], [2 + 2 countIndex]
    };
    std::vector<Range> draws;
    VkBuffer lodIndices = VK_NULL_HANDLE;  ///< the coarser levels' index buffer
    std::uint64_t triangles = 0;  ///< the clustered draws' triangles at full detail
    bool any() const { return recordCount > 0; }
    const Range* range(std::size_t draw) const {
        return draw < draws.size() && draws[draw].count > 0 ? &draws[draw] : nullptr;
    }
};

class Culler {
public:
    static Result<std::unique_ptr<Culler>> create(Context& ctx, Pipelines& pipelines);
    /// Fills `slot` for `list` (nothing when the list does not cull, the device cannot draw
    /// indirectly many times, or no draw is clustered).
    Result<void> prepare(CullSlot& slot, const DrawList& list, const SceneBuffers& scene);
    /// The dispatch, between the barriers that order it after the counters' reset and before
    /// the draws' indirect reads.
    void record(VkCommandBuffer cmd, const CullSlot& slot) const;

private:
    explicit Culler(Context& ctx) : m_ctx(ctx) {}
    Result<void> upload(CullSlot& slot, const std::vector<CullRecord>& records,
                        const std::vector<CullView>& views, VkDeviceSize commandBytes,
                        VkDeviceSize countBytes, const SceneClusters& clusters);
    Context& m_ctx;
    UniqueDescriptorSetLayout m_setLayout;
    UniquePipelineLayout m_layout;
    UniquePipeline m_pipeline;
};

/// Records the draws of `range`: level 0's indirect draws from `geometry`'s indices, then the
/// coarser levels' from their own list.
void drawClusters(VkCommandBuffer cmd, const CullSlot& slot, const CullSlot::Range& range,
                  VkBuffer geometry);

} // namespace lantern::gpu
