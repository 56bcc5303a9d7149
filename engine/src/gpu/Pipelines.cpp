// The pipeline layout, the shader modules and the variant cache. Set, binding, attribute and
// output numbers come from shaders/include/lantern_shared.h, as the shaders read them.
#include "gpu/Pipelines.h"

#include "gpu/Pipeline.h"
#include "gpu/Targets.h"

#include "ShaderBlobs.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

namespace lantern::gpu {
namespace {

using shaders::ShaderId;
using frame::Program;

// A program's vertex stage (plain, and guarded where the vertex stage lights: it checks what
// it lit, shaders/include/guard.glsl) and its fragment stage (plain, and with the AOV outputs).
// Blended draws under exact transparency store their fragments (_list, with and without the
// AOV outputs); under weighted transparency they add into the weighted sums (_weighted).
struct ProgramShaders {
    ShaderId vertex, vertexGuard, fragment, fragmentAov;
    ShaderId fragmentList, fragmentAovList, fragmentWeighted;
};

// The stage that lights comes as the light loop, unrolled for up to 2 lights and for up to 8
// (LANTERN_UNROLL, shaders/include/lighting.glsl): the entry point with the fewest copies of a
// light's terms that the variant's SC_UNROLLED_LIGHTS fits, as each copy costs its creation.
ShaderId byUnroll(std::uint32_t lights, ShaderId loop, ShaderId two, ShaderId eight) {
    static_assert(LANTERN_MAX_UNROLLED_LIGHTS == 8, "the _u8 entry points unroll 8 lights");
    return lights == 0 ? loop : lights <= 2 ? two : eight;
}

ProgramShaders programShaders(const PipelineKey& key) {
    using S = ShaderId;
    if (key.flatPerTriangle)  // lit (and checked) by the pre-pass
        return {S::flatprim_vert, S::flatprim_vert, S::flatprim_frag, S::flatprim_aov_frag,
                S::flatprim_list_frag, S::flatprim_aov_list_frag, S::flatprim_weighted_frag};
    const std::uint32_t n = key.constants[LANTERN_SC_UNROLLED_LIGHTS];
    switch (key.program) {
    case Program::Phong: break;
    case Program::Gouraud:
        return {byUnroll(n, S::gouraud_vert, S::gouraud_u2_vert, S::gouraud_u8_vert),
                byUnroll(n, S::gouraud_guard_vert, S::gouraud_guard_u2_vert, S::gouraud_guard_u8_vert),
                S::gouraud_frag, S::gouraud_aov_frag, S::gouraud_list_frag,
                S::gouraud_aov_list_frag, S::gouraud_weighted_frag};
    case Program::Flat:
        return {byUnroll(n, S::flat_vert, S::flat_u2_vert, S::flat_u8_vert),
                byUnroll(n, S::flat_guard_vert, S::flat_guard_u2_vert, S::flat_guard_u8_vert),
                S::flat_frag, S::flat_aov_frag, S::flat_list_frag, S::flat_aov_list_frag,
                S::flat_weighted_frag};
    case Program::GlFlat:
        return {byUnroll(n, S::glflat_vert, S::glflat_u2_vert, S::glflat_u8_vert),
                byUnroll(n, S::glflat_guard_vert, S::glflat_guard_u2_vert, S::glflat_guard_u8_vert),
                S::flat_frag, S::flat_aov_frag, S::flat_list_frag, S::flat_aov_list_frag,
                S::flat_weighted_frag};
    case Program::Floor:  // the trivial shader measures rasterising alone: blended or not
        return {S::mesh_vert, S::mesh_vert, S::floor_frag, S::floor_aov_frag,
                S::floor_frag, S::floor_aov_frag, S::floor_frag};
    }
    return {S::mesh_vert, S::mesh_vert, byUnroll(n, S::phong_frag, S::phong_u2_frag, S::phong_u8_frag),
            byUnroll(n, S::phong_aov_frag, S::phong_aov_u2_frag, S::phong_aov_u8_frag),
            byUnroll(n, S::phong_list_frag, S::phong_list_u2_frag, S::phong_list_u8_frag),
            byUnroll(n, S::phong_aov_list_frag, S::phong_aov_list_u2_frag, S::phong_aov_list_u8_frag),
            byUnroll(n, S::phong_weighted_frag, S::phong_weighted_u2_frag, S::phong_weighted_u8_frag)};
}

// One vertex-buffer binding per attribute, numbered as its location (non-interleaved streams).
struct Attribute {
    std::uint32_t location;
    VkFormat format;
    std::uint32_t stride;
};
constexpr Attribute kAttributes[LANTERN_VERTEX_BINDINGS] = {
    {LANTERN_LOC_POSITION, VK_FORMAT_R32G32B32_SFLOAT, 12},
    {LANTERN_LOC_NORMAL, VK_FORMAT_R32G32B32_SFLOAT, 12},
    {LANTERN_LOC_COLOR, VK_FORMAT_R32G32B32A32_SFLOAT, 16},
    {LANTERN_LOC_TEXCOORD, VK_FORMAT_R32G32_SFLOAT, 8},
    {LANTERN_LOC_CENTROID, VK_FORMAT_R32G32B32_SFLOAT, 12},
};

Result<UniqueDescriptorSetLayout> makeSetLayout(Context& ctx,
                                                const std::vector<VkDescriptorSetLayoutBinding>& b) {
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = std::uint32_t(b.size());
    lci.pBindings = b.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorSetLayout(ctx.device(), &lci, nullptr, &layout));
    return UniqueDescriptorSetLayout(ctx.device(), layout);
}

// What a frame's first use of its variants cost (`--verbose` prints it).
void logCompiled(const Context& ctx, std::size_t count, std::size_t threads,
                 std::chrono::steady_clock::time_point start) {
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    char text[128];
    std::snprintf(text, sizeof text, "pipeline variants compiled: %zu in %.1f ms on %zu thread%s",
                  count, ms, threads, threads == 1 ? "" : "s");
    ctx.log(LogLevel::Info, text);
}

} // namespace

