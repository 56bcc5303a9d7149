// Uploads a scene's geometry (one buffer, non-interleaved streams), builds flat-shading
// streams on demand, and uploads textures with a mip chain.
#include "gpu/SceneBuffers.h"

#include "lantern_shared.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace lantern::gpu {
namespace {

VkDeviceSize align16(VkDeviceSize v) { return (v + 15) & ~VkDeviceSize(15); }

// Where the bytes of a new device buffer are written: straight into it when it is host-visible,
// else into a staging buffer copied over afterwards.
struct Filler {
    Buffer staging;
    char* dst = nullptr;
};

Result<Filler> beginFill(Context& ctx, Buffer& target) {
    Filler f;
    if (target.mapped) {
        f.dst = static_cast<char*>(target.mapped);
        return f;
    }
    auto staging = createBuffer(ctx, target.size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                     MemoryUsage::Upload, "geometry staging");
    if (!staging) return std::move(staging).error();
    f.staging = std::move(*staging);
    f.dst = static_cast<char*>(f.staging.mapped);
    return f;
}

Result<void> endFill(Context& ctx, Buffer& target, Filler& f,
                     VkPipelineStageFlags2 dstStage = VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT,
                     VkAccessFlags2 dstAccess = VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT |
                                                VK_ACCESS_2_INDEX_READ_BIT) {
    if (!f.staging.buffer) return flush(ctx, target);
    LANTERN_TRY(flush(ctx, f.staging));
    return ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, target.size};
        vkCmdCopyBuffer(cmd, f.staging.get(), target.get(), 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      dstStage, dstAccess);
    });
}

template <typename T>
void put(char* dst, VkDeviceSize offset, const std::vector<T>& v) {
    if (!v.empty()) std::memcpy(dst + offset, v.data(), v.size() * sizeof(T));
}

Error tooLarge(const char* what) {
    return makeError(ErrorCode::OutOfMemory, std::string(what) + " exceeds the addressable size");
}

// Linear blits build the mip chain when the format supports them.
bool canBlitMips(const Context& c) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(c.physicalDevice(), VK_FORMAT_R8G8B8A8_SRGB, &fp);
    const VkFormatFeatureFlags blitNeeds = VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                           VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                           VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    return (fp.optimalTilingFeatures & blitNeeds) == blitNeeds;
}

struct TextureSource {
    int width, height;
    const std::uint8_t* pixels;
};

// A white 1x1 texture (for materials without one), then the scene's textures.
std::vector<TextureSource> textureSources(const Scene& s) {
    static const std::uint8_t kWhite[4] = {255, 255, 255, 255};
    std::vector<TextureSource> sources{{1, 1, kWhite}};
    for (const Texture& t : s.textures)
        sources.push_back({t.width, t.height, t.rgba8.data()});
    return sources;
}

// Every source's pixels in one host-visible buffer, one after the other.
struct TextureStaging {
    Buffer buffer;
    std::vector<VkDeviceSize> offsets; ///< per source
};

Result<TextureStaging> stageTextures(Context& c, const std::vector<TextureSource>& sources) {
    VkDeviceSize stagingSize = 0;
    for (const TextureSource& src : sources)
        stagingSize += VkDeviceSize(src.width) * src.height * 4;
    auto staging = createBuffer(c, stagingSize, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                MemoryUsage::Upload, "texture staging");
    if (!staging) return std::move(staging).error();
    TextureStaging out{std::move(*staging), {}};
    VkDeviceSize offset = 0;
    for (const TextureSource& src : sources) {
        out.offsets.push_back(offset);
        const VkDeviceSize bytes = VkDeviceSize(src.width) * src.height * 4;
        std::memcpy(static_cast<char*>(out.buffer.mapped) + offset, src.pixels, bytes);
        offset += bytes;
    }
    LANTERN_TRY(flush(c, out.buffer));
    return out;
}

