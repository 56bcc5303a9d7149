// OBJ (with its MTL libraries) into the scene model (ObjInternal.h lists the passes): a node
// and mesh per tinyobjloader shape (`o`/`g`), a primitive per material used (`usemtl`), the
// file's lines and points as primitives of the object they were written in.
#include "io/FileAccess.h"
#include "io/mesh/MeshLoad.h"
#include "scene/Fidelity.h"
#include "io/mesh/ObjBuild.h"

#include <map>
#include <sstream>

namespace lantern::mesh {
namespace {

struct ByteStream : std::streambuf {
    explicit ByteStream(std::vector<unsigned char>& b) {
        char* p = reinterpret_cast<char*>(b.data());
        setg(p, p, p + b.size());
    }
};

/// The model tinyobjloader makes of the file.
struct TinyModel {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::set<std::string> illum;  ///< materials that state their illum
    std::string warnings;
};

std::filesystem::path folderOf(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.parent_path();
    return folder.empty() ? std::filesystem::path(".") : folder;
}

Result<TinyModel> parse(std::vector<unsigned char>& bytes, const std::filesystem::path& path,
                        const LoadOptions& options, const Diagnostics& diag) {
    TinyModel m;
    ConfinedMtlReader mtl(folderOf(path), options, diag);
    ByteStream buf(bytes);
    std::istream in(&buf);
    std::string err;
    // triangulate = false: faces come back whole (Lantern triangulates them in linear time);
    // default_vcols_fallback = false: colours only when every v line has them.
    const bool ok = tinyobj::LoadObj(&m.attrib, &m.shapes, &m.materials, &m.warnings, &err, &in,
                                     &mtl, false, false);
    if (mtl.failure()) return *mtl.failure();
    m.illum = mtl.illum();
    // Colours for every vertex or none (tinyobjloader's rule with no fallback): kept only whole.
    if (m.attrib.colors.size() != m.attrib.vertices.size()) m.attrib.colors.clear();
    if (!ok) {
        std::istringstream lines(err);
        std::string first;
        std::getline(lines, first);
        return diag.error("", "tinyobjloader refused it: " + io::printable(first, 200));
    }
    return m;
}

// Every number tinyobjloader kept is finite (the scan refused "nan" and "inf"; a number beyond
// float's range reads as infinity and is refused here, by its element).
Result<void> checkFinite(const tinyobj::attrib_t& a, const Diagnostics& diag) {
    const std::pair<const std::vector<float>*, std::pair<const char*, std::size_t>> arrays[] = {
        {&a.vertices, {"vertex", 3}}, {&a.colors, {"vertex", 3}},
        {&a.normals, {"normal", 3}},  {&a.texcoords, {"texture coordinate", 2}}};
    for (const auto& [values, what] : arrays)
        for (std::size_t i = 0; i < values->size(); ++i)
            if (!std::isfinite((*values)[i]))
                return diag.error(at(what.first, i / what.second + 1), "a number is beyond float's range (not finite)");
    return {};
}

/// Turns tinyobjloader's shapes and the scan's lines and points into meshes.
class ObjAssembly {
public:
    ObjAssembly(const TinyModel& model, const ObjScan& scan, const Diagnostics& diag)
        : m_model(model), m_scan(scan), m_diag(diag) {}

    Result<std::vector<Mesh>> run() {
        for (const tinyobj::shape_t& s : m_model.shapes) LANTERN_TRY(shape(s));
        skipShortFaces();
        if (m_face != m_scan.degrees.size())
            return mismatch("the file has " + std::to_string(m_scan.degrees.size()) +
                            " faces, tinyobjloader returned " + std::to_string(m_face));
        if (m_short)
            m_diag.warn("faces", std::to_string(m_short) + " face(s) with fewer than 3 corners skipped");
        LANTERN_TRY(polylines());
        return std::move(m_meshes);
    }

private:
    Error mismatch(const std::string& what) const {
        return makeError(ErrorCode::Internal, "tinyobjloader's faces disagree with the file's: " + what,
                         "faces", m_diag.file());
    }

    void skipShortFaces() {
        while (m_face < m_scan.degrees.size() && m_scan.degrees[m_face] < 3) {
            ++m_face;
            ++m_short;
        }
    }

    Result<void> checkCorner(const tinyobj::index_t& c, std::size_t corner) const {
        const tinyobj::attrib_t& a = m_model.attrib;
        const std::size_t nv = a.vertices.size() / 3, nt = a.texcoords.size() / 2, nn = a.normals.size() / 3;
        const bool ok = c.vertex_index >= 0 && std::size_t(c.vertex_index) < nv &&
                        (c.texcoord_index == -1 || (c.texcoord_index >= 0 && std::size_t(c.texcoord_index) < nt)) &&
                        (c.normal_index == -1 || (c.normal_index >= 0 && std::size_t(c.normal_index) < nn));
        if (ok) return {};
        return m_diag.error(at("face", m_face + 1),
                            "corner " + std::to_string(corner + 1) + " names vertex " +
                                std::to_string(c.vertex_index + 1) + "/" + std::to_string(c.texcoord_index + 1) +
                                "/" + std::to_string(c.normal_index + 1) + " (1-based; relative indices resolved), "
                                "outside the file's " + std::to_string(nv) + " vertices, " + std::to_string(nt) +
                                " texture coordinates and " + std::to_string(nn) + " normals (line " +
                                std::to_string(m_scan.faceLines[m_face]) + ")");
    }

    /// A mesh's primitives of one topology, one per material, in the order of first use.
    struct Primitives {
        std::vector<std::unique_ptr<ObjPrimitive>> list;
        std::map<int, std::size_t> byMaterial;
    };

