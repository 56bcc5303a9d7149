// Pipeline.h: graphics pipelines for dynamic rendering (no render passes or framebuffers),
// built from a plain description. Viewport, scissor, cull mode, front face and vertex-buffer
// strides are dynamic state, so one pipeline serves every view, material side and mesh layout.
#pragma once

#include "gpu/Context.h"
#include "gpu/Handles.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lantern::gpu {

Result<UniqueShaderModule> createShaderModule(Context& ctx, std::span<const std::uint32_t> words,
                                              const std::string& name);

struct GraphicsPipelineDesc {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkShaderModule vertex = VK_NULL_HANDLE;
    VkShaderModule fragment = VK_NULL_HANDLE;  ///< none: a depth-only pipeline
    /// Specialisation constants, applied to both stages: entries index into `specData`.
    std::vector<VkSpecializationMapEntry> specEntries;
    std::vector<std::uint32_t> specData;
    std::vector<VkVertexInputBindingDescription> bindings;
    std::vector<VkVertexInputAttributeDescription> attributes;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    bool blend = false;  ///< straight-alpha "over" on attachment 0, premultiplied result
    bool premultiplied = false;  ///< premultiplied "over" on attachment 0 (the transparency composites)
    /// Weighted transparency's pass: attachment 0 adds (ONE, ONE), attachment 1 multiplies by
    /// one minus the source (ZERO, ONE_MINUS_SRC_COLOR).
    bool weightedSums = false;
    bool colorWrite = true;  ///< false: attachment 0 is not written (the fragment stores elsewhere)
    bool depthTest = true;  ///< with a depth format: the depth test is on
    bool depthWrite = true;
    VkCompareOp depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL;
    bool provokingLast = false;  ///< VK_EXT_provoking_vertex: the last vertex (GL's rule)
    bool depthBias = false;      ///< dynamic depth bias (overlays)
    std::string name;
};

Result<UniquePipeline> createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc);

} // namespace lantern::gpu
