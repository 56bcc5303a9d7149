// Shader modules and graphics pipelines (dynamic rendering).
#include "gpu/Pipeline.h"

#include <array>

namespace lantern::gpu {

Result<UniqueShaderModule> createShaderModule(Context& ctx, std::span<const std::uint32_t> words,
                                              const std::string& name) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = words.size() * sizeof(std::uint32_t);
    ci.pCode = words.data();
    VkShaderModule module = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateShaderModule(ctx.device(), &ci, nullptr, &module));
    ctx.setName(VK_OBJECT_TYPE_SHADER_MODULE, module, name);
    return UniqueShaderModule(ctx.device(), module);
}

namespace {

VkSpecializationInfo specializationInfo(const GraphicsPipelineDesc& d) {
    VkSpecializationInfo spec{};
    spec.mapEntryCount = std::uint32_t(d.specEntries.size());
    spec.pMapEntries = d.specEntries.data();
    spec.dataSize = d.specData.size() * sizeof(std::uint32_t);
    spec.pData = d.specData.data();
    return spec;
}

// Vertex and fragment stages, both specialised by `spec`.
std::array<VkPipelineShaderStageCreateInfo, 2> shaderStages(const GraphicsPipelineDesc& d,
                                                            const VkSpecializationInfo* spec) {
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = d.vertex;
    stages[0].pName = "main";
    stages[0].pSpecializationInfo = spec;
    stages[1] = stages[0];
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = d.fragment;
    return stages;
}

VkPipelineVertexInputStateCreateInfo vertexInputState(const GraphicsPipelineDesc& d) {
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = std::uint32_t(d.bindings.size());
    vi.pVertexBindingDescriptions = d.bindings.data();
    vi.vertexAttributeDescriptionCount = std::uint32_t(d.attributes.size());
    vi.pVertexAttributeDescriptions = d.attributes.data();
    return vi;
}

// `next`: the provoking-vertex state, or null.
VkPipelineRasterizationStateCreateInfo rasterizationState(const GraphicsPipelineDesc& d,
                                                          const void* next) {
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.pNext = next;
    rs.polygonMode = d.polygonMode;
    rs.cullMode = VK_CULL_MODE_NONE;                 // dynamic
    rs.frontFace = VK_FRONT_FACE_CLOCKWISE;          // dynamic
    rs.depthBiasEnable = d.depthBias ? VK_TRUE : VK_FALSE;
    rs.lineWidth = 1.0f;
    return rs;
}

VkPipelineDepthStencilStateCreateInfo depthStencilState(const GraphicsPipelineDesc& d) {
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = d.depthTest && d.depthFormat != VK_FORMAT_UNDEFINED ? VK_TRUE : VK_FALSE;
    ds.depthWriteEnable = d.depthWrite ? VK_TRUE : VK_FALSE;
    ds.depthCompareOp = d.depthCompare;
    return ds;
}

std::vector<VkPipelineColorBlendAttachmentState> blendAttachments(const GraphicsPipelineDesc& d) {
    std::vector<VkPipelineColorBlendAttachmentState> blends(d.colorFormats.size());
    for (auto& b : blends) b.colorWriteMask = 0xF;
    if (!d.colorWrite && !blends.empty()) blends[0].colorWriteMask = 0;
    if (d.premultiplied && !blends.empty()) {
        blends[0].blendEnable = VK_TRUE;
        blends[0].srcColorBlendFactor = blends[0].srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blends[0].dstColorBlendFactor = blends[0].dstAlphaBlendFactor =
            VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    }
    if (d.weightedSums && blends.size() == 2) {
        blends[0].blendEnable = blends[1].blendEnable = VK_TRUE;
        blends[0].srcColorBlendFactor = blends[0].srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blends[0].dstColorBlendFactor = blends[0].dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blends[1].srcColorBlendFactor = blends[1].srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
        blends[1].dstColorBlendFactor = blends[1].dstAlphaBlendFactor =
            VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR;
    }
    if (d.blend && !blends.empty()) {
        // Straight-alpha "over" into a premultiplied target (the EXR convention):
        // rgb = a * src + (1 - a) * dst, alpha = a + (1 - a) * dstAlpha.
        blends[0].blendEnable = VK_TRUE;
        blends[0].srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
        blends[0].dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blends[0].colorBlendOp = VK_BLEND_OP_ADD;
        blends[0].srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blends[0].dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blends[0].alphaBlendOp = VK_BLEND_OP_ADD;
    }
    return blends;
}

std::vector<VkDynamicState> dynamicStates(const GraphicsPipelineDesc& d) {
    std::vector<VkDynamicState> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                           VK_DYNAMIC_STATE_CULL_MODE, VK_DYNAMIC_STATE_FRONT_FACE};
    // Dynamic strides only with vertex buffers: a pipeline without them (per-triangle flat
    // pulls its corners) would otherwise need vkCmdBindVertexBuffers2 before its draws.
    if (!d.bindings.empty()) dynamic.push_back(VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE);
    if (d.depthBias) dynamic.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
    if (d.polygonMode == VK_POLYGON_MODE_LINE || d.topology == VK_PRIMITIVE_TOPOLOGY_LINE_LIST)
        dynamic.push_back(VK_DYNAMIC_STATE_LINE_WIDTH);
    return dynamic;
}

} // namespace

