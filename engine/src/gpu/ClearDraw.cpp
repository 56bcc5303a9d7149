// Clearing by drawing (gpu/ClearDraw.h): one pipeline per (sample count, colour attachments),
// made on first use.
#include "gpu/ClearDraw.h"

#include "gpu/Pipeline.h"
#include "gpu/Pipelines.h"

#include "ShaderBlobs.h"

#include <utility>

namespace lantern::gpu {

namespace {

// The passes' colour attachment counts, as gpu/Recorder.cpp builds them: the AOV planes join the
// scene pass unless it is multisampled, when they have a single-sampled pass of their own.
std::uint32_t aovAttachments(const Target& t) {
    return t.surface ? LANTERN_OUT_COUNT_AOV : LANTERN_OUT_SURFACE;
}
std::uint32_t sceneAttachments(const Target& t) {
    return t.aov && !t.multisampled() ? aovAttachments(t) : 1;
}

} // namespace

Result<std::unique_ptr<ClearDraw>> ClearDraw::create(Context& ctx, Pipelines& pipelines) {
    std::unique_ptr<ClearDraw> c(new ClearDraw(ctx, pipelines.layout()));
    using shaders::ShaderId;
    for (auto [id, module] : {std::pair{ShaderId::clear_vert, &c->m_vertex},
                              std::pair{ShaderId::clear_frag, &c->m_fragment},
                              std::pair{ShaderId::clear_aov_frag, &c->m_fragmentAov}}) {
        auto m = pipelines.shader(std::uint32_t(id));
        if (!m) return std::move(m).error();
        *module = *m;
    }
    return c;
}

bool ClearDraw::preferred(const Context& ctx, std::uint32_t width, std::uint32_t height,
                          bool firstFrame) {
    return !firstFrame && ctx.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU &&
           std::uint64_t(width) * height >= kMinPixels;
}

bool ClearDraw::ready(const Target& t) const {
    return m_cache.count({t.samples, sceneAttachments(t)}) &&
           (!t.separateAovPass() || m_cache.count({1u, aovAttachments(t)}));
}

Result<VkPipeline> ClearDraw::pipeline(std::uint32_t samples, std::uint32_t colorAttachments) {
    const auto key = std::make_pair(samples, colorAttachments);
    if (auto it = m_cache.find(key); it != m_cache.end()) return it->second.get();
    const bool aov = colorAttachments > 1;
    GraphicsPipelineDesc d;
    d.layout = m_layout;
    d.vertex = m_vertex;
    d.fragment = aov ? m_fragmentAov : m_fragment;
    d.colorFormats = passColorFormats(colorAttachments);  // as the scene pipelines'
    d.depthFormat = kDepthFormat;
    d.depthTest = false;
    d.depthWrite = false;
    d.samples = VkSampleCountFlagBits(samples);
    d.name = aov ? "clear with AOVs" : "clear";
    auto p = createGraphicsPipeline(m_ctx, d);
    if (!p) return std::move(p).error();
    const VkPipeline handle = p->get();
    m_cache.emplace(key, std::move(*p));
    return handle;
}

Result<ClearFrame> ClearDraw::prepare(const Target& t) {
    ClearFrame f;
    auto scene = pipeline(t.samples, sceneAttachments(t));
    if (!scene) return std::move(scene).error();
    f.scene = *scene;
    if (t.separateAovPass()) {
        auto aov = pipeline(1, aovAttachments(t));
        if (!aov) return std::move(aov).error();
        f.aov = *aov;
    }
    return f;
}

void ClearDraw::record(VkCommandBuffer cmd, VkPipelineLayout layout, VkPipeline pipeline,
                       std::uint32_t width, std::uint32_t height, const float clear[4]) {
    const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    // clear.frag reads the colour as the push block's first 16 bytes; the range is pushed for
    // both stages, as the layout declares it.
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       4 * sizeof(float), clear);
    vkCmdDraw(cmd, 3, 1, 0, 0);
}

} // namespace lantern::gpu