// Source `i`'s image (0 is the white texture), with a full mip chain when `canMip`.
Result<Image> createTextureImage(Context& c, const TextureSource& src, std::size_t i, bool canMip) {
    ImageDesc d;
    d.format = VK_FORMAT_R8G8B8A8_SRGB;
    d.width = std::uint32_t(src.width);
    d.height = std::uint32_t(src.height);
    d.mipLevels =
        canMip ? std::uint32_t(std::floor(std::log2(std::max(d.width, d.height)))) + 1 : 1;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
              VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.name = i == 0 ? "white texture" : "texture " + std::to_string(i - 1);
    return createImage(c, d);
}

// Level 0 copied from the staging buffer at `offset`, each further level blitted from the one
// before; every level ends shader-readable.
void recordTextureUpload(VkCommandBuffer cmd, const Image& img, VkBuffer staging,
                         VkDeviceSize offset) {
    const std::uint32_t mips = img.desc.mipLevels;
    imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                 VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.bufferOffset = offset;
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {img.desc.width, img.desc.height, 1};
    vkCmdCopyBufferToImage(cmd, staging, img.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
    std::int32_t w = std::int32_t(img.desc.width), h = std::int32_t(img.desc.height);
    for (std::uint32_t m = 1; m < mips; ++m) {
        imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, m - 1, 1);
        const std::int32_t nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
        blit.srcOffsets[1] = {w, h, 1};
        blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
        blit.dstOffsets[1] = {nw, nh, 1};
        vkCmdBlitImage(cmd, img.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img.get(),
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                     m - 1, 1);
        w = nw;
        h = nh;
    }
    imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, mips - 1, 1);
}

} // namespace

SceneBuffers::~SceneBuffers() {
    // Descriptor sets go with their pool; images, buffers and samplers with their owners. The
    // device stays alive through m_ctx until this object is gone.
}

Result<std::shared_ptr<SceneBuffers>> SceneBuffers::create(std::shared_ptr<Context> ctx,
                                                   std::shared_ptr<const Scene> scene,
                                                   VkDescriptorSetLayout textureLayout) {
    std::shared_ptr<SceneBuffers> g(new SceneBuffers());
    g->m_ctx = std::move(ctx);
    g->m_scene = std::move(scene);
    const Scene& s = *g->m_scene;

    // Layout: defaults first (a white colour and a zero texcoord for stride-0 bindings).
    VkDeviceSize size = 32;
    g->m_defaultColor = 0;
    g->m_defaultTexcoord = 16;
    for (const Mesh& mesh : s.meshes) {
        g->m_meshFirst.push_back(g->m_primitives.size());
        for (const Primitive& p : mesh.primitives) {
            PrimitiveBuffers gp;
            const VkDeviceSize n = p.positions.size();
            if (n > std::numeric_limits<std::uint32_t>::max() ||
                p.indices.size() > std::numeric_limits<std::uint32_t>::max())
                return tooLarge("a primitive");
            gp.vertexCount = std::uint32_t(n);
            gp.indexCount = std::uint32_t(p.indices.size());
            gp.position = size;
            size = align16(size + n * 12);
            gp.normal = size;
            size = align16(size + n * 12);
            if (!p.colors.empty()) {
                gp.color = size;
                size = align16(size + n * 16);
            }
            if (!p.texcoords.empty()) {
                gp.texcoord = size;
                size = align16(size + n * 8);
            }
            if (!p.indices.empty()) {
                gp.index = size;
                size = align16(size + p.indices.size() * 4);
            }
            g->m_primitives.push_back(gp);
        }
    }
    Context& c = *g->m_ctx;
    auto buffer = createBuffer(c, size,
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    MemoryUsage::DeviceLocal, "scene geometry");
    if (!buffer) return std::move(buffer).error();
    g->m_geometry = std::move(*buffer);
    auto fill = beginFill(c, g->m_geometry);
    if (!fill) return std::move(fill).error();
    char* dst = fill->dst;
    const float white[4] = {1, 1, 1, 1}, zero[2] = {0, 0};
    std::memcpy(dst + g->m_defaultColor, white, sizeof white);
    std::memcpy(dst + g->m_defaultTexcoord, zero, sizeof zero);
    std::size_t k = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            const PrimitiveBuffers& gp = g->m_primitives[k++];
            put(dst, gp.position, p.positions);
            put(dst, gp.normal, p.normals);
            if (gp.color != kNoStream) put(dst, gp.color, p.colors);
            if (gp.texcoord != kNoStream) put(dst, gp.texcoord, p.texcoords);
            if (gp.index != kNoStream) put(dst, gp.index, p.indices);
        }
    LANTERN_TRY(endFill(c, g->m_geometry, *fill));
    LANTERN_TRY(g->uploadDeformInputs());
    LANTERN_TRY(g->uploadTextures(textureLayout));
    return g;
}

