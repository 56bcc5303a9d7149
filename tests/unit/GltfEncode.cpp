// Test meshes and their encodings (plain, KHR_mesh_quantization, EXT_meshopt_compression with
// meshoptimizer's encoders and filters, KHR_draco_mesh_compression with draco::Encoder), and an
// order-independent comparison of a loaded primitive with the mesh it was written from.
#include "GltfEncode.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace lantern::test {
namespace {

constexpr int kByte = 5120, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;
/// Quantized positions use 14 bits, as gltfpack does by default.
constexpr double kPositionSteps = 16383.0;

struct Bounds {
    glm::dvec3 min{1e300}, max{-1e300};
    double extent() const { return std::max({max.x - min.x, max.y - min.y, max.z - min.z}); }
};

Bounds positionBounds(const TestMesh& m) {
    Bounds b;
    for (std::size_t i = 0; i < m.vertexCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            b.min[c] = std::min(b.min[c], double(m.positions[3 * i + std::size_t(c)]));
            b.max[c] = std::max(b.max[c], double(m.positions[3 * i + std::size_t(c)]));
        }
    return b;
}

double texcoordExtent(const TestMesh& m) {
    if (m.texcoords.empty()) return 0.0;
    const auto [lo, hi] = std::minmax_element(m.texcoords.begin(), m.texcoords.end());
    return double(*hi - *lo);
}

bool texcoordsInUnitRange(const TestMesh& m) {
    return std::all_of(m.texcoords.begin(), m.texcoords.end(),
                       [](float v) { return v >= 0.0f && v <= 1.0f; });
}

/// The mesh's attributes in KHR_mesh_quantization's formats: positions as USHORT (padded to 8
/// bytes) on a 14-bit grid undone by the node's scale and translation, normals as normalized
/// BYTE (padded to 4), texcoords as normalized USHORT when they lie in [0, 1].
struct Quantized {
    std::vector<std::uint16_t> positions; ///< x, y, z, 0 per vertex
    std::vector<std::int8_t> normals;     ///< x, y, z, 0 per vertex
    std::vector<std::uint16_t> texcoords; ///< empty when they leave [0, 1]
    glm::dvec3 translation{0.0};
    double scale = 1.0;
};

Quantized quantize(const TestMesh& m) {
    Quantized q;
    const Bounds b = positionBounds(m);
    q.translation = b.min;
    q.scale = b.extent() > 0 ? b.extent() / kPositionSteps : 1.0;
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double p = (m.positions[3 * i + std::size_t(c)] - b.min[c]) / q.scale;
            q.positions.push_back(std::uint16_t(std::lround(p)));
            q.normals.push_back(std::int8_t(std::lround(m.normals[3 * i + std::size_t(c)] * 127.0)));
        }
        q.positions.push_back(0);
        q.normals.push_back(0);
    }
    if (texcoordsInUnitRange(m))
        for (float v : m.texcoords)
            q.texcoords.push_back(std::uint16_t(std::lround(v * 65535.0)));
    return q;
}

template <typename T>
std::vector<unsigned char> bytesOf(const std::vector<T>& v) {
    const auto* p = reinterpret_cast<const unsigned char*>(v.data());
    return std::vector<unsigned char>(p, p + v.size() * sizeof(T));
}

int addAccessorJson(GltfBuilder& b, nlohmann::json accessor) {
    b.doc["accessors"].push_back(std::move(accessor));
    return int(b.doc["accessors"].size()) - 1;
}

/// An accessor over a new plain view of `bytes`.
int addPlain(GltfBuilder& b, const std::vector<unsigned char>& bytes, std::size_t stride,
             std::size_t count, const char* type, int componentType, bool normalized) {
    const int view = b.addView(bytes.data(), bytes.size(), stride);
    nlohmann::json a = {{"bufferView", view}, {"componentType", componentType}, {"count", count},
                        {"type", type}};
    if (normalized) a["normalized"] = true;
    return addAccessorJson(b, a);
}

/// The meshopt views of one mesh: compressed bytes in buffer 0, and a fallback buffer without
/// data (added by finish()) that the views' own ranges lie in, as gltfpack writes them.
struct MeshoptWriter {
    GltfBuilder& b;
    int fallback;
    std::size_t fallbackLength = 0;

    explicit MeshoptWriter(GltfBuilder& builder)
        : b(builder), fallback(1 + int(builder.extraBuffers.size())) {}

