// Pipelines.h: the shader programs and their pipeline variants. One pipeline layout (the frame
// set, the texture set, the per-triangle flat set, the push-constant DrawBlock) serves every
// program; shader modules are
// made from the embedded SPIR-V on first use, and a pipeline per PipelineKey on first use,
// then cached (and compiled through the context's VkPipelineCache).
#pragma once

#include "gpu/Context.h"
#include "gpu/DrawList.h"
#include "gpu/Handles.h"
#include "gpu/Pipeline.h"

#include <map>
#include <unordered_map>
#include <vector>

namespace lantern::gpu {

class Pipelines {
public:
    static Result<Pipelines> create(Context& ctx);
    Pipelines(Pipelines&&) noexcept = default;

    VkPipelineLayout layout() const { return m_layout.get(); }
    VkDescriptorSetLayout frameSetLayout() const { return m_frameLayout.get(); }
    VkDescriptorSetLayout textureSetLayout() const { return m_textureLayout.get(); }
    /// The geometry, deformed streams and jobs of per-triangle flat shading (gpu/FlatLight.h),
    /// read by its pre-pass and by its draws' vertex stage.
    VkDescriptorSetLayout flatSetLayout() const { return m_flatLayout.get(); }

    /// The pipeline for a variant (created on first use).
    Result<VkPipeline> pipeline(const PipelineKey& key);
    /// Creates every variant of `keys` not made yet, several at once on as many threads.
    Result<void> prepare(const std::vector<PipelineKey>& keys);
    std::size_t count() const { return m_pipelines.size(); }

    /// A shader module of the embedded registry (shaders::ShaderId), made on first use.
    Result<VkShaderModule> shader(std::uint32_t id);

    /// A compute pre-pass of its own (deformation, cluster culling): a set of `storageBuffers`
    /// storage buffers at bindings 0, 1, ..., a layout of that set and `pushBytes` of push
    /// constants, and the pipeline of compute shader `shaderId`, named `name`.
    struct ComputePass {
        UniqueDescriptorSetLayout setLayout;
        UniquePipelineLayout layout;
        UniquePipeline pipeline;
    };
    Result<ComputePass> computePass(std::uint32_t shaderId, std::uint32_t storageBuffers,
                                    std::uint32_t pushBytes, const char* name);

private:
    Pipelines() = default;
    Result<GraphicsPipelineDesc> describe(const PipelineKey& key);

    Context* m_ctx = nullptr;
    UniqueDescriptorSetLayout m_frameLayout, m_textureLayout, m_flatLayout;
    UniquePipelineLayout m_layout;
    std::map<std::uint32_t, UniqueShaderModule> m_shaders;
    std::unordered_map<PipelineKey, UniquePipeline, PipelineKeyHash> m_pipelines;
};

} // namespace lantern::gpu
