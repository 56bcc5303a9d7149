// What the mesh readers share (io/mesh/MeshInternal.h): the file read and charged, the scene
// assembled and checked, per-face colours, smooth normals, number tokens.
#include "io/mesh/MeshInternal.h"

#include "io/FileAccess.h"
#include "io/mesh/MeshLoad.h"
#include "scene/Fidelity.h"

#include <charconv>
#include <cstdio>
#include <limits>
#include <new>

namespace lantern::mesh {

std::string at(const char* what, std::uint64_t index) {
    return std::string(what) + " " + std::to_string(index);
}

Result<Scene> loadFile(BytesReader reader, const std::filesystem::path& path,
                       const LoadOptions& options) {
    const Diagnostics diag(path.string(), options.log, options.maxBytes);
    auto bytes = io::readRegularFile(path, options.maxBytes, false);
    if (!bytes) {
        Error e = std::move(bytes).error();
        e.message = "the scene file " + e.message;
        e.file = diag.file();
        return e;
    }
    LANTERN_TRY(diag.charge(bytes->size(), 1, "", "the file's bytes"));
    return reader(*bytes, options, diag);
}

Result<Scene> loadBytes(BytesReader reader, std::vector<unsigned char> bytes,
                        const std::filesystem::path& path, const LoadOptions& options) {
    try {
        const Diagnostics diag(path.string(), options.log, options.maxBytes);
        LANTERN_TRY(diag.charge(bytes.size(), 1, "", "the file's bytes"));
        return reader(bytes, options, diag);
    } catch (const std::bad_alloc&) {
        return makeError(ErrorCode::OutOfMemory, "out of memory while loading", {}, path.string());
    } catch (const std::exception& e) {
        return makeError(ErrorCode::InvalidInput, std::string("cannot be loaded: ") + e.what(), {},
                         path.string());
    }
}

Result<void> spreadFaceColors(Primitive& prim, const std::vector<std::uint32_t>& faceOfTriangle,
                              const std::vector<glm::vec4>& faceColors, const Diagnostics& diag) {
    const std::size_t corners = prim.indices.size();
    const std::uint64_t each = sizeof(glm::vec3) * 2 + sizeof(glm::vec4) + sizeof(glm::vec2);
    LANTERN_TRY(diag.charge(corners, each, "faces", "the faces' own vertices (per-face colours)"));
    Primitive out;
    out.topology = prim.topology;
    out.material = prim.material;
    out.positions.reserve(corners);
    if (!prim.normals.empty()) out.normals.reserve(corners);
    if (!prim.texcoords.empty()) out.texcoords.reserve(corners);
    out.colors.reserve(corners);
    for (std::size_t c = 0; c < corners; ++c) {
        const std::uint32_t v = prim.indices[c];
        out.positions.push_back(prim.positions[v]);
        if (!prim.normals.empty()) out.normals.push_back(prim.normals[v]);
        if (!prim.texcoords.empty()) out.texcoords.push_back(prim.texcoords[v]);
        const glm::vec4 own = faceColors[faceOfTriangle[c / 3]];
        // A face without a colour of its own (alpha < 0 marks it) keeps its vertex colour.
        out.colors.push_back(own.a >= 0.0f ? own
                             : prim.colors.empty() ? glm::vec4(1.0f)
                                                   : prim.colors[v]);
    }
    prim = std::move(out);
    return {};
}

Result<void> addSmoothNormals(Primitive& prim, const Diagnostics& diag) {
    // computeSmoothNormals holds a double-precision sum per vertex beside the result.
    LANTERN_TRY(diag.charge(prim.positions.size(), sizeof(glm::dvec3) + sizeof(glm::vec3),
                            "vertices", "computing the normals"));
    prim.normals = computeSmoothNormals(prim.positions, prim.indices);
    return {};
}

namespace {

// What a mesh file uses, for the fidelity report: the format, the maps, blending, points and
// lines.
void noteMeshFeatures(Scene& scene, std::string_view formatKey) {
    scene::noteFeature(scene, formatKey, std::filesystem::path(scene.sourcePath).filename().string());
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        const std::string object = "materials \"" + m.name + "\"";
        if (m.baseColorTexture >= 0) scene::noteFeature(scene, "base-color-texture", object);
        if (m.normalMap.texture >= 0) scene::noteFeature(scene, "normal-texture", object);
        if (m.emissiveMap.texture >= 0) scene::noteFeature(scene, "emissive-texture", object);
        if (m.alphaMode != AlphaMode::Opaque) scene::noteFeature(scene, "alpha-modes", object);
    }
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& p : mesh.primitives)
            if (p.topology != Topology::Triangles) {
                scene::noteFeature(scene, "points-lines", "meshes \"" + mesh.name + "\"");
                break;
            }
}

} // namespace

