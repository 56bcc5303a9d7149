// A scene's textures on the GPU: each uploaded with its whole mip chain (made on the host,
// gpu/TextureMips.h), the samplers their glTF samplers ask for, one descriptor set per material.
#include "gpu/SceneBuffers.h"
#include "gpu/TextureMips.h"

#include "lantern_shared.h"

#include <algorithm>
#include <cstring>

namespace lantern::gpu {
namespace {

struct TextureSource {
    int width, height;
    const std::uint8_t* pixels;
    VkFormat format;  ///< sRGB colour or linear data
};

// A white 1x1 texture (for materials without one), then the scene's textures.
std::vector<TextureSource> textureSources(const Scene& s) {
    static const std::uint8_t kWhite[4] = {255, 255, 255, 255};
    std::vector<TextureSource> sources{{1, 1, kWhite, VK_FORMAT_R8G8B8A8_SRGB}};
    for (const Texture& t : s.textures)
        sources.push_back({t.width, t.height, t.rgba8.data(),
                           t.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM});
    return sources;
}

// Every source's mip chain in one host-visible buffer, level after level, source after source.
struct TextureStaging {
    Buffer buffer;
    std::vector<VkDeviceSize> offsets; ///< per source, its level 0; the levels follow packed
};

VkDeviceSize chainBytes(const TextureSource& src) {
    VkDeviceSize bytes = 0;
    for (std::uint32_t m = 0; m < mipLevelCount(src.width, src.height); ++m)
        bytes += VkDeviceSize(mipExtent(src.width, m)) * VkDeviceSize(mipExtent(src.height, m)) * 4;
    return bytes;
}

// Level 0 copied from the source, each further level made from the one before it on the host
// (a copy of it kept in `previous`, so the mapped buffer is only written).
void writeChain(const TextureSource& src, char* to) {
    const bool srgb = src.format == VK_FORMAT_R8G8B8A8_SRGB;
    std::size_t bytes = std::size_t(src.width) * std::size_t(src.height) * 4;
    std::memcpy(to, src.pixels, bytes);
    to += bytes;
    std::vector<std::uint8_t> previous, level;
    const std::uint8_t* from = src.pixels;
    int w = src.width, h = src.height;
    for (std::uint32_t m = 1; m < mipLevelCount(src.width, src.height); ++m) {
        const int nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
        level.resize(std::size_t(nw) * std::size_t(nh) * 4);
        downsampleRgba8(from, w, h, level.data(), nw, nh, srgb);
        std::memcpy(to, level.data(), level.size());
        to += level.size();
        previous.swap(level);
        from = previous.data();
        w = nw;
        h = nh;
    }
}

Result<TextureStaging> stageTextures(Context& c, const std::vector<TextureSource>& sources) {
    VkDeviceSize stagingSize = 0;
    for (const TextureSource& src : sources) stagingSize += chainBytes(src);
    auto staging = createBuffer(c, stagingSize, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                MemoryUsage::Upload, "texture staging");
    if (!staging) return std::move(staging).error();
    TextureStaging out{std::move(*staging), {}};
    VkDeviceSize offset = 0;
    for (const TextureSource& src : sources) {
        out.offsets.push_back(offset);
        writeChain(src, static_cast<char*>(out.buffer.mapped) + offset);
        offset += chainBytes(src);
    }
    LANTERN_TRY(flush(c, out.buffer));
    return out;
}

// Source `i`'s image (0 is the white texture), with room for its whole mip chain.
Result<Image> createTextureImage(Context& c, const TextureSource& src, std::size_t i) {
    ImageDesc d;
    d.format = src.format;
    d.width = std::uint32_t(src.width);
    d.height = std::uint32_t(src.height);
    d.mipLevels = mipLevelCount(src.width, src.height);
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.name = i == 0 ? "white texture" : "texture " + std::to_string(i - 1);
    return createImage(c, d);
}

// Every level copied from the staging buffer at `offset` (packed, level 0 first), then made
// shader-readable.
void recordTextureUpload(VkCommandBuffer cmd, const Image& img, VkBuffer staging,
                         VkDeviceSize offset) {
    const std::uint32_t mips = img.desc.mipLevels;
    imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                 VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, 0, mips);
    std::vector<VkBufferImageCopy> regions(mips);
    for (std::uint32_t m = 0; m < mips; ++m) {
        const int w = mipExtent(int(img.desc.width), m), h = mipExtent(int(img.desc.height), m);
        VkBufferImageCopy& region = regions[m];
        region.bufferOffset = offset;
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
        region.imageExtent = {std::uint32_t(w), std::uint32_t(h), 1};
        offset += VkDeviceSize(w) * VkDeviceSize(h) * 4;
    }
    vkCmdCopyBufferToImage(cmd, staging, img.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, mips,
                           regions.data());
    imageBarrier(cmd, img.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 0, mips);
}

} // namespace