Result<UniquePipeline> createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& d) {
    const VkSpecializationInfo spec = specializationInfo(d);
    const std::array<VkPipelineShaderStageCreateInfo, 2> stages = shaderStages(d, &spec);
    const VkPipelineVertexInputStateCreateInfo vi = vertexInputState(d);

    VkPipelineInputAssemblyStateCreateInfo ia{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = d.topology;

    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.scissorCount = 1;

    VkPipelineRasterizationProvokingVertexStateCreateInfoEXT provoking{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_PROVOKING_VERTEX_STATE_CREATE_INFO_EXT};
    provoking.provokingVertexMode = VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT;
    if (d.provokingLast && !ctx.capabilities().provokingVertexLast)
        return makeError(ErrorCode::Unsupported,
                         "the device lacks VK_EXT_provoking_vertex (provokingVertexLast), "
                         "needed for GL-compatible flat shading");
    const VkPipelineRasterizationStateCreateInfo rs =
        rasterizationState(d, d.provokingLast ? &provoking : nullptr);

    VkPipelineMultisampleStateCreateInfo ms{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = d.samples;

    const VkPipelineDepthStencilStateCreateInfo ds = depthStencilState(d);

    const std::vector<VkPipelineColorBlendAttachmentState> blends = blendAttachments(d);
    VkPipelineColorBlendStateCreateInfo cb{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = std::uint32_t(blends.size());
    cb.pAttachments = blends.data();

    const std::vector<VkDynamicState> dynamic = dynamicStates(d);
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = std::uint32_t(dynamic.size());
    dyn.pDynamicStates = dynamic.data();

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = std::uint32_t(d.colorFormats.size());
    rendering.pColorAttachmentFormats = d.colorFormats.data();
    rendering.depthAttachmentFormat = d.depthFormat;

    VkGraphicsPipelineCreateInfo pci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    pci.stageCount = d.fragment != VK_NULL_HANDLE ? 2 : 1;  // none: depth only
    pci.pStages = stages.data();
    pci.pVertexInputState = &vi;
    pci.pInputAssemblyState = &ia;
    pci.pViewportState = &vp;
    pci.pRasterizationState = &rs;
    pci.pMultisampleState = &ms;
    pci.pDepthStencilState = &ds;
    pci.pColorBlendState = &cb;
    pci.pDynamicState = &dyn;
    pci.layout = d.layout;

    VkPipeline pipeline = VK_NULL_HANDLE;
    LANTERN_VK_TRY(
        vkCreateGraphicsPipelines(ctx.device(), ctx.pipelineCache(), 1, &pci, nullptr, &pipeline));
    ctx.setName(VK_OBJECT_TYPE_PIPELINE, pipeline, d.name);
    return UniquePipeline(ctx.device(), pipeline);
}

} // namespace lantern::gpu
