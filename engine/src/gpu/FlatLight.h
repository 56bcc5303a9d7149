// FlatLight.h: flat shading lit once per triangle. Before a frame's draws, one compute dispatch
// per flat triangle draw (shaders/flatlight.comp) lights each triangle the rasteriser may draw
// once, at its centroid with its face normal, and writes its colour into the frame slot's
// record buffer, and the draw's index list: triangle t as vertices (t, count + v1, count + v2),
// a skipped one as (count, count, count). The draw is indexed, without vertex buffers: its
// vertex stage (shaders/flat.vert) maps a vertex back to its mesh corner (vertex t is triangle
// t's first corner, the one that provokes; count + v is mesh vertex v), pulls it from the
// job's index and position words as the pass did, and vertex t passes triangle t's record
// index to the fragment stage as a flat varying. A shared corner is shaded once, and the
// triangles the pass skipped shade no vertex. (Not gl_PrimitiveID: on llvmpipe a fragment
// shader reading it sends the draw through a primitive assembler that de-indexes the mesh on
// the CPU and reallocates per primitive; docs/performance.md.) Gouraud lights every vertex, the per-corner path three
// corners per triangle; this pass lights only the triangles that face the camera inside the
// view, on every core the device has. Taken where the scene's geometry fits one storage-buffer
// binding; otherwise flat draws keep the per-corner streams (gpu/SceneBuffers.cpp). Points and
// lines always keep them.
#pragma once

#include "gpu/Context.h"
#include "gpu/Deform.h"
#include "gpu/DrawList.h"
#include "gpu/Handles.h"
#include "gpu/Pipelines.h"
#include "gpu/Resources.h"
#include "gpu/SceneBuffers.h"

#include <array>
#include <map>
#include <memory>
#include <vector>

namespace lantern::gpu {

/// FlatSlot::drawJobs of a draw that is not lit per triangle.
inline constexpr std::uint32_t kNoFlatJob = ~0u;

/// One frame slot's per-triangle flat lighting.
struct FlatSlot {
    Buffer jobs;     ///< one FlatJob per flat triangle draw (host-written)
    Buffer records;  ///< the triangles' records (flat.glsl), then their normals
    Buffer indices;  ///< the draws' index lists, three per triangle at 3 x its record (flat.vert)
    VkDeviceSize recordBytes = 0, normalOffset = 0, normalBytes = 0;
    UniqueDescriptorPool pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
    struct Dispatch {
        std::uint32_t job = 0, view = 0, groups = 0;
        VkPipeline pipeline = VK_NULL_HANDLE;
    };
    std::vector<Dispatch> dispatches;
    /// Per draw, in list order across the views: its job (DrawBlock::flatJob), or kNoFlatJob.
    std::vector<std::uint32_t> drawJobs;
    std::vector<std::uint32_t> firstRecords;  ///< per job: its first triangle record (FlatJob::flatBase)
    std::uint64_t triangles = 0;  ///< triangles given to the pass this frame
    bool any() const { return !dispatches.empty(); }
};

class FlatLighter {
public:
    static Result<std::unique_ptr<FlatLighter>> create(Context& ctx, Pipelines& pipelines);

    /// Whether this frame's flat triangle draws of `scene` may be lit per triangle: the
    /// geometry and the frame's records each fit one storage-buffer binding.
    static bool available(const Context& ctx, const SceneBuffers& scene, const DrawList& list);
    /// The triangles of a draw lit per triangle; its indexed draw takes three indices each
    /// from FlatSlot::indices at three times its first record.
    static std::uint32_t triangleCount(const PrimitiveBuffers& gp);
    /// Whether draw `key` is lit per triangle in a frame where the pass is `available`.
    static bool perTriangle(const PipelineKey& key, bool available) {
        return available && key.program == frame::Program::Flat &&
               key.topology == Topology::Triangles;
    }

    /// Fills `slot` for `list`: jobs written, records sized, pipelines made, descriptors
    /// pointed at the geometry and `deform`'s output. `available`: as available() said.
    Result<void> prepare(FlatSlot& slot, const DrawList& list, const SceneBuffers& scene,
                         const DeformSlot* deform, bool available);

    /// Records the dispatches between the barriers that order them after the deformation
    /// pre-pass and before the draws' reads (the vertex stage's of the deformed positions,
    /// the fragment stage's of the records). `frameOffsets`, `lightOffsets`: per view, the
    /// dynamic offsets of the frame set.
    void record(VkCommandBuffer cmd, const FlatSlot& slot, VkDescriptorSet frameSet,
                const std::vector<VkDeviceSize>& frameOffsets,
                const std::vector<VkDeviceSize>& lightOffsets) const;

private:
    FlatLighter(Context& ctx, Pipelines& pipelines) : m_ctx(ctx), m_pipelines(pipelines) {}
    Result<VkPipeline> pipeline(const std::array<std::uint32_t, LANTERN_SC_COUNT>& constants);
    Result<void> ensureDescriptorSet(FlatSlot& slot);
    Context& m_ctx;
    Pipelines& m_pipelines;
    UniquePipelineLayout m_layout;
    std::map<std::array<std::uint32_t, LANTERN_SC_COUNT>, UniquePipeline> m_variants;
};

} // namespace lantern::gpu
