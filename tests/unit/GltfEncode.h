// GltfEncode.h: test meshes (a cube, a UV sphere, any loaded primitive) written into a GltfBuilder
// plain, quantized (KHR_mesh_quantization), meshopt-compressed (EXT_meshopt_compression) or
// Draco-compressed (KHR_draco_mesh_compression), encoded with the same Debian libraries the
// loader decodes with; and a comparison of a loaded primitive with the mesh it came from that
// does not depend on vertex order (Draco reorders vertices).
#pragma once

#include "GltfTestBuilder.h"

#include <lantern/Scene.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::test {

/// A triangle mesh as flat arrays: xyz positions, xyz unit normals, uv texcoords, triangle list.
struct TestMesh {
    std::vector<float> positions, normals, texcoords;
    std::vector<std::uint32_t> indices;
    std::size_t vertexCount() const { return positions.size() / 3; }
};

/// 24 vertices (4 a face, face normals), 12 triangles, uv in [0, 1]; side `size`.
TestMesh makeCube(float size = 2.0f);
/// A UV sphere of `rings` x `segments` quads (2 x rings x segments triangles), radius `radius`.
TestMesh makeSphere(int rings, int segments, float radius = 1.0f);
/// A loaded primitive as a TestMesh, in the coordinates of `transform` (its node's).
TestMesh meshOf(const Primitive& p, const glm::dmat4& transform = glm::dmat4(1.0));

enum class Encoding {
    Float,            ///< FLOAT attributes, UNSIGNED_INT indices
    Quantized,        ///< KHR_mesh_quantization: USHORT positions + node scale, BYTE normals
    MeshoptFloat,     ///< FLOAT data; EXPONENTIAL filter on normals; INDICES mode
    MeshoptQuantized, ///< quantized data; OCTAHEDRAL normals; TRIANGLES mode (gltfpack's choice)
    Draco,            ///< Draco edgebreaker, quantized 14/10/12 bits (position/normal/uv)
    DracoSequential,  ///< Draco sequential connectivity, same quantization
};
std::string encodingName(Encoding e);
inline const Encoding kAllEncodings[] = {Encoding::Float,        Encoding::Quantized,
                                         Encoding::MeshoptFloat, Encoding::MeshoptQuantized,
                                         Encoding::Draco,        Encoding::DracoSequential};

/// The largest errors an encoding may introduce in a mesh's positions, normals and texcoords
/// (quantization steps follow the mesh's extents).
struct Tolerance {
    double position, normal, texcoord;
};
Tolerance toleranceOf(Encoding e, const TestMesh& mesh);

/// Adds `mesh` in `encoding` (a mesh and a root node carrying any dequantization transform) to
/// the builder, declaring the extensions it needs; returns the node index.
int addEncodedMesh(GltfBuilder& b, const TestMesh& mesh, Encoding encoding);

// --- Building blocks, for the hostile-input tests ---------------------------------------------

/// Appends raw bytes to the builder's binary buffer (4-byte aligned); returns their offset.
std::size_t appendBytes(GltfBuilder& b, const std::vector<unsigned char>& bytes);
/// Adds `name` to extensionsUsed and, when `required`, to extensionsRequired (once each).
void declareExtension(GltfBuilder& b, const std::string& name, bool required);
std::vector<unsigned char> meshoptVertices(const void* data, std::size_t count, std::size_t stride);
std::vector<unsigned char> meshoptTriangles(const std::vector<std::uint32_t>& indices,
                                            std::size_t vertexCount);
/// The mesh as a Draco stream (edgebreaker or sequential), with the points and faces a decoder
/// will produce (Draco may reorder and merge vertices).
struct DracoStream {
    std::vector<unsigned char> bytes;
    std::size_t points = 0, faces = 0;
    int positionId = 0, normalId = 0, texcoordId = 0;
};
DracoStream encodeDraco(const TestMesh& mesh, bool edgebreaker);

/// Checks that `loaded` has the triangles of `original` (same count, each triangle's corners
/// within the tolerance of the original's, winding kept), whatever the vertex order.
::testing::AssertionResult sameGeometry(const TestMesh& loaded, const TestMesh& original,
                                        const Tolerance& tolerance);

} // namespace lantern::test