    int view(const std::vector<unsigned char>& compressed, std::size_t stride, std::size_t count,
             const char* mode, const char* filter) {
        const std::size_t offset = appendBytes(b, compressed);
        nlohmann::json ext = {{"buffer", 0},       {"byteOffset", offset},
                              {"byteLength", compressed.size()}, {"byteStride", stride},
                              {"count", count},    {"mode", mode}};
        if (std::string(filter) != "NONE") ext["filter"] = filter;
        nlohmann::json v = {{"buffer", fallback},
                            {"byteOffset", fallbackLength},
                            {"byteLength", stride * count},
                            {"extensions", {{"EXT_meshopt_compression", ext}}}};
        if (std::string(mode) == "ATTRIBUTES") v["byteStride"] = stride;
        fallbackLength += (stride * count + 3) & ~std::size_t(3);
        b.doc["bufferViews"].push_back(v);
        return int(b.doc["bufferViews"].size()) - 1;
    }
    int accessor(int view, std::size_t count, const char* type, int componentType,
                 bool normalized) {
        nlohmann::json a = {{"bufferView", view}, {"componentType", componentType},
                            {"count", count}, {"type", type}};
        if (normalized) a["normalized"] = true;
        return addAccessorJson(b, a);
    }
    void finish() {
        b.extraBuffers.push_back(
            {{"byteLength", fallbackLength},
             {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
        declareExtension(b, "EXT_meshopt_compression", true);
    }
};

nlohmann::json primitiveJson(int position, int normal, int texcoord, int indices) {
    return {{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", texcoord}}},
            {"indices", indices}};
}

int addFloatMesh(GltfBuilder& b, const TestMesh& m) {
    const int position = b.addFloats(m.positions, "VEC3");
    const int normal = b.addFloats(m.normals, "VEC3");
    const int texcoord = b.addFloats(m.texcoords, "VEC2");
    const int indices = b.addAccessor(m.indices, "SCALAR", kUnsignedInt);
    return b.addNode({{"mesh", b.addMesh(primitiveJson(position, normal, texcoord, indices))}});
}

/// The node of a quantized mesh: its transform undoes the position quantization.
int addQuantizedNode(GltfBuilder& b, const Quantized& q, const nlohmann::json& primitive) {
    declareExtension(b, "KHR_mesh_quantization", true);
    const nlohmann::json t = {q.translation.x, q.translation.y, q.translation.z};
    return b.addNode({{"mesh", b.addMesh(primitive)},
                      {"translation", t},
                      {"scale", {q.scale, q.scale, q.scale}}});
}

int addQuantizedMesh(GltfBuilder& b, const TestMesh& m) {
    const Quantized q = quantize(m);
    const std::size_t n = m.vertexCount();
    const int position = addPlain(b, bytesOf(q.positions), 8, n, "VEC3", kUnsignedShort, false);
    const int normal = addPlain(b, bytesOf(q.normals), 4, n, "VEC3", kByte, true);
    const int texcoord = q.texcoords.empty()
                             ? b.addFloats(m.texcoords, "VEC2")
                             : addPlain(b, bytesOf(q.texcoords), 0, n, "VEC2", kUnsignedShort, true);
    std::vector<std::uint16_t> small(m.indices.begin(), m.indices.end());
    const int indices = n <= 65535 ? b.addIndices(small)
                                   : b.addAccessor(m.indices, "SCALAR", kUnsignedInt);
    return addQuantizedNode(b, q, primitiveJson(position, normal, texcoord, indices));
}

int addMeshoptQuantizedMesh(GltfBuilder& b, const TestMesh& m) {
    const Quantized q = quantize(m);
    const std::size_t n = m.vertexCount();
    MeshoptWriter w(b);
    const int position = w.accessor(
        w.view(meshoptVertices(q.positions.data(), n, 8), 8, n, "ATTRIBUTES", "NONE"), n, "VEC3",
        kUnsignedShort, false);
    // Octahedral normals: 8-bit x/y, z reconstructed on decoding; w (0) kept as is.
    std::vector<float> normals4;
    for (std::size_t i = 0; i < n; ++i)
        normals4.insert(normals4.end(), {m.normals[3 * i], m.normals[3 * i + 1],
                                         m.normals[3 * i + 2], 0.0f});
    std::vector<std::int8_t> oct(n * 4);
    meshopt_encodeFilterOct(oct.data(), n, 4, 8, normals4.data());
    const int normal = w.accessor(
        w.view(meshoptVertices(oct.data(), n, 4), 4, n, "ATTRIBUTES", "OCTAHEDRAL"), n, "VEC3",
        kByte, true);
    const int texcoord =
        q.texcoords.empty()
            ? w.accessor(w.view(meshoptVertices(m.texcoords.data(), n, 8), 8, n, "ATTRIBUTES",
                                "NONE"),
                         n, "VEC2", kFloat, false)
            : w.accessor(w.view(meshoptVertices(q.texcoords.data(), n, 4), 4, n, "ATTRIBUTES",
                                "NONE"),
                         n, "VEC2", kUnsignedShort, true);
    const std::size_t stride = n <= 65535 ? 2 : 4;
    const int indices = w.accessor(
        w.view(meshoptTriangles(m.indices, n), stride, m.indices.size(), "TRIANGLES", "NONE"),
        m.indices.size(), "SCALAR", stride == 2 ? kUnsignedShort : kUnsignedInt, false);
    w.finish();
    return addQuantizedNode(b, q, primitiveJson(position, normal, texcoord, indices));
}

int addMeshoptFloatMesh(GltfBuilder& b, const TestMesh& m) {
    const std::size_t n = m.vertexCount();
    MeshoptWriter w(b);
    const int position = w.accessor(
        w.view(meshoptVertices(m.positions.data(), n, 12), 12, n, "ATTRIBUTES", "NONE"), n,
        "VEC3", kFloat, false);
    std::vector<std::uint32_t> exp(n * 3);
    meshopt_encodeFilterExp(exp.data(), n, 12, 15, m.normals.data());
    const int normal = w.accessor(
        w.view(meshoptVertices(exp.data(), n, 12), 12, n, "ATTRIBUTES", "EXPONENTIAL"), n, "VEC3",
        kFloat, false);
    const int texcoord = w.accessor(
        w.view(meshoptVertices(m.texcoords.data(), n, 8), 8, n, "ATTRIBUTES", "NONE"), n, "VEC2",
        kFloat, false);
    std::vector<unsigned char> sequence(meshopt_encodeIndexSequenceBound(m.indices.size(), n));
    sequence.resize(meshopt_encodeIndexSequence(sequence.data(), sequence.size(), m.indices.data(),
                                                m.indices.size()));
    const int indices = w.accessor(w.view(sequence, 4, m.indices.size(), "INDICES", "NONE"),
                                   m.indices.size(), "SCALAR", kUnsignedInt, false);
    w.finish();
    return b.addNode({{"mesh", b.addMesh(primitiveJson(position, normal, texcoord, indices))}});
}

int addDracoMesh(GltfBuilder& b, const TestMesh& m, bool edgebreaker) {
    const DracoStream s = encodeDraco(m, edgebreaker);
    const int view = b.addView(s.bytes.data(), s.bytes.size());
    auto attribute = [&](const char* type) {
        return addAccessorJson(b, {{"componentType", kFloat}, {"count", s.points}, {"type", type}});
    };
    const int position = attribute("VEC3"), normal = attribute("VEC3"), texcoord = attribute("VEC2");
    const int indices = addAccessorJson(
        b, {{"componentType", kUnsignedInt}, {"count", 3 * s.faces}, {"type", "SCALAR"}});
    nlohmann::json prim = primitiveJson(position, normal, texcoord, indices);
    prim["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", view},
        {"attributes",
         {{"POSITION", s.positionId}, {"NORMAL", s.normalId}, {"TEXCOORD_0", s.texcoordId}}}};
    declareExtension(b, "KHR_draco_mesh_compression", true);
    return b.addNode({{"mesh", b.addMesh(prim)}});
}

} // namespace

TestMesh makeCube(float size) {
    TestMesh m;
    const float h = size / 2;
    const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
    // Each face: its normal and two axes with cross(u, v) = normal, so the corners below run
    // counter-clockwise seen from outside.
    const std::array<std::array<glm::vec3, 3>, 6> faces = {{{X, Y, Z}, {-X, Z, Y}, {Y, Z, X},
                                                            {-Y, X, Z}, {Z, X, Y}, {-Z, Y, X}}};
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& [n, u, v] : faces) {
        const auto base = std::uint32_t(m.vertexCount());
        for (const auto& c : corners) {
            const glm::vec3 p = h * (n + c[0] * u + c[1] * v);
            m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
            m.normals.insert(m.normals.end(), {n.x, n.y, n.z});
            m.texcoords.insert(m.texcoords.end(), {(c[0] + 1) / 2, (c[1] + 1) / 2});
        }
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return m;
}

TestMesh makeSphere(int rings, int segments, float radius) {
    TestMesh m;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const double theta = pi * i / rings, phi = 2 * pi * j / segments;
            const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                               std::sin(theta) * std::sin(phi));
            m.positions.insert(m.positions.end(), {float(radius * n.x), float(radius * n.y),
                                                   float(radius * n.z)});
            m.normals.insert(m.normals.end(), {float(n.x), float(n.y), float(n.z)});
            m.texcoords.insert(m.texcoords.end(), {float(j) / float(segments), float(i) / float(rings)});
        }
    auto vertex = [&](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    auto position = [&](std::uint32_t k) {
        return glm::dvec3(m.positions[3 * k], m.positions[3 * k + 1], m.positions[3 * k + 2]);
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                                d = vertex(i, j + 1);
            for (std::array<std::uint32_t, 3> t : {std::array{a, b, c}, std::array{a, c, d}}) {
                const glm::dvec3 e = glm::cross(position(t[1]) - position(t[0]),
                                                position(t[2]) - position(t[0]));
                if (glm::length(e) < 1e-12) continue; // the poles' degenerate halves
                if (glm::dot(e, position(t[0]) + position(t[1]) + position(t[2])) < 0)
                    std::swap(t[1], t[2]); // counter-clockwise seen from outside
                m.indices.insert(m.indices.end(), t.begin(), t.end());
            }
        }
    return m;
}

TestMesh meshOf(const Primitive& p, const glm::dmat4& transform) {
    TestMesh m;
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(transform)));
    for (std::size_t i = 0; i < p.positions.size(); ++i) {
        const glm::dvec3 q = glm::dvec3(transform * glm::dvec4(glm::dvec3(p.positions[i]), 1.0));
        m.positions.insert(m.positions.end(), {float(q.x), float(q.y), float(q.z)});
        glm::dvec3 n = normalMatrix * glm::dvec3(p.normals[i]);
        if (glm::length(n) > 0) n = glm::normalize(n);
        m.normals.insert(m.normals.end(), {float(n.x), float(n.y), float(n.z)});
        const glm::vec2 uv = i < p.texcoords.size() ? p.texcoords[i] : glm::vec2(0.0f);
        m.texcoords.insert(m.texcoords.end(), {uv.x, uv.y});
    }
    m.indices = p.indices;
    if (m.indices.empty())
        for (std::uint32_t i = 0; i < p.positions.size(); ++i)
            m.indices.push_back(i);
    return m;
}