std::size_t PipelineKeyHash::operator()(const PipelineKey& k) const noexcept {
    std::size_t h = std::size_t(k.program) * 1000003u + std::size_t(k.topology);
    for (std::uint32_t c : k.constants) h = h * 31u + c;
    h = h * 31u + (k.blend ? 1u : 0u);
    h = h * 31u + (k.aov ? 1u : 0u);
    h = h * 31u + (k.aovSurface ? 1u : 0u);
    h = h * 31u + k.samples;
    h = h * 31u + (k.reversedZ ? 1u : 0u);
    h = h * 31u + (k.flatPerTriangle ? 1u : 0u);
    h = h * 31u + (k.guard ? 1u : 0u);
    h = h * 31u + std::size_t(k.blendPath);
    h = h * 31u + (k.weightedPass ? 1u : 0u);
    return h;
}

Result<Pipelines> Pipelines::create(Context& ctx) {
    Pipelines p;
    p.m_ctx = &ctx;
    const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    // The flat-lighting pre-pass (gpu/FlatLight.cpp) binds the same frame set for compute: it
    // reads the view, lights and materials and writes the per-triangle records.
    const VkShaderStageFlags all = both | VK_SHADER_STAGE_COMPUTE_BIT;
    const VkShaderStageFlags records = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
    auto frameLayout = makeSetLayout(
        ctx, {{LANTERN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, all, nullptr},
              {LANTERN_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 1, all, nullptr},
              {LANTERN_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
              {LANTERN_BINDING_FLAT_COLORS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, records, nullptr},
              {LANTERN_BINDING_FLAT_NORMALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, records, nullptr},
              {LANTERN_BINDING_GUARD, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
              {LANTERN_BINDING_LIGHTS_UNIFORM, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, all,
               nullptr},
              {LANTERN_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
               VK_SHADER_STAGE_VERTEX_BIT, nullptr},
              {LANTERN_BINDING_SHADOW_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
              {LANTERN_BINDING_SHADOW_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
              {LANTERN_BINDING_SHADOWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
              {LANTERN_BINDING_FRAGMENT_LISTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
               VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
              {LANTERN_BINDING_WEIGHTED_ACCUM, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1,
               VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
              {LANTERN_BINDING_WEIGHTED_REVEAL, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1,
               VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}});
    if (!frameLayout) return std::move(frameLayout).error();
    p.m_frameLayout = std::move(*frameLayout);
    std::vector<VkDescriptorSetLayoutBinding> textureBindings;
    for (std::uint32_t b = 0; b < LANTERN_TEXTURE_BINDINGS; ++b)
        textureBindings.push_back({b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                   VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    auto textureLayout = makeSetLayout(ctx, textureBindings);
    if (!textureLayout) return std::move(textureLayout).error();
    p.m_textureLayout = std::move(*textureLayout);
    // Per-triangle flat shading: its pre-pass and its draws' vertex stage (flat.vert) read the
    // same jobs and corners (shaders/include/flatjob.glsl).
    const VkShaderStageFlags pulled = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
    auto flatLayout = makeSetLayout(
        ctx, {{LANTERN_BINDING_FLAT_GEOMETRY, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, pulled, nullptr},
              {LANTERN_BINDING_FLAT_DEFORMED, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, pulled, nullptr},
              {LANTERN_BINDING_FLAT_JOBS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, pulled, nullptr},
              {LANTERN_BINDING_FLAT_INDICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
               VK_SHADER_STAGE_COMPUTE_BIT, nullptr}});
    if (!flatLayout) return std::move(flatLayout).error();
    p.m_flatLayout = std::move(*flatLayout);

    VkDescriptorSetLayout setLayouts[3] = {};
    setLayouts[LANTERN_SET_FRAME] = p.m_frameLayout.get();
    setLayouts[LANTERN_SET_TEXTURE] = p.m_textureLayout.get();
    setLayouts[LANTERN_SET_FLAT] = p.m_flatLayout.get();
    VkPushConstantRange push{both, 0, sizeof(DrawBlock)};
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = 3;
    plci.pSetLayouts = setLayouts;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &push;
    VkPipelineLayout pl = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreatePipelineLayout(ctx.device(), &plci, nullptr, &pl));
    p.m_layout = UniquePipelineLayout(ctx.device(), pl);
    return p;
}

Result<VkShaderModule> Pipelines::shader(std::uint32_t id) {
    if (auto it = m_shaders.find(id); it != m_shaders.end()) return it->second.get();
    const shaders::ShaderBlob blob = shaders::shaderBlob(ShaderId(id));
    auto module = createShaderModule(*m_ctx, {blob.words, blob.wordCount}, std::string(blob.name));
    if (!module) return std::move(module).error();
    const VkShaderModule handle = module->get();
    m_shaders.emplace(id, std::move(*module));
    return handle;
}

// What a variant is made of; its shader modules are made here, on the calling thread.
Result<GraphicsPipelineDesc> Pipelines::describe(const PipelineKey& key) {
    const ProgramShaders ps = programShaders(key);
    auto vs = shader(std::uint32_t(key.guard ? ps.vertexGuard : ps.vertex));
    if (!vs) return std::move(vs).error();
    const bool list = key.blend && key.blendPath == BlendPath::List;
    const bool weighted = key.blend && key.blendPath == BlendPath::Weighted;
    ShaderId fragment = key.aov ? ps.fragmentAov : ps.fragment;
    if (list) fragment = key.aov ? ps.fragmentAovList : ps.fragmentList;
    if (key.weightedPass) fragment = ps.fragmentWeighted;
    auto fs = shader(std::uint32_t(fragment));
    if (!fs) return std::move(fs).error();

    GraphicsPipelineDesc d;
    d.layout = m_layout.get();
    d.vertex = *vs;
    d.fragment = *fs;
    for (std::uint32_t i = 0; i < LANTERN_SC_COUNT; ++i) {
        d.specEntries.push_back({i, i * 4u, 4u});
        d.specData.push_back(key.constants[i]);
    }
    // Only flat shading reads the centroid stream; lit per triangle, it has no vertex buffers
    // (flat.vert pulls its corners from storage buffers).
    const std::uint32_t attributes = key.flatPerTriangle               ? 0
                                     : key.program == Program::Flat ? LANTERN_VERTEX_BINDINGS
                                                                    : LANTERN_LOC_CENTROID;
    for (std::uint32_t a = 0; a < attributes; ++a) {
        const Attribute& at = kAttributes[a];
        d.bindings.push_back({at.location, at.stride, VK_VERTEX_INPUT_RATE_VERTEX});
        d.attributes.push_back({at.location, at.location, at.format, 0});
    }
    // mesh.vert (phong and floor) reads the tangents too; every vertex stage with streams
    // the second texture-coordinate set.
    if (!key.flatPerTriangle && (key.program == Program::Phong || key.program == Program::Floor)) {
        d.bindings.push_back({LANTERN_LOC_TANGENT, 16, VK_VERTEX_INPUT_RATE_VERTEX});
        d.attributes.push_back(
            {LANTERN_LOC_TANGENT, LANTERN_LOC_TANGENT, VK_FORMAT_R32G32B32A32_SFLOAT, 0});
    }
    if (!key.flatPerTriangle) {
        d.bindings.push_back({LANTERN_LOC_TEXCOORD1, 8, VK_VERTEX_INPUT_RATE_VERTEX});
        d.attributes.push_back(
            {LANTERN_LOC_TEXCOORD1, LANTERN_LOC_TEXCOORD1, VK_FORMAT_R32G32_SFLOAT, 0});
    }
    // Without the surface plane the pipeline has no attachment at its location, and the
    // shader's writes there are discarded (a null attachment would need its format undefined,
    // which the validation layer reports against the shader's output type).
    d.colorFormats = passColorFormats(
        key.aov ? (key.aovSurface ? LANTERN_OUT_COUNT_AOV : LANTERN_OUT_SURFACE) : 1);
    if (key.weightedPass) d.colorFormats = {kWeightedAccumFormat, kWeightedRevealFormat};
    d.depthFormat = kDepthFormat;
    d.samples = VkSampleCountFlagBits(key.samples);
    // Blended over the colour (sorted), or not written there: stored in the fragment lists
    // (exact), or, in the scene pass, only the AOVs of a weighted draw, whose colour its own
    // pass adds into the weighted sums.
    d.blend = key.blend && key.blendPath == BlendPath::Over;
    d.colorWrite = !(list || weighted) || key.weightedPass;
    d.weightedSums = key.weightedPass;
    d.depthWrite = !key.blend;
    // GL's default depth test is strict: the first of two equal depths wins.
    d.depthCompare = key.reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
    d.provokingLast = key.program == Program::GlFlat;
    d.topology = key.topology == Topology::Lines    ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST
                 : key.topology == Topology::Points ? VK_PRIMITIVE_TOPOLOGY_POINT_LIST
                                                    : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    d.name = std::string(frame::toString(key.program)) +
             (key.flatPerTriangle ? " per-triangle" : "") + (key.guard ? " guarded" : "") +
             (list ? " fragment-list" : "") + (key.weightedPass ? " weighted" : "") + " variant";
    return d;
}

Result<VkPipeline> Pipelines::pipeline(const PipelineKey& key) {
    if (auto it = m_pipelines.find(key); it != m_pipelines.end()) return it->second.get();
    auto d = describe(key);
    if (!d) return std::move(d).error();
    auto p = createGraphicsPipeline(*m_ctx, *d);
    if (!p) return std::move(p).error();
    const VkPipeline handle = p->get();
    m_pipelines.emplace(key, std::move(*p));
    m_ctx->log(LogLevel::Debug, "pipeline variant created: " + d->name);
    return handle;
}

Result<void> Pipelines::prepare(const std::vector<PipelineKey>& keys) {
    std::vector<PipelineKey> missing;
    for (const PipelineKey& k : keys)
        if (!m_pipelines.count(k) && std::find(missing.begin(), missing.end(), k) == missing.end())
            missing.push_back(k);
    if (missing.empty()) return {};
    const auto start = std::chrono::steady_clock::now();
    if (missing.size() == 1) {
        auto p = pipeline(missing[0]);
        if (!p) return std::move(p).error();
        logCompiled(*m_ctx, 1, 1, start);
        return {};
    }
    std::vector<GraphicsPipelineDesc> descs;
    for (const PipelineKey& k : missing) {
        auto d = describe(k);
        if (!d) return std::move(d).error();
        descs.push_back(std::move(*d));
    }
    // The driver compiles each variant on its own thread, at most one per core. The pipeline
    // cache needs no lock of ours: Vulkan synchronises it internally unless it was created
    // with VK_PIPELINE_CACHE_CREATE_EXTERNALLY_SYNCHRONIZED_BIT (Lantern's is not).
    std::vector<std::optional<Result<UniquePipeline>>> made(descs.size());
    std::atomic<std::size_t> next{0};
    const std::size_t threads =
        std::min<std::size_t>(descs.size(), std::max(1u, std::thread::hardware_concurrency()));
    {
        std::vector<std::jthread> workers;
        for (std::size_t t = 0; t < threads; ++t)
            workers.emplace_back([&] {
                for (std::size_t i = next++; i < descs.size(); i = next++)
                    made[i].emplace(createGraphicsPipeline(*m_ctx, descs[i]));
            });
    }
    for (std::size_t i = 0; i < descs.size(); ++i) {
        if (!*made[i]) return std::move(*made[i]).error();
        m_pipelines.emplace(missing[i], std::move(**made[i]));
        m_ctx->log(LogLevel::Debug, "pipeline variant created: " + descs[i].name);
    }
    logCompiled(*m_ctx, descs.size(), threads, start);
    return {};
}

Result<Pipelines::ComputePass> Pipelines::computePass(std::uint32_t shaderId, std::uint32_t storageBuffers,
                                                     std::uint32_t pushBytes, const char* name) {
    const VkDevice dev = m_ctx->device();
    ComputePass pass;
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (std::uint32_t b = 0; b < storageBuffers; ++b)
        bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = storageBuffers;
    lci.pBindings = bindings.data();
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &setLayout));
    pass.setLayout = UniqueDescriptorSetLayout(dev, setLayout);
    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &setLayout;
    plci.pushConstantRangeCount = pushBytes > 0 ? 1u : 0u;
    plci.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreatePipelineLayout(dev, &plci, nullptr, &layout));
    pass.layout = UniquePipelineLayout(dev, layout);
    auto module = shader(shaderId);
    if (!module) return std::move(module).error();
    VkComputePipelineCreateInfo cpci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cpci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    cpci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cpci.stage.module = *module;
    cpci.stage.pName = "main";
    cpci.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateComputePipelines(dev, m_ctx->pipelineCache(), 1, &cpci, nullptr, &pipeline));
    pass.pipeline = UniquePipeline(dev, pipeline);
    m_ctx->setName(VK_OBJECT_TYPE_PIPELINE, pipeline, name);
    return pass;
}

} // namespace lantern::gpu
