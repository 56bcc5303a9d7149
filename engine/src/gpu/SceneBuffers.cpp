// Uploads a scene's geometry (one buffer, non-interleaved streams), builds flat-shading
// streams on demand, and the skinning and morph-target inputs (textures: SceneTextures.cpp).
#include "gpu/SceneBuffers.h"

#include "lantern_shared.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>
#include <unordered_map>

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


// What flat shading lights an element with: its centroid, its normal (a triangle's face
// normal from its positions, zero when degenerate; the normalised mean of a line's or a point's
// vertex normals, zero without normals) and its mean vertex colour.
struct FlatElement {
    glm::vec3 centroid{0.0f}, normal{0.0f};
    glm::vec4 color{0.0f};
};

FlatElement flatElement(const Primitive& p, const std::uint32_t (&v)[3]) {
    const std::size_t k = p.verticesPerElement();
    FlatElement f;
    glm::dvec3 sum(0.0), normals(0.0);
    glm::dvec4 colors(0.0);
    for (std::size_t c = 0; c < k; ++c) {
        sum += glm::dvec3(p.positions[v[c]]);
        if (!p.normals.empty()) normals += glm::dvec3(p.normals[v[c]]);
        if (!p.colors.empty()) colors += glm::dvec4(p.colors[v[c]]);
    }
    f.centroid = glm::vec3(sum / double(k));
    f.color = glm::vec4(colors / double(k));
    if (k == 3) {
        const glm::dvec3 a(p.positions[v[0]]), b(p.positions[v[1]]), c(p.positions[v[2]]);
        normals = glm::cross(b - a, c - a);
    }
    const double len = glm::length(normals);
    if (len > 0.0 && std::isfinite(len)) f.normal = glm::vec3(normals / len);
    return f;
}


// The streams laid out so far, by their bytes: a primitive whose index list, colours, texture
// coordinates or tangents are byte for byte those of a primitive laid out before reads that
// stream (a file that shares an accessor between meshes holds it once on the device too).
// Positions and normals are never shared: updateVertices rewrites them per primitive.
class SharedStreams {
public:
    // Where `v` goes: the offset of the same bytes laid out before, or a new range from `size`
    // on (advanced past it, 16-byte aligned).
    template <typename T>
    VkDeviceSize place(const std::vector<T>& v, VkDeviceSize& size) {
        const std::size_t bytes = v.size() * sizeof(T);
        const std::size_t hash =
            std::hash<std::string_view>{}(std::string_view(reinterpret_cast<const char*>(v.data()), bytes));
        const auto [first, last] = m_byHash.equal_range(hash);
        for (auto it = first; it != last; ++it)
            if (it->second.bytes == bytes && std::memcmp(it->second.data, v.data(), bytes) == 0)
                return it->second.offset;
        const VkDeviceSize at = size;
        size = align16(size + bytes);
        m_byHash.emplace(hash, Entry{v.data(), bytes, at});
        return at;
    }
    // Writes each stream once, at its offset in `dst`.
    void fill(char* dst) const {
        for (const auto& entry : m_byHash)
            std::memcpy(dst + entry.second.offset, entry.second.data, entry.second.bytes);
    }

private:
    struct Entry {
        const void* data;  // the Scene's array (alive while the buffer is filled)
        std::size_t bytes;
        VkDeviceSize offset;
    };
    std::unordered_multimap<std::size_t, Entry> m_byHash;
};

// Where primitive `p`'s streams go in the geometry buffer, from byte `size` on (advanced past
// the new ones, each 16-byte aligned).
Result<PrimitiveBuffers> layOut(const Primitive& p, VkDeviceSize& size, SharedStreams& shared) {
    PrimitiveBuffers gp;
    const VkDeviceSize n = p.positions.size();
    if (n > std::numeric_limits<std::uint32_t>::max() ||
        p.indices.size() > std::numeric_limits<std::uint32_t>::max())
        return tooLarge("a primitive");
    gp.vertexCount = std::uint32_t(n);
    gp.corners = std::uint32_t(p.verticesPerElement());
    gp.indexCount = std::uint32_t(p.indices.size());
    gp.position = size;
    size = align16(size + n * 12);
    gp.normal = size;
    size = align16(size + n * 12);
    if (!p.colors.empty()) gp.color = shared.place(p.colors, size);
    if (!p.texcoords.empty()) gp.texcoord = shared.place(p.texcoords, size);
    if (!p.texcoords1.empty()) gp.texcoord1 = shared.place(p.texcoords1, size);
    if (!p.tangents.empty()) gp.tangent = shared.place(p.tangents, size);
    if (!p.indices.empty()) gp.index = shared.place(p.indices, size);
    return gp;
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

    // Layout: defaults first (a white colour, and 16 zero bytes: the texcoord and the tangent
    // of stride-0 bindings).
    VkDeviceSize size = 32;
    g->m_defaultColor = 0;
    g->m_defaultTexcoord = 16;
    SharedStreams shared;
    for (const Mesh& mesh : s.meshes) {
        g->m_meshFirst.push_back(g->m_primitives.size());
        for (const Primitive& p : mesh.primitives) {
            auto gp = layOut(p, size, shared);
            if (!gp) return std::move(gp).error();
            g->m_primitives.push_back(*gp);
        }
    }
    Context& c = *g->m_ctx;
    // Vertices and indices to draw, storage for the per-triangle flat pass to read.
    auto buffer = createBuffer(c, size,
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT |
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    MemoryUsage::DeviceLocal, "scene geometry");
    if (!buffer) return std::move(buffer).error();
    g->m_geometry = std::move(*buffer);
    auto fill = beginFill(c, g->m_geometry);
    if (!fill) return std::move(fill).error();
    char* dst = fill->dst;
    const float white[4] = {1, 1, 1, 1}, zero[4] = {0, 0, 0, 0};
    std::memcpy(dst + g->m_defaultColor, white, sizeof white);
    std::memcpy(dst + g->m_defaultTexcoord, zero, sizeof zero);
    std::size_t k = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            const PrimitiveBuffers& gp = g->m_primitives[k++];
            put(dst, gp.position, p.positions);
            if (p.normals.empty())  // unlit lines and points: zero normals (the normal AOV)
                std::memset(dst + gp.normal, 0, p.positions.size() * 12);
            else
                put(dst, gp.normal, p.normals);
        }
    shared.fill(dst);  // the other streams, each once however many primitives read it
    LANTERN_TRY(endFill(c, g->m_geometry, *fill,
                        VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT |
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT));
    auto clusters = SceneClusters::create(c, g->m_scene);
    if (!clusters) return std::move(clusters).error();
    if ((*clusters)->any()) g->m_clusters = std::move(*clusters);
    LANTERN_TRY(g->uploadDeformInputs());
    LANTERN_TRY(g->uploadTextures(textureLayout));
    return g;
}

