// MeshInternal.h: what the mesh formats' readers share (only engine/src/io/mesh/ includes it):
// the scene file read and charged, growth charged to the load's budget, polygons
// triangulated in linear time (ear clipping within a budget), a text cursor for the ASCII
// formats, per-face colours spread onto corners, and the scene assembled from meshes.
#pragma once

#include "io/LoadDiagnostics.h"
#include "io/mesh/MeshLoad.h"

#include <lantern/FileOptions.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::mesh {

using io::Diagnostics;

/// "vertex 57", "face 12": the object of a message, 0-based as the file's elements count.
std::string at(const char* what, std::uint64_t index);


/// Makes room in `v` for `extra` more elements, charging the new block to the budget before it
/// is allocated (and returning the old one's bytes): a vector that grows with what the file
/// says is bounded like any other allocation. Doubles, so pushes stay amortised linear.
template <class T>
Result<void> reserveCharged(std::vector<T>& v, std::size_t extra, const Diagnostics& diag,
                            const char* object) {
    if (v.capacity() - v.size() >= extra) return {};
    const std::size_t want = std::max(v.size() + extra, v.capacity() * 2);
    LANTERN_TRY(diag.charge(want, sizeof(T), object, "the data read"));
    diag.release(std::uint64_t(v.capacity()) * sizeof(T));
    v.reserve(want);
    return {};
}

/// Polygons to triangles, for every format. 3 corners as they are; 4 by the shorter diagonal;
/// more: a fan when the polygon is convex in its plane (Newell's normal), else ear clipping,
/// whose quadratic work is bounded per load (kEarClipBudget steps): beyond it a concave polygon
/// is fanned, with one warning. So a polygon of any degree costs linear time.
class Triangulator {
public:
    static constexpr std::uint64_t kEarClipBudget = std::uint64_t(1) << 26;
    Triangulator(const std::vector<glm::vec3>& positions, const Diagnostics& diag)
        : m_positions(positions), m_diag(diag) {}
    /// Appends the triangles of the polygon whose corners are `corners[0..n)` (indices into the
    /// positions, checked by the caller) to `out`; returns how many. Fewer than 3 corners: 0.
    std::size_t add(const std::uint32_t* corners, std::size_t n, std::vector<std::uint32_t>& out);

private:
    bool convex(const std::uint32_t* corners, std::size_t n, const glm::dvec3& normal) const;
    std::size_t earClip(const std::uint32_t* corners, std::size_t n, const glm::dvec3& normal,
                        std::vector<std::uint32_t>& out);
    const std::vector<glm::vec3>& m_positions;
    const Diagnostics& m_diag;
    std::uint64_t m_earWork = 0;
    bool m_warned = false;
};

/// True when every component is finite.
inline bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// A primitive whose triangles came from faces with colours of their own: each triangle's
/// three corners become vertices of their own, carrying the face's colour (`faceOfTriangle`
/// names each triangle's face, `faceColors` each face's colour). Normals (computed on the
/// indexed mesh before) and the other attributes are copied per corner; indices are dropped.
Result<void> spreadFaceColors(Primitive& prim, const std::vector<std::uint32_t>& faceOfTriangle,
                              const std::vector<glm::vec4>& faceColors, const Diagnostics& diag);

/// Fills `prim.normals` for a triangle primitive without them: angle-weighted vertex normals
/// over its indexed triangles (computeSmoothNormals), charged first.
Result<void> addSmoothNormals(Primitive& prim, const Diagnostics& diag);

/// What an indexed format (PLY, OFF) read: vertex streams (each empty or one per vertex),
/// triangles, and the faces' own colours (alpha < 0: the face has none).
struct IndexedMesh {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec4> colors;
    std::vector<glm::vec2> texcoords;
    std::vector<std::uint32_t> indices;         ///< triangles
    std::vector<std::uint32_t> faceOfTriangle;  ///< the face each triangle came from
    std::vector<glm::vec4> faceColors;          ///< empty, or one per face
    bool hasFaces = false;  ///< false: a point cloud (Topology::Points)
};

/// The scene of an indexed format: one mesh of one primitive, triangles (normals computed when
/// the file has none; faces with colours of their own spread onto their corners) or, for a file
/// without faces, points. `formatKey`: the format's fidelity key (as assembleScene).
Result<Scene> indexedScene(std::string_view formatKey, IndexedMesh m, const Diagnostics& diag);

/// The scene of a mesh file: one root named after the file with a node per mesh (empty meshes
/// are left out), the materials and textures given; then Scene::validate(), errors naming the
/// file. The fidelity report (Scene::features) notes the format by `formatKey` ("obj", "ply",
/// "stl", "off") and what the materials and meshes use (textures, blending, points and lines).
Result<Scene> assembleScene(std::string_view formatKey, std::vector<Mesh> meshes,
                            std::vector<Material> materials, std::vector<Texture> textures,
                            const Diagnostics& diag);

/// The ASCII formats' reader: whitespace-separated tokens with their line numbers (1-based), a
/// comment character that hides the rest of a line, lines kept apart when asked.
class TextCursor {
public:
    TextCursor(const unsigned char* data, std::size_t size, std::size_t pos = 0, char comment = 0)
        : m_data(data), m_size(size), m_pos(pos), m_comment(comment) {}
    /// The next token anywhere ahead (empty at the end).
    std::string_view next();
    /// The next token on this line; empty at its end (the cursor stays there: skipLine goes on).
    std::string_view nextOnLine();
    /// Skips the rest of the current line.
    void skipLine();
    bool atEnd();
    std::size_t line() const { return m_line; }
    std::size_t pos() const { return m_pos; }
    std::size_t remaining() const { return m_size - m_pos; }

private:
    /// Skips blanks (and newlines unless `stayOnLine`) and comments; false at a line end when
    /// staying on the line, or at the end of the data.
    bool skipSpace(bool stayOnLine);
    std::string_view token();
    const unsigned char* m_data;
    std::size_t m_size, m_pos;
    char m_comment;
    std::size_t m_line = 1;
};

/// A number as a message shows it: "9000", "0.25", "nan" (%.17g, so an integer reads as one).
std::string shownNumber(double value);

/// A decimal number (std::from_chars: "1", "-2.5e3", "nan", "inf"), the whole token; false
/// when the token is not one. Callers refuse non-finite values with the element named.
bool parseNumber(std::string_view token, double& out);
/// A decimal integer, the whole token; false when it is not one or not in int64's range.
bool parseInteger(std::string_view token, std::int64_t& out);

} // namespace lantern::mesh