Result<Scene> assembleScene(std::string_view formatKey, std::vector<Mesh> meshes,
                            std::vector<Material> materials, std::vector<Texture> textures,
                            const Diagnostics& diag) {
    Scene scene;
    scene.sourcePath = diag.file();
    scene.materials = std::move(materials);
    scene.textures = std::move(textures);
    SceneRoot root;
    root.name = std::filesystem::path(diag.file()).filename().string();
    for (Mesh& m : meshes) {
        std::erase_if(m.primitives, [](const Primitive& p) { return p.elementCount() == 0; });
        if (m.primitives.empty()) continue;
        Node node;
        node.name = m.name;
        node.mesh = int(scene.meshes.size());
        root.nodes.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(std::move(node));
        scene.meshes.push_back(std::move(m));
    }
    scene.roots.push_back(std::move(root));
    if (auto valid = scene.validate(); !valid) {
        Error e = std::move(valid).error();
        e.file = diag.file();
        return e;
    }
    noteMeshFeatures(scene, formatKey);
    return scene;
}

Result<Scene> indexedScene(std::string_view formatKey, IndexedMesh m, const Diagnostics& diag) {
    Primitive prim;
    prim.topology = m.hasFaces ? Topology::Triangles : Topology::Points;
    prim.positions = std::move(m.positions);
    prim.normals = std::move(m.normals);
    prim.colors = std::move(m.colors);
    prim.texcoords = std::move(m.texcoords);
    if (m.hasFaces && m.indices.empty()) {
        prim = Primitive{};  // faces, none with 3 corners: nothing to draw (no implicit list)
    } else if (m.hasFaces) {
        prim.indices = std::move(m.indices);
        if (prim.normals.empty()) LANTERN_TRY(addSmoothNormals(prim, diag));
        if (!m.faceColors.empty()) LANTERN_TRY(spreadFaceColors(prim, m.faceOfTriangle, m.faceColors, diag));
    }
    Mesh mesh;
    mesh.name = std::filesystem::path(diag.file()).stem().string();
    mesh.primitives.push_back(std::move(prim));
    std::vector<Mesh> meshes;
    meshes.push_back(std::move(mesh));
    return assembleScene(formatKey, std::move(meshes), {}, {}, diag);
}

std::string shownNumber(double value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", value);
    return buf;
}

bool parseNumber(std::string_view token, double& out) {
    if (token.empty()) return false;
    const char* first = token.data();
    const char* last = first + token.size();
    if (*first == '+') ++first;  // from_chars refuses a leading '+'; files write it
    const auto [end, ec] = std::from_chars(first, last, out);
    if (end != last) return false;
    // Out of double's range: the value is not finite, which the caller refuses by name.
    if (ec == std::errc::result_out_of_range) out = std::numeric_limits<double>::infinity();
    return ec == std::errc() || ec == std::errc::result_out_of_range;
}

bool parseInteger(std::string_view token, std::int64_t& out) {
    if (token.empty()) return false;
    const char* first = token.data();
    const char* last = first + token.size();
    if (*first == '+') ++first;
    const auto [end, ec] = std::from_chars(first, last, out);
    return ec == std::errc() && end == last;
}

// --- TextCursor -------------------------------------------------------------------------------

bool TextCursor::skipSpace(bool stayOnLine) {
    while (m_pos < m_size) {
        const unsigned char c = m_data[m_pos];
        if (m_comment && c == static_cast<unsigned char>(m_comment)) {
            while (m_pos < m_size && m_data[m_pos] != '\n' && m_data[m_pos] != '\r') ++m_pos;
            continue;
        }
        if (c == '\n' || c == '\r') {
            if (stayOnLine) return false;
            // "\r\n" is one line end; a lone '\r' is one too.
            if (c == '\r' && m_pos + 1 < m_size && m_data[m_pos + 1] == '\n') ++m_pos;
            ++m_pos;
            ++m_line;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\v' || c == '\f') {
            ++m_pos;
            continue;
        }
        return true;
    }
    return false;
}

std::string_view TextCursor::token() {
    const std::size_t start = m_pos;
    while (m_pos < m_size) {
        const unsigned char c = m_data[m_pos];
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f' ||
            (m_comment && c == static_cast<unsigned char>(m_comment)))
            break;
        ++m_pos;
    }
    return {reinterpret_cast<const char*>(m_data) + start, m_pos - start};
}

std::string_view TextCursor::next() { return skipSpace(false) ? token() : std::string_view(); }

std::string_view TextCursor::nextOnLine() {
    return skipSpace(true) ? token() : std::string_view();
}

void TextCursor::skipLine() {
    while (m_pos < m_size && m_data[m_pos] != '\n' && m_data[m_pos] != '\r') ++m_pos;
    if (m_pos < m_size) {
        if (m_data[m_pos] == '\r' && m_pos + 1 < m_size && m_data[m_pos + 1] == '\n') ++m_pos;
        ++m_pos;
        ++m_line;
    }
}

bool TextCursor::atEnd() { return !skipSpace(false); }

} // namespace lantern::mesh
