// ObjInternal.h: the OBJ reader's passes (only io/mesh/Obj*.cpp include this).
//   1. ObjScan.cpp       one pass over the text before tinyobjloader sees it: every number and
//                        index token checked (tinyobjloader reads "nan" as 0 and wraps indices
//                        beyond 2^31 silently), the counts the budget is charged with, each face's
//                        degree (tinyobjloader keeps it in a byte), the lines and points (read
//                        here: tinyobjloader repeats or drops them around usemtl and g), and the
//                        lines tinyobjloader must not see turned into comments in place.
//   2. tinyobjloader     v/vt/vn, faces with their groups, materials and smoothing groups; MTL
//                        libraries through ObjMaterials.cpp's confined reader.
//   3. ObjLoad.cpp       indices checked, corners welded into vertices, polygons triangulated,
//                        normals by smoothing group, one primitive per material.
//   4. ObjMaterials.cpp  MTL -> the classic material, the textures decoded.
#pragma once

#include "io/mesh/MeshInternal.h"

#include <tiny_obj_loader.h>

#include <map>
#include <memory>
#include <optional>
#include <set>

namespace lantern::mesh {

/// A line or point element an OBJ file lists (`l`, `p`), its corners resolved to 0-based
/// indices (negative ones relative to the vertices read so far; checked against the final
/// counts later).
struct ObjCorner {
    std::int64_t v = 0, vt = -1;
};
struct ObjPolyline {
    std::size_t first = 0, count = 0;  ///< its corners in ObjScan::corners
    bool points = false;               ///< `p`: each corner a point; `l`: a polyline
    std::uint32_t group = 0;           ///< ObjScan::groups index: the object and material
    std::size_t line = 0;
};

/// What the first pass learned.
struct ObjScan {
    std::uint64_t v = 0, vt = 0, vn = 0;
    std::uint64_t faces = 0, faceCorners = 0, groupLines = 0, mtlNames = 0;
    std::vector<std::uint32_t> degrees;  ///< every `f` line's corner count, in order
    std::vector<std::size_t> faceLines;  ///< its line number
    std::vector<ObjCorner> corners;      ///< the `l` and `p` elements' corners
    std::vector<ObjPolyline> polylines;
    /// (object name, material name) of each run of lines and points.
    std::vector<std::pair<std::string, std::string>> groups;
};

/// Pass 1 (ObjScan.cpp). OBJ elements are numbered from 1 in messages, as the file's own indices
/// count them ("vertex 57", "face 12", with the line). Refuses, naming the line: a NUL byte, a number token on a v/vt/vn
/// line that is no number (nan, inf included), an index token that is not one (0, beyond
/// 2^31 - 1); turns `l`, `p`, `t` and `vw` lines into comments in `bytes`.
Result<ObjScan> scanObj(std::vector<unsigned char>& bytes, const Diagnostics& diag);

/// Charges what tinyobjloader will hold for a file of these counts, before it is called.
Result<void> chargeTinyobj(const ObjScan& scan, const Diagnostics& diag);

/// Reads MTL libraries for tinyobjloader, confined: a name must be a relative path inside the
/// OBJ's folder (or an allowed folder, where ".." may lead there), resolved to a regular file
/// within the budget. A missing library is a warning (the default material); any other refusal
/// is kept and ends the load (failure()).
class ConfinedMtlReader : public tinyobj::MaterialReader {
public:
    ConfinedMtlReader(std::filesystem::path folder, const LoadOptions& options,
                      const Diagnostics& diag)
        : m_folder(std::move(folder)), m_options(options), m_diag(diag) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string* warn,
                    std::string* err) override;
    const std::optional<Error>& failure() const { return m_failure; }
    /// The materials whose definition has an illum line.
    const std::set<std::string>& illum() const { return m_illum; }

private:
    std::filesystem::path m_folder;
    const LoadOptions& m_options;
    const Diagnostics& m_diag;
    std::optional<Error> m_failure;
    std::set<std::string> m_illum;
};

/// A name an OBJ or MTL file gives for another file (an MTL library, a texture), checked as a
/// glTF URI is: relative (no absolute path, no drive letter), no ".." unless folders are
/// allowed; backslashes read as slashes. Then resolved and read, confined (io/FileAccess.h).
/// Nothing: the file does not exist (the caller warns); an error for every other refusal.
Result<std::optional<std::vector<unsigned char>>> readNamedFile(
    const std::string& name, const std::string& object, const std::filesystem::path& folder,
    const LoadOptions& options, const Diagnostics& diag);

/// Pass 4 (ObjMaterials.cpp): the MTL materials as Lantern's classic materials, and the
/// textures they name (decoded once each) into `textures`. `illum`: the names of the materials
/// that state their illumination model (ConfinedMtlReader::illum). The materials that name
/// maps Lantern does not read are added to `skippedMaps` (for the fidelity report).
Result<std::vector<Material>> convertObjMaterials(const std::vector<tinyobj::material_t>& mtl,
                                                  const std::set<std::string>& illum,
                                                  const std::filesystem::path& folder,
                                                  const LoadOptions& options,
                                                  const Diagnostics& diag,
                                                  std::vector<Texture>& textures,
                                                  std::vector<std::string>& skippedMaps);

} // namespace lantern::mesh