    ObjPrimitive& primitive(Primitives& prims, Topology t, int material) {
        const auto [it, added] = prims.byMaterial.emplace(material, prims.list.size());
        if (added) prims.list.push_back(std::make_unique<ObjPrimitive>(m_model.attrib, t, material, m_diag));
        return *prims.list[it->second];
    }

    Result<void> shape(const tinyobj::shape_t& s);
    Result<void> polylines();
    Result<void> addMesh(const std::string& name, Primitives& prims);

    const TinyModel& m_model;
    const ObjScan& m_scan;
    const Diagnostics& m_diag;
    std::vector<Mesh> m_meshes;
    std::map<std::string, std::size_t> m_meshByName;  ///< shapes of one name share a mesh
    std::size_t m_face = 0, m_short = 0;
};

Result<void> ObjAssembly::shape(const tinyobj::shape_t& s) {
    Primitives prims;
    const tinyobj::mesh_t& mesh = s.mesh;
    std::size_t offset = 0;
    for (std::size_t k = 0; k < mesh.num_face_vertices.size(); ++k) {
        skipShortFaces();
        // tinyobjloader keeps a face's degree in a byte: the scan's count is the true one.
        const std::size_t degree = m_face < m_scan.degrees.size() ? m_scan.degrees[m_face] : 0;
        if (degree == 0 || (degree & 0xFF) != mesh.num_face_vertices[k] ||
            offset + degree > mesh.indices.size() || k >= mesh.material_ids.size() ||
            k >= mesh.smoothing_group_ids.size())
            return mismatch(at("face", m_face + 1) + " of shape \"" + io::printable(s.name) + "\"");
        for (std::size_t c = 0; c < degree; ++c) LANTERN_TRY(checkCorner(mesh.indices[offset + c], c));
        int material = mesh.material_ids[k];
        if (material < -1 || material >= int(m_model.materials.size())) material = -1;
        LANTERN_TRY(primitive(prims, Topology::Triangles, material)
                        .polygon(&mesh.indices[offset], degree, mesh.smoothing_group_ids[k]));
        offset += degree;
        ++m_face;
    }
    if (offset != mesh.indices.size()) return mismatch("corners left over in shape \"" + io::printable(s.name) + "\"");
    return addMesh(s.name, prims);
}

Result<void> ObjAssembly::addMesh(const std::string& name, Primitives& prims) {
    if (prims.list.empty()) return {};
    const auto [it, added] = m_meshByName.emplace(name, m_meshes.size());
    if (added) {
        m_meshes.emplace_back();
        m_meshes.back().name = name;
    }
    Mesh* mesh = &m_meshes[it->second];
    for (auto& p : prims.list) {
        auto prim = p->finish();
        if (!prim) return std::move(prim).error();
        mesh->primitives.push_back(std::move(*prim));
    }
    return {};
}

// The lines and points, each run in the object and material it was written under (the scan's
// polylines come in the order of their runs).
Result<void> ObjAssembly::polylines() {
    std::map<std::string, int> materialIds;  // the first material of each name, as tinyobjloader
    for (std::size_t i = 0; i < m_model.materials.size(); ++i)
        materialIds.emplace(m_model.materials[i].name, int(i));
    for (std::size_t first = 0; first < m_scan.polylines.size();) {
        const std::uint32_t g = m_scan.polylines[first].group;
        const auto& [object, material] = m_scan.groups[g];
        const auto id = materialIds.find(material);
        const int mat = id == materialIds.end() ? -1 : id->second;
        Primitives lines, points;
        std::size_t i = first;
        for (; i < m_scan.polylines.size() && m_scan.polylines[i].group == g; ++i) {
            const ObjPolyline& p = m_scan.polylines[i];
            LANTERN_TRY(primitive(p.points ? points : lines, p.points ? Topology::Points : Topology::Lines, mat)
                            .polyline(m_scan.corners.data() + p.first, p.count));
        }
        LANTERN_TRY(addMesh(object, lines));
        LANTERN_TRY(addMesh(object, points));
        first = i;
    }
    return {};
}

// tinyobjloader's warnings worth passing on: a usemtl naming no material.
void forwardWarnings(const std::string& warnings, const Diagnostics& diag) {
    std::istringstream lines(warnings);
    for (std::string line; std::getline(lines, line);)
        if (line.find("not found in .mtl") != std::string::npos)
            diag.warn("usemtl", io::printable(line, 200) + ": the default material is used");
}

} // namespace

Result<Scene> readObj(std::vector<unsigned char>& bytes, const LoadOptions& options,
                      const Diagnostics& diag) {
    auto scan = scanObj(bytes, diag);
    if (!scan) return std::move(scan).error();
    LANTERN_TRY(chargeTinyobj(*scan, diag));
    const std::filesystem::path path(diag.file());
    auto model = parse(bytes, path, options, diag);
    if (!model) return std::move(model).error();
    // The text is read: its memory goes back before the vertices are built.
    diag.release(bytes.size());
    std::vector<unsigned char>().swap(bytes);
    LANTERN_TRY(checkFinite(model->attrib, diag));
    std::vector<Texture> textures;
    std::vector<std::string> skippedMaps;
    auto materials = convertObjMaterials(model->materials, model->illum, folderOf(path), options,
                                         diag, textures, skippedMaps);
    if (!materials) return std::move(materials).error();
    auto meshes = ObjAssembly(*model, *scan, diag).run();
    if (!meshes) return std::move(meshes).error();
    forwardWarnings(model->warnings, diag);
    auto scene = assembleScene("obj", std::move(*meshes), std::move(*materials),
                               std::move(textures), diag);
    if (scene)
        for (std::string& object : skippedMaps)
            scene::noteFeature(*scene, "obj-skipped-maps", std::move(object));
    return scene;
}

} // namespace lantern::mesh
