// The wireframe and normals overlays: pipelines made on first use per (kind, samples, depth
// mode), recorded per view after the view's shaded draws.
#include "gpu/Overlays.h"

#include "gpu/Pipeline.h"
#include "gpu/Pipelines.h"
#include "gpu/Targets.h"

#include "ShaderBlobs.h"

namespace lantern::gpu {
namespace {

using shaders::ShaderId;

// Lines lie on their triangles: lift them toward the eye by a few depth units, plus more where
// the triangle is steep, so they win the depth test against their own surface.
constexpr float kBiasConstant = 4.0f;
constexpr float kBiasSlope = 1.5f;

} // namespace

Result<void> OverlayPipelines::check(const Context& ctx, const Overlays& o, const AovSet& aovs) {
    if (o.any() && aovs.any())
        return makeError(ErrorCode::InvalidInput,
                         "the wireframe and normals overlays are for display and cannot be "
                         "combined with AOVs",
                         "options.wireframe/normals");
    if (o.wireframe && !ctx.capabilities().fillModeNonSolid)
        return makeError(ErrorCode::Unsupported,
                         "the device lacks fillModeNonSolid, needed for the wireframe overlay",
                         "options.wireframe");
    return {};
}

Result<VkPipeline> OverlayPipelines::pipeline(bool normals, std::uint32_t samples, bool reversedZ) {
    const auto key = std::make_tuple(normals, samples, reversedZ);
    if (auto it = m_cache.find(key); it != m_cache.end()) return it->second.get();
    auto vs = m_pipelines.shader(std::uint32_t(normals ? ShaderId::normals_vert : ShaderId::wireframe_vert));
    if (!vs) return std::move(vs).error();
    auto fs = m_pipelines.shader(std::uint32_t(ShaderId::debug_frag));
    if (!fs) return std::move(fs).error();

    GraphicsPipelineDesc d;
    d.layout = m_pipelines.layout();
    d.vertex = *vs;
    d.fragment = *fs;
    if (normals) {
        // Position and normal step once per instance; gl_VertexIndex picks the line's end.
        d.bindings = {{LANTERN_LOC_POSITION, 12, VK_VERTEX_INPUT_RATE_INSTANCE},
                      {LANTERN_LOC_NORMAL, 12, VK_VERTEX_INPUT_RATE_INSTANCE}};
        d.attributes = {{LANTERN_LOC_POSITION, LANTERN_LOC_POSITION, VK_FORMAT_R32G32B32_SFLOAT, 0},
                        {LANTERN_LOC_NORMAL, LANTERN_LOC_NORMAL, VK_FORMAT_R32G32B32_SFLOAT, 0}};
        d.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    } else {
        d.bindings = {{LANTERN_LOC_POSITION, 12, VK_VERTEX_INPUT_RATE_VERTEX}};
        d.attributes = {{LANTERN_LOC_POSITION, LANTERN_LOC_POSITION, VK_FORMAT_R32G32B32_SFLOAT, 0}};
        d.polygonMode = VK_POLYGON_MODE_LINE;
        d.depthBias = true;
    }
    d.colorFormats = {kColorFormat};
    d.depthFormat = kDepthFormat;
    d.samples = VkSampleCountFlagBits(samples);
    d.depthWrite = false;
    d.depthCompare = reversedZ ? VK_COMPARE_OP_GREATER_OR_EQUAL : VK_COMPARE_OP_LESS_OR_EQUAL;
    d.name = normals ? "overlay: normals" : "overlay: wireframe";
    auto p = createGraphicsPipeline(m_ctx, d);
    if (!p) return std::move(p).error();
    const VkPipeline handle = p->get();
    m_cache.emplace(key, std::move(*p));
    return handle;
}

Result<OverlayFrame> OverlayPipelines::prepare(const Overlays& o, const TargetDesc& target) {
    OverlayFrame f;
    if (o.wireframe) {
        auto p = pipeline(false, target.samples, target.reversedZ);
        if (!p) return std::move(p).error();
        f.wireframe = *p;
    }
    if (o.normals) {
        auto p = pipeline(true, target.samples, target.reversedZ);
        if (!p) return std::move(p).error();
        f.normals = *p;
        f.normalLength = o.normalLength;
    }
    f.depthBias = target.reversedZ ? 1.0f : -1.0f;
    return f;
}

void OverlayPipelines::recordView(VkCommandBuffer cmd, const SceneBuffers& scene,
                                  const ViewCommands& view, VkDescriptorSet frameSet,
                                  const FrameSetOffsets& dynamicOffsets,
                                  const OverlayFrame& f) const {
    const VkPipelineLayout layout = m_pipelines.layout();
    if (!f.any() || view.draws.empty()) return;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, LANTERN_SET_FRAME, 1,
                            &frameSet, std::uint32_t(dynamicOffsets.size()), dynamicOffsets.data());
    const VkBuffer geometry = scene.geometry();
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    if (f.wireframe) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.wireframe);
        vkCmdSetLineWidth(cmd, 1.0f);
        vkCmdSetDepthBias(cmd, f.depthBias * kBiasConstant, 0.0f, f.depthBias * kBiasSlope);
        for (const DrawCommand& d : view.draws) {
            if (d.pipeline.topology != Topology::Triangles) continue;  // lines are their own wires
            const PrimitiveBuffers& gp = scene.primitive(d.mesh, d.primitive);
            vkCmdSetCullMode(cmd, d.cullBack ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE);
            vkCmdSetFrontFace(cmd, d.frontClockwise ? VK_FRONT_FACE_CLOCKWISE
                                              : VK_FRONT_FACE_COUNTER_CLOCKWISE);
            vkCmdPushConstants(cmd, layout, stages, 0, sizeof(DrawBlock), &d.block);
            const VkDeviceSize offset = gp.position, stride = 12;
            vkCmdBindVertexBuffers2(cmd, LANTERN_LOC_POSITION, 1, &geometry, &offset, nullptr, &stride);
            if (gp.indexCount > 0) {
                vkCmdBindIndexBuffer(cmd, geometry, gp.index, VK_INDEX_TYPE_UINT32);
                vkCmdDrawIndexed(cmd, gp.indexCount, 1, 0, 0, 0);
            } else {
                vkCmdDraw(cmd, gp.vertexCount, 1, 0, 0);
            }
        }
    }
    if (f.normals) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.normals);
        vkCmdSetLineWidth(cmd, 1.0f);
        vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
        vkCmdSetFrontFace(cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
        for (const DrawCommand& d : view.draws) {
            const PrimitiveBuffers& gp = scene.primitive(d.mesh, d.primitive);
            DrawBlock block = d.block;
            block.normalMatrix[3] = f.normalLength;
            vkCmdPushConstants(cmd, layout, stages, 0, sizeof(DrawBlock), &block);
            const VkBuffer buffers[2] = {geometry, geometry};
            const VkDeviceSize offsets[2] = {gp.position, gp.normal}, strides[2] = {12, 12};
            vkCmdBindVertexBuffers2(cmd, LANTERN_LOC_POSITION, 2, buffers, offsets, nullptr, strides);
            vkCmdDraw(cmd, 2, gp.vertexCount, 0, 0);
        }
    }
}

} // namespace lantern::gpu