Result<void> SceneBuffers::uploadTextures(VkDescriptorSetLayout layout) {
    LANTERN_TRY(uploadTextureImages());
    LANTERN_TRY(createSamplers());
    return createTextureSets(layout);
}

Result<void> SceneBuffers::uploadTextureImages() {
    Context& c = *m_ctx;
    const std::vector<TextureSource> sources = textureSources(*m_scene);
    auto staging = stageTextures(c, sources);
    if (!staging) return std::move(staging).error();
    for (std::size_t i = 0; i < sources.size(); ++i) {
        auto img = createTextureImage(c, sources[i], i);
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

// One descriptor set per material (its base colour and maps; white where it has none), and
// one all white (set 0) for draws without textures; each texture with the sampler it asks for.
Result<void> SceneBuffers::createTextureSets(VkDescriptorSetLayout layout) {
    Context& c = *m_ctx;
    const Scene& s = *m_scene;
    const std::size_t sets = s.materials.size() + 1;
    VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                  std::uint32_t(sets * LANTERN_TEXTURE_BINDINGS)};
    VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpci.maxSets = std::uint32_t(sets);
    dpci.poolSizeCount = 1;
    dpci.pPoolSizes = &poolSize;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorPool(c.device(), &dpci, nullptr, &pool));
    m_pool = UniqueDescriptorPool(c.device(), pool);
    std::vector<VkDescriptorSetLayout> layouts(sets, layout);
    m_textureSets.resize(sets);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = std::uint32_t(layouts.size());
    ai.pSetLayouts = layouts.data();
    LANTERN_VK_TRY(vkAllocateDescriptorSets(c.device(), &ai, m_textureSets.data()));
    // Scene texture t is m_textures[t + 1]; -1 (none) is the white texture.
    auto info = [&](int t) {
        int samplerIndex = 0;
        if (t >= 0) {
            const Texture& tex = s.textures[std::size_t(t)];
            samplerIndex = samplerIndexOf(tex.nearest, tex.wrapS, tex.wrapT);
        }
        return VkDescriptorImageInfo{m_samplers[samplerIndex].get(),
                                     m_textures[std::size_t(t + 1)].view.get(),
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    };
    for (std::size_t set = 0; set < sets; ++set) {
        int bound[LANTERN_TEXTURE_BINDINGS] = {-1, -1, -1, -1, -1};
        if (set > 0) {
            const Material& m = s.materials[set - 1];
            bound[LANTERN_BINDING_BASE_COLOR] = m.baseColorTexture;
            bound[LANTERN_BINDING_METALLIC_ROUGHNESS] = m.metallicRoughnessMap.texture;
            bound[LANTERN_BINDING_NORMAL] = m.normalMap.texture;
            bound[LANTERN_BINDING_OCCLUSION] = m.occlusionMap.texture;
            bound[LANTERN_BINDING_EMISSIVE] = m.emissiveMap.texture;
        }
        VkDescriptorImageInfo infos[LANTERN_TEXTURE_BINDINGS];
        VkWriteDescriptorSet writes[LANTERN_TEXTURE_BINDINGS];
        for (std::uint32_t b = 0; b < LANTERN_TEXTURE_BINDINGS; ++b) {
            infos[b] = info(bound[b]);
            writes[b] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[b].dstSet = m_textureSets[set];
            writes[b].dstBinding = b;
            writes[b].descriptorCount = 1;
            writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[b].pImageInfo = &infos[b];
        }
        vkUpdateDescriptorSets(c.device(), LANTERN_TEXTURE_BINDINGS, writes, 0, nullptr);
    }
    return {};
}

} // namespace lantern::gpu
