// SceneBuffers.h: a Scene's geometry and textures on the device. All primitives share one
// geometry buffer (non-interleaved streams at 16-byte-aligned offsets), also read as a storage
// buffer by the per-triangle flat pass (gpu/FlatLight.h); the de-indexed streams the per-corner
// flat path needs (face normal and centroid per element corner: points, lines, and triangles
// where the per-triangle pass cannot run) are built on first use.
#pragma once

#include "gpu/Clusters.h"
#include "gpu/Context.h"
#include "gpu/Resources.h"

#include <lantern/Scene.h>

#include <memory>
#include <mutex>
#include <vector>

namespace lantern::gpu {

inline constexpr VkDeviceSize kNoStream = ~VkDeviceSize(0);

struct PrimitiveBuffers {
    // Offsets into the geometry buffer; kNoStream for absent colours/texcoords.
    VkDeviceSize position = 0, normal = 0, color = kNoStream, texcoord = kNoStream,
                 texcoord1 = kNoStream, tangent = kNoStream, index = kNoStream;
    std::uint32_t vertexCount = 0;
    std::uint32_t indexCount = 0;  ///< 0: non-indexed
    // Offsets into the flat-geometry buffer (valid once flat streams exist).
    VkDeviceSize flatPosition = 0, flatNormal = 0, flatColor = kNoStream,
                 flatTexcoord = kNoStream, flatTexcoord1 = kNoStream, flatCentroid = 0;
    std::uint32_t flatVertexCount = 0;
    std::uint32_t corners = 3;  ///< vertices per element: 3 triangles, 2 lines, 1 points
    // Words into the deformation-input buffer (primitives with joints or morph targets).
    bool deformable = false;
    std::uint32_t deformPosition = 0, deformNormal = 0, deformJoints = 0, deformWeights = 0;
    std::uint32_t influences = 0;  ///< 0, 4 or 8
    std::uint32_t deformTargets = 0, targetCount = 0;
    std::uint32_t deformIndices = ~0u;  ///< the element list; ~0u: non-indexed
};

class SceneBuffers {
public:
    /// Uploads `scene` (which must have passed Scene::validate()).
    static Result<std::shared_ptr<SceneBuffers>> create(std::shared_ptr<Context> ctx,
                                                    std::shared_ptr<const Scene> scene,
                                                    VkDescriptorSetLayout textureLayout);
    ~SceneBuffers();

    const Scene& scene() const { return *m_scene; }
    /// The context (device) the scene lives on: only its own Renderer may draw it.
    const Context* context() const { return m_ctx.get(); }
    const std::shared_ptr<const Scene>& sharedScene() const { return m_scene; }
    const PrimitiveBuffers& primitive(std::uint32_t mesh, std::uint32_t prim) const {
        return m_primitives[m_meshFirst[mesh] + prim];
    }
    VkBuffer geometry() const { return m_geometry.get(); }
    VkBuffer flatGeometry() const { return m_flatGeometry.get(); }
    /// The skinning and morph-target inputs (storage buffer); null when nothing can deform.
    VkBuffer deformInput() const { return m_deformInput.get(); }
    VkDeviceSize deformInputBytes() const { return m_deformInput.size; }
    VkDeviceSize defaultColorOffset() const { return m_defaultColor; }
    VkDeviceSize defaultTexcoordOffset() const { return m_defaultTexcoord; }
    /// A zero vec4 (a tangent of zero: the normal map's frame from derivatives).
    VkDeviceSize defaultTangentOffset() const { return m_defaultTexcoord; }
    /// The texture set of material `index` (its base colour and maps, white where it has
    /// none); -1: every binding white.
    VkDescriptorSet textureSet(int index) const {
        return m_textureSets[std::size_t(index + 1)];
    }
    /// Builds the per-corner flat-shading streams of the points and lines, and of the triangles
    /// when `triangles`, if they do not exist yet (thread-safe).
    Result<void> ensureFlatStreams(bool triangles);
    /// Writes again the positions and normals of primitive `prim` of mesh `mesh` (and what is
    /// derived from them: the deformation inputs, the per-corner flat streams) from the Scene,
    /// which the host has edited in place. Waits for the device to be idle first: no frame
    /// reads the buffers while they change. InvalidInput naming the primitive when its vertex
    /// count changed or a value is not finite (nothing is written then).
    Result<void> updateVertices(std::uint32_t mesh, std::uint32_t prim);
    /// Bytes of the per-corner flat streams built so far (0: none).
    std::size_t flatGeometryBytes() const { return std::size_t(m_flatGeometry.size); }
    std::size_t geometryBytes() const { return std::size_t(m_geometry.size); }
    /// The clusters of the large triangle meshes (gpu/Clusters.h); null when none is large.
    SceneClusters* clusters() const { return m_clusters.get(); }

private:
    SceneBuffers() = default;
    // uploadTextures: the images (a white one first), the four samplers, one descriptor set
    // per image.
    Result<void> uploadTextures(VkDescriptorSetLayout layout);
    Result<void> uploadTextureImages();
    Result<void> createSamplers();
    Result<void> createTextureSets(VkDescriptorSetLayout layout);
    Result<void> uploadDeformInputs();
    Result<void> fillFlatStreams();
    /// Writes `bytes` at `offset` of `target` (mapped, or through a staging copy), for frames
    /// that read it at `dstStage`.
    Result<void> writeRange(Buffer& target, VkDeviceSize offset, const void* data,
                            VkDeviceSize bytes, VkPipelineStageFlags2 dstStage,
                            VkAccessFlags2 dstAccess);

    std::shared_ptr<Context> m_ctx;
    std::shared_ptr<const Scene> m_scene;
    std::vector<PrimitiveBuffers> m_primitives;
    std::vector<std::size_t> m_meshFirst;
    Buffer m_geometry;
    Buffer m_flatGeometry;
    Buffer m_deformInput;
    std::unique_ptr<SceneClusters> m_clusters;
    std::mutex m_flatMutex;
    bool m_flatReady = false, m_flatTriangles = false;
    /// Flat streams replaced by a larger set: a frame in flight may still read them.
    std::vector<Buffer> m_retiredFlat;
    VkDeviceSize m_defaultColor = 0, m_defaultTexcoord = 0;
    std::vector<Image> m_textures;  ///< [0] is the white default
    std::vector<UniqueSampler> m_samplers;  ///< by (nearest, clamp)
    UniqueDescriptorPool m_pool;
    std::vector<VkDescriptorSet> m_textureSets;
};

} // namespace lantern::gpu