Result<void> SceneBuffers::ensureFlatStreams() {
    std::lock_guard lock(m_flatMutex);
    if (m_flatReady) return {};
    const Scene& s = *m_scene;
    VkDeviceSize size = 16;
    std::size_t k = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            PrimitiveBuffers& gp = m_primitives[k++];
            const VkDeviceSize n = VkDeviceSize(p.triangleCount()) * 3;
            if (n > std::numeric_limits<std::uint32_t>::max()) return tooLarge("a primitive");
            gp.flatVertexCount = std::uint32_t(n);
            gp.flatPosition = size;
            size = align16(size + n * 12);
            gp.flatNormal = size;
            size = align16(size + n * 12);
            gp.flatCentroid = size;
            size = align16(size + n * 12);
            if (!p.colors.empty()) {
                gp.flatColor = size;
                size = align16(size + n * 16);
            }
            if (!p.texcoords.empty()) {
                gp.flatTexcoord = size;
                size = align16(size + n * 8);
            }
        }
    auto buffer = createBuffer(*m_ctx, size,
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    MemoryUsage::DeviceLocal, "flat geometry");
    if (!buffer) return std::move(buffer).error();
    m_flatGeometry = std::move(*buffer);
    auto fill = beginFill(*m_ctx, m_flatGeometry);
    if (!fill) return std::move(fill).error();
    char* dst = fill->dst;
    k = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            const PrimitiveBuffers& gp = m_primitives[k++];
            auto* pos = reinterpret_cast<glm::vec3*>(dst + gp.flatPosition);
            auto* nrm = reinterpret_cast<glm::vec3*>(dst + gp.flatNormal);
            auto* cen = reinterpret_cast<glm::vec3*>(dst + gp.flatCentroid);
            auto* col = gp.flatColor != kNoStream ? reinterpret_cast<glm::vec4*>(dst + gp.flatColor) : nullptr;
            auto* tex = gp.flatTexcoord != kNoStream ? reinterpret_cast<glm::vec2*>(dst + gp.flatTexcoord) : nullptr;
            const std::size_t triangles = p.triangleCount();
            for (std::size_t t = 0; t < triangles; ++t) {
                std::uint32_t v[3];
                for (int c = 0; c < 3; ++c)
                    v[c] = p.indices.empty() ? std::uint32_t(t * 3 + c) : p.indices[t * 3 + c];
                const glm::dvec3 a(p.positions[v[0]]), b(p.positions[v[1]]), cpos(p.positions[v[2]]);
                // The face normal in object space (the normal matrix carries it to eye space);
                // a degenerate triangle gets zero (ambient and emission only, covers no pixel).
                const glm::dvec3 cross = glm::cross(b - a, cpos - a);
                const double len = glm::length(cross);
                const glm::vec3 face = (len > 0.0 && std::isfinite(len)) ? glm::vec3(cross / len) : glm::vec3(0.0f);
                const glm::vec3 centroid((a + b + cpos) / 3.0);
                glm::vec4 avg(0.0f);
                if (col)
                    avg = glm::vec4((glm::dvec4(p.colors[v[0]]) + glm::dvec4(p.colors[v[1]]) +
                                     glm::dvec4(p.colors[v[2]])) / 3.0);
                for (int c = 0; c < 3; ++c) {
                    const std::size_t o = t * 3 + std::size_t(c);
                    pos[o] = p.positions[v[c]];
                    nrm[o] = face;
                    cen[o] = centroid;
                    if (col) col[o] = avg;
                    if (tex) tex[o] = p.texcoords[v[c]];
                }
            }
        }
    LANTERN_TRY(endFill(*m_ctx, m_flatGeometry, *fill));
    m_flatReady = true;
    return {};
}