std::string encodingName(Encoding e) {
    switch (e) {
    case Encoding::Float:
        return "Float";
    case Encoding::Quantized:
        return "Quantized";
    case Encoding::MeshoptFloat:
        return "MeshoptFloat";
    case Encoding::MeshoptQuantized:
        return "MeshoptQuantized";
    case Encoding::Draco:
        return "Draco";
    case Encoding::DracoSequential:
        return "DracoSequential";
    }
    return "?";
}

Tolerance toleranceOf(Encoding e, const TestMesh& mesh) {
    const double extent = positionBounds(mesh).extent(), uv = texcoordExtent(mesh);
    const bool unitUv = texcoordsInUnitRange(mesh);
    // Float rounding of the values as written (and of the node transform for quantized data).
    const double floatPosition = 1e-6 * std::max(extent, 1.0);
    // A grid of `steps` over the extent: half a step per component, sqrt(3)/2 steps in 3D.
    const double grid = std::sqrt(3.0) / 2 * extent / kPositionSteps + floatPosition;
    const double byteNormal = std::sqrt(3.0) * 0.5 / 127.0 + 1e-6;
    // Half a step per component, sqrt(2)/2 steps in 2D.
    const double shortUv = unitUv ? std::sqrt(2.0) * 0.5 / 65535.0 + 1e-7 : 1e-6;
    switch (e) {
    case Encoding::Float:
        return {floatPosition, 1e-6, 1e-6};
    case Encoding::Quantized:
        return {grid, byteNormal, shortUv};
    case Encoding::MeshoptFloat:
        // EXPONENTIAL with a 15-bit mantissa: 2^-15 of each component's magnitude.
        return {floatPosition, 1e-4, 1e-6};
    case Encoding::MeshoptQuantized:
        // Octahedral 8-bit normals: about 1.5 degrees at worst.
        return {grid, 0.03, shortUv};
    case Encoding::Draco:
    case Encoding::DracoSequential:
        // 14/10/12-bit quantization over each attribute's range (normals: octahedral).
        return {std::sqrt(3.0) * extent / 16383.0 + floatPosition, 0.01,
                std::sqrt(2.0) * std::max(uv, 1e-3) / 4095.0 + 1e-6};
    }
    return {};
}

