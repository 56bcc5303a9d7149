// Deform.h: the skinning and morph-target pre-pass. Before a frame's draws, one compute
// dispatch per DeformCommand (shaders/deform.comp) writes the deformed positions and normals
// (or flat-shading streams) into the frame slot's own output buffer, which the draws then
// bind as vertex streams. Per slot, so a frame in flight never sees the next frame's pose; a
// frame without deformation records nothing and allocates nothing.
#pragma once

#include "gpu/Context.h"
#include "gpu/DrawList.h"
#include "gpu/Handles.h"
#include "gpu/Pipelines.h"
#include "gpu/Resources.h"
#include "gpu/SceneBuffers.h"

#include <memory>
#include <vector>

namespace lantern::gpu {

/// Where a DeformCommand's results lie in the slot's output buffer (bytes).
struct DeformStreams {
    VkDeviceSize position = 0, normal = 0, centroid = 0;
};

/// One frame slot's deformation state.
struct DeformSlot {
    Buffer params;  ///< joint matrices and morph weights (host-written)
    Buffer output;  ///< deformed streams (storage + vertex buffer)
    UniqueDescriptorPool pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
    std::vector<DeformJob> jobs;          ///< push constants, one per DeformCommand
    std::vector<DeformStreams> streams;   ///< one per DeformCommand
};

class Deformer {
public:
    static Result<std::unique_ptr<Deformer>> create(Context& ctx, Pipelines& pipelines);

    /// Fills `slot` for `list` (which has deforms): parameters written, output sized,
    /// descriptors pointed at the scene's inputs. `flatPerTriangle`: flat triangles are lit by
    /// the per-triangle pass (gpu/FlatLight.h), which reads per-vertex deformed positions, so
    /// only flat points and lines get the per-corner streams.
    Result<void> prepare(DeformSlot& slot, const DrawList& list, const SceneBuffers& scene,
                         bool flatPerTriangle);

    /// Records the dispatches and the barrier that makes their output vertex input.
    void record(VkCommandBuffer cmd, const DeformSlot& slot) const;

private:
    explicit Deformer(Context& ctx) : m_ctx(ctx) {}
    Result<void> ensureDescriptorSet(DeformSlot& slot);  ///< the slot's pool and set, once
    Context& m_ctx;
    UniqueDescriptorSetLayout m_setLayout;
    UniquePipelineLayout m_layout;
    UniquePipeline m_pipeline;
};

} // namespace lantern::gpu