// Primitives with joints or morph targets: base positions and normals, joints and weights
// (4 or 8 per vertex), per target position then normal displacements (zeros where a target
// has none), the triangle list; all as 32-bit words. A scene that cannot deform has none.
Result<void> SceneBuffers::uploadDeformInputs() {
    const Scene& s = *m_scene;
    std::uint64_t words = 0;
    std::size_t k = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            PrimitiveBuffers& gp = m_primitives[k++];
            if (p.joints0.empty() && p.targets.empty()) continue;
            const std::uint64_t n = p.positions.size();
            gp.deformable = true;
            gp.influences = p.joints0.empty() ? 0 : p.joints1.empty() ? 4 : 8;
            gp.targetCount = std::uint32_t(p.targets.size());
            gp.deformPosition = std::uint32_t(words);
            words += 3 * n;
            gp.deformNormal = std::uint32_t(words);
            words += 3 * n;
            gp.deformJoints = std::uint32_t(words);
            words += gp.influences * n;
            gp.deformWeights = std::uint32_t(words);
            words += gp.influences * n;
            gp.deformTargets = std::uint32_t(words);
            words += 6 * n * p.targets.size();
            if (!p.indices.empty()) {
                gp.deformIndices = std::uint32_t(words);
                words += p.indices.size();
            }
            if (words >= LANTERN_DEFORM_NONE) return tooLarge("the skinning and morph-target data");
        }
    if (words == 0) return {};
    auto buffer = createBuffer(*m_ctx, words * 4,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               MemoryUsage::DeviceLocal, "deformation inputs");
    if (!buffer) return std::move(buffer).error();
    m_deformInput = std::move(*buffer);
    auto fill = beginFill(*m_ctx, m_deformInput);
    if (!fill) return std::move(fill).error();
    auto* dst = reinterpret_cast<std::uint32_t*>(fill->dst);
    auto putFloat = [&](std::uint64_t at, float f) { std::memcpy(dst + at, &f, 4); };
    auto put3 = [&](std::uint64_t at, const std::vector<glm::vec3>& v) {
        if (!v.empty()) std::memcpy(dst + at, v.data(), v.size() * 12);
    };
    k = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            const PrimitiveBuffers& gp = m_primitives[k++];
            if (!gp.deformable) continue;
            const std::size_t n = p.positions.size();
            put3(gp.deformPosition, p.positions);
            put3(gp.deformNormal, p.normals);
            for (std::size_t v = 0; v < n && gp.influences > 0; ++v)
                for (std::uint32_t i = 0; i < gp.influences; ++i) {
                    const glm::uvec4& j = i < 4 ? p.joints0[v] : p.joints1[v];
                    const glm::vec4& w = i < 4 ? p.weights0[v] : p.weights1[v];
                    dst[gp.deformJoints + v * gp.influences + i] = j[int(i % 4)];
                    putFloat(gp.deformWeights + v * gp.influences + i, w[int(i % 4)]);
                }
            for (std::size_t t = 0; t < p.targets.size(); ++t) {
                const std::uint64_t base = gp.deformTargets + t * 6 * n;
                std::memset(dst + base, 0, 6 * n * 4);
                put3(base, p.targets[t].positions);
                put3(base + 3 * n, p.targets[t].normals);
            }
            if (!p.indices.empty())
                std::memcpy(dst + gp.deformIndices, p.indices.data(), p.indices.size() * 4);
        }
    return endFill(*m_ctx, m_deformInput, *fill, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

Result<void> SceneBuffers::uploadTextures(VkDescriptorSetLayout layout) {
    LANTERN_TRY(uploadTextureImages());
    LANTERN_TRY(createSamplers());
    return createTextureSets(layout);
}

Result<void> SceneBuffers::uploadTextureImages() {
    Context& c = *m_ctx;
    const bool canMip = canBlitMips(c);
    const std::vector<TextureSource> sources = textureSources(*m_scene);
    auto staging = stageTextures(c, sources);
    if (!staging) return std::move(staging).error();
    for (std::size_t i = 0; i < sources.size(); ++i) {
        auto img = createTextureImage(c, sources[i], i, canMip);
        if (!img) return std::move(img).error();
        m_textures.push_back(std::move(*img));
    }
    return c.submitAndWait([&](VkCommandBuffer cmd) {
        for (std::size_t i = 0; i < m_textures.size(); ++i)
            recordTextureUpload(cmd, m_textures[i], staging->buffer.get(), staging->offsets[i]);
    });
}

namespace {

VkSamplerAddressMode addressMode(TextureWrap w) {
    return w == TextureWrap::ClampToEdge      ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
           : w == TextureWrap::MirroredRepeat ? VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT
                                              : VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

// The sampler a texture asks for: nearest * 9 + wrapS * 3 + wrapT (18 in all).
int samplerIndexOf(bool nearest, TextureWrap s, TextureWrap t) {
    return (nearest ? 9 : 0) + int(s) * 3 + int(t);
}

} // namespace

Result<void> SceneBuffers::createSamplers() {
    Context& c = *m_ctx;
    for (int i = 0; i < 18; ++i) {
        VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        const bool nearest = i >= 9;
        sci.magFilter = nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
        sci.minFilter = sci.magFilter;
        sci.mipmapMode = nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR;
        sci.addressModeU = addressMode(TextureWrap((i % 9) / 3));
        sci.addressModeV = addressMode(TextureWrap(i % 3));
        sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
        sci.maxLod = VK_LOD_CLAMP_NONE;
        VkSampler sampler = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateSampler(c.device(), &sci, nullptr, &sampler));
        m_samplers.emplace_back(c.device(), sampler);
    }
    return {};
}

// One descriptor set per texture, with the sampler its texture asks for.
Result<void> SceneBuffers::createTextureSets(VkDescriptorSetLayout layout) {
    Context& c = *m_ctx;
    const Scene& s = *m_scene;
    VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                  std::uint32_t(m_textures.size())};
    VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpci.maxSets = std::uint32_t(m_textures.size());
    dpci.poolSizeCount = 1;
    dpci.pPoolSizes = &poolSize;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorPool(c.device(), &dpci, nullptr, &pool));
    m_pool = UniqueDescriptorPool(c.device(), pool);
    std::vector<VkDescriptorSetLayout> layouts(m_textures.size(), layout);
    m_textureSets.resize(m_textures.size());
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = std::uint32_t(layouts.size());
    ai.pSetLayouts = layouts.data();
    LANTERN_VK_TRY(vkAllocateDescriptorSets(c.device(), &ai, m_textureSets.data()));
    for (std::size_t i = 0; i < m_textures.size(); ++i) {
        int samplerIndex = 0;
        if (i > 0) {
            const Texture& t = s.textures[i - 1];
            samplerIndex = samplerIndexOf(t.nearest, t.wrapS, t.wrapT);
        }
        VkDescriptorImageInfo info{m_samplers[samplerIndex].get(), m_textures[i].view.get(),
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = m_textureSets[i];
        w.dstBinding = LANTERN_BINDING_BASE_COLOR;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        w.pImageInfo = &info;
        vkUpdateDescriptorSets(c.device(), 1, &w, 0, nullptr);
    }
    return {};
}

} // namespace lantern::gpu