int addEncodedMesh(GltfBuilder& b, const TestMesh& mesh, Encoding encoding) {
    switch (encoding) {
    case Encoding::Float:
        return addFloatMesh(b, mesh);
    case Encoding::Quantized:
        return addQuantizedMesh(b, mesh);
    case Encoding::MeshoptFloat:
        return addMeshoptFloatMesh(b, mesh);
    case Encoding::MeshoptQuantized:
        return addMeshoptQuantizedMesh(b, mesh);
    case Encoding::Draco:
        return addDracoMesh(b, mesh, true);
    case Encoding::DracoSequential:
        return addDracoMesh(b, mesh, false);
    }
    return -1;
}

std::size_t appendBytes(GltfBuilder& b, const std::vector<unsigned char>& bytes) {
    while (b.bin.size() % 4 != 0)
        b.bin.push_back(0);
    const std::size_t offset = b.bin.size();
    b.bin.insert(b.bin.end(), bytes.begin(), bytes.end());
    return offset;
}

void declareExtension(GltfBuilder& b, const std::string& name, bool required) {
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
        if (std::string(list) == "extensionsRequired" && !required) continue;
        nlohmann::json& names = b.doc[list];
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
}

std::vector<unsigned char> meshoptVertices(const void* data, std::size_t count, std::size_t stride) {
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
    return out;
}