Result<void> SceneBuffers::ensureFlatStreams(bool triangles) {
    std::lock_guard lock(m_flatMutex);
    if (m_flatReady && (m_flatTriangles || !triangles)) return {};
    const Scene& s = *m_scene;
    VkDeviceSize size = 16;
    std::size_t k = 0;
    bool any = false;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            PrimitiveBuffers& gp = m_primitives[k++];
            gp.flatVertexCount = 0;
            if (p.verticesPerElement() == 3 && !triangles) continue;
            any = true;
            const VkDeviceSize n = VkDeviceSize(p.elementCount()) * p.verticesPerElement();
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
            if (!p.texcoords1.empty()) {
                gp.flatTexcoord1 = size;
                size = align16(size + n * 8);
            }
        }
    m_flatReady = !any;
    m_flatTriangles = triangles;
    if (!any) return {};
    auto buffer = createBuffer(*m_ctx, size,
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    MemoryUsage::DeviceLocal, "flat geometry");
    if (!buffer) return std::move(buffer).error();
    if (m_flatGeometry.get()) m_retiredFlat.push_back(std::move(m_flatGeometry));
    m_flatGeometry = std::move(*buffer);
    LANTERN_TRY(fillFlatStreams());
    m_flatReady = true;
    return {};
}

// Writes the per-corner streams of every primitive that has them from the Scene's vertices
// into the flat-geometry buffer laid out by ensureFlatStreams (again after updateVertices).
Result<void> SceneBuffers::fillFlatStreams() {
    const Scene& s = *m_scene;
    auto fill = beginFill(*m_ctx, m_flatGeometry);
    if (!fill) return std::move(fill).error();
    char* dst = fill->dst;
    std::size_t k = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            const PrimitiveBuffers& gp = m_primitives[k++];
            if (gp.flatVertexCount == 0) continue;
            auto* pos = reinterpret_cast<glm::vec3*>(dst + gp.flatPosition);
            auto* nrm = reinterpret_cast<glm::vec3*>(dst + gp.flatNormal);
            auto* cen = reinterpret_cast<glm::vec3*>(dst + gp.flatCentroid);
            auto* col = gp.flatColor != kNoStream ? reinterpret_cast<glm::vec4*>(dst + gp.flatColor) : nullptr;
            auto* tex = gp.flatTexcoord != kNoStream ? reinterpret_cast<glm::vec2*>(dst + gp.flatTexcoord) : nullptr;
            auto* tex1 = gp.flatTexcoord1 != kNoStream ? reinterpret_cast<glm::vec2*>(dst + gp.flatTexcoord1) : nullptr;
            const std::size_t corners = p.verticesPerElement(), elements = p.elementCount();
            for (std::size_t e = 0; e < elements; ++e) {
                std::uint32_t v[3] = {};
                for (std::size_t c = 0; c < corners; ++c)
                    v[c] = p.indices.empty() ? std::uint32_t(e * corners + c)
                                             : p.indices[e * corners + c];
                const FlatElement f = flatElement(p, v);
                for (std::size_t c = 0; c < corners; ++c) {
                    const std::size_t o = e * corners + c;
                    pos[o] = p.positions[v[c]];
                    nrm[o] = f.normal;
                    cen[o] = f.centroid;
                    if (col) col[o] = f.color;
                    if (tex) tex[o] = p.texcoords[v[c]];
                    if (tex1) tex1[o] = p.texcoords1[v[c]];
                }
            }
        }
    return endFill(*m_ctx, m_flatGeometry, *fill);
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
            if (p.normals.empty()) std::memset(dst + gp.deformNormal, 0, n * 12);
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

} // namespace lantern::gpu