std::vector<unsigned char> meshoptTriangles(const std::vector<std::uint32_t>& indices,
                                            std::size_t vertexCount) {
    std::vector<unsigned char> out(meshopt_encodeIndexBufferBound(indices.size(), vertexCount));
    out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), indices.data(), indices.size()));
    return out;
}

DracoStream encodeDraco(const TestMesh& mesh, bool edgebreaker) {
    draco::Mesh dm;
    const std::size_t n = mesh.vertexCount();
    dm.set_num_points(std::uint32_t(n));
    auto add = [&](draco::GeometryAttribute::Type type, int components, const std::vector<float>& v) {
        draco::GeometryAttribute ga;
        ga.Init(type, nullptr, std::uint8_t(components), draco::DT_FLOAT32, false,
                std::int64_t(sizeof(float)) * components, 0);
        const int id = dm.AddAttribute(ga, true, std::uint32_t(n));
        for (std::size_t i = 0; i < n; ++i)
            dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(std::uint32_t(i)),
                                                &v[i * std::size_t(components)]);
        return id;
    };
    const int position = add(draco::GeometryAttribute::POSITION, 3, mesh.positions);
    const int normal = add(draco::GeometryAttribute::NORMAL, 3, mesh.normals);
    const int texcoord = add(draco::GeometryAttribute::TEX_COORD, 2, mesh.texcoords);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        dm.AddFace({draco::PointIndex(mesh.indices[t]), draco::PointIndex(mesh.indices[t + 1]),
                    draco::PointIndex(mesh.indices[t + 2])});
    dm.DeduplicateAttributeValues();
    dm.DeduplicatePointIds();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    encoder.SetEncodingMethod(edgebreaker ? draco::MESH_EDGEBREAKER_ENCODING
                                          : draco::MESH_SEQUENTIAL_ENCODING);
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(dm, &buffer);
    if (!status.ok()) throw std::runtime_error("draco encoding failed: " + status.error_msg_string());
    DracoStream s;
    s.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    // What a decoder produces, as glTF writers use for the accessors' counts.
    draco::DecoderBuffer in;
    in.Init(buffer.data(), buffer.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok()) throw std::runtime_error("draco decoding failed");
    s.points = decoded.value()->num_points();
    s.faces = decoded.value()->num_faces();
    s.positionId = int(dm.attribute(position)->unique_id());
    s.normalId = int(dm.attribute(normal)->unique_id());
    s.texcoordId = int(dm.attribute(texcoord)->unique_id());
    return s;
}

} // namespace lantern::test
