// STL, binary and ASCII, into the scene model: flat facets (each facet its own three vertices
// with its normal; a normal that is zero, not finite or not unit length is recomputed from the
// vertices), one mesh per ASCII solid. A binary file is one whose size is 84 + 50 x the count
// at byte 80, whatever its header says (binary files often start with "solid" too).
#include "io/mesh/MeshInternal.h"
#include "io/mesh/MeshLoad.h"

#include "io/FileAccess.h"

#include <cctype>
#include <cstring>

namespace lantern::mesh {
namespace {

constexpr std::size_t kHeaderBytes = 84, kFacetBytes = 50;

std::uint32_t readU32(const unsigned char* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
           std::uint32_t(p[3]) << 24;
}

glm::vec3 readVec3(const unsigned char* p) {
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) {
        const std::uint32_t bits = readU32(p + 4 * i);
        float f;
        std::memcpy(&f, &bits, 4);
        v[i] = f;
    }
    return v;
}

/// Collects one mesh's flat facets and counts the normals it had to recompute.
struct FacetSink {
    Primitive prim;
    std::size_t recomputed = 0;

    /// A facet's corners (a fan when an ASCII facet has more than 3), all with one normal: the
    /// file's when it is unit length (within 1e-3), else the corners' own (zero when they are
    /// degenerate).
    void add(glm::vec3 normal, const glm::vec3* corners, std::size_t n) {
        const float length = glm::length(normal);
        if (!(std::abs(length - 1.0f) <= 1e-3f)) {
            ++recomputed;
            const glm::vec3 cross = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
            const float l = glm::length(cross);
            normal = l > 0.0f && std::isfinite(l) ? cross / l : glm::vec3(0.0f);
        } else {
            normal /= length;
        }
        for (std::size_t i = 1; i + 1 < n; ++i)
            for (const glm::vec3& p : {corners[0], corners[i], corners[i + 1]}) {
                prim.positions.push_back(p);
                prim.normals.push_back(normal);
            }
    }
};

Result<void> checkCorners(const glm::vec3* corners, std::size_t n, std::uint64_t facet,
                          const Diagnostics& diag) {
    for (std::size_t c = 0; c < n; ++c)
        if (!finite(corners[c]))
            return diag.error(at("facet", facet), "vertex " + std::to_string(c) +
                                                      " is not a finite number");
    return {};
}

void warnRecomputed(std::size_t recomputed, const Diagnostics& diag) {
    if (recomputed)
        diag.warn("facets", std::to_string(recomputed) +
                                " facet normal(s) were zero, not finite or not unit length: "
                                "recomputed from the vertices");
}

Result<Scene> loadBinary(const std::vector<unsigned char>& bytes, const Diagnostics& diag) {
    const std::uint32_t count = readU32(bytes.data() + 80);
    FacetSink sink;
    LANTERN_TRY(diag.charge(std::uint64_t(count) * 3, 2 * sizeof(glm::vec3), "facets",
                            std::to_string(count) + " facets' vertices"));
    sink.prim.positions.reserve(std::size_t(count) * 3);
    sink.prim.normals.reserve(std::size_t(count) * 3);
    for (std::uint32_t f = 0; f < count; ++f) {
        const unsigned char* p = bytes.data() + kHeaderBytes + std::size_t(f) * kFacetBytes;
        const glm::vec3 corners[3] = {readVec3(p + 12), readVec3(p + 24), readVec3(p + 36)};
        LANTERN_TRY(checkCorners(corners, 3, f, diag));
        sink.add(readVec3(p), corners, 3);
    }
    warnRecomputed(sink.recomputed, diag);
    Mesh mesh;
    mesh.name = std::filesystem::path(diag.file()).stem().string();
    mesh.primitives.push_back(std::move(sink.prim));
    std::vector<Mesh> meshes;
    meshes.push_back(std::move(mesh));
    return assembleScene("stl", std::move(meshes), {}, {}, diag);
}

bool keyword(std::string_view token, std::string_view word) {
    if (token.size() != word.size()) return false;
    for (std::size_t i = 0; i < token.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(token[i])) != word[i]) return false;
    return true;
}

/// The ASCII grammar, one facet at a time; lenient where exporters differ ("outer loop" and
/// "endloop" may be missing, a facet may have more than 3 vertices, a file may end without
/// "endsolid"), strict about numbers.
class AsciiReader {
public:
    AsciiReader(const std::vector<unsigned char>& bytes, const Diagnostics& diag)
        : m_text(bytes.data(), bytes.size()), m_diag(diag) {}

    Result<std::vector<Mesh>> read() {
        std::vector<Mesh> meshes;
        std::string_view t = m_text.next();
        while (!t.empty()) {
            if (!keyword(t, "solid")) return refuse("solid", "expected \"solid\", got", t);
            Mesh mesh;
            for (std::string_view w = m_text.nextOnLine(); !w.empty(); w = m_text.nextOnLine())
                mesh.name += (mesh.name.empty() ? "" : " ") + std::string(w.substr(0, 200));
            if (mesh.name.empty()) mesh.name = std::filesystem::path(m_diag.file()).stem().string();
            FacetSink sink;
            for (t = m_text.next(); keyword(t, "facet"); t = m_text.next())
                LANTERN_TRY(facet(sink));
            if (keyword(t, "endsolid")) {
                m_text.skipLine();
                t = m_text.next();
            } else if (!t.empty()) {
                return refuse(at("facet", m_facets), "expected \"facet\" or \"endsolid\", got", t);
            } else {
                m_diag.warn("solid \"" + mesh.name + "\"", "the file ends without \"endsolid\"");
            }
            warnRecomputed(sink.recomputed, m_diag);
            mesh.primitives.push_back(std::move(sink.prim));
            meshes.push_back(std::move(mesh));
        }
        return meshes;
    }

private:
    Error refuse(const std::string& object, const std::string& what, std::string_view got) const {
        return m_diag.error(object, what + " \"" + io::printable(got, 40) + "\" (line " +
                                        std::to_string(m_text.line()) + ")");
    }

    Result<glm::vec3> vec3(const std::string& object) {
        glm::vec3 v;
        for (int i = 0; i < 3; ++i) {
            const std::string_view t = m_text.next();
            double d = 0.0;
            if (!parseNumber(t, d)) return refuse(object, "expected a number, got", t);
            v[i] = float(d);
        }
        return v;
    }

    Result<void> facet(FacetSink& sink) {
        const std::string object = at("facet", m_facets);
        if (std::string_view t = m_text.next(); !keyword(t, "normal"))
            return refuse(object, "expected \"normal\", got", t);
        auto normal = vec3(object);
        if (!normal) return std::move(normal).error();
        std::string_view t = m_text.next();
        if (keyword(t, "outer")) {
            if (t = m_text.next(); !keyword(t, "loop"))
                return refuse(object, "expected \"loop\", got", t);
            t = m_text.next();
        }
        m_corners.clear();
        for (; keyword(t, "vertex"); t = m_text.next()) {
            auto v = vec3(object);
            if (!v) return std::move(v).error();
            m_corners.push_back(*v);
        }
        if (keyword(t, "endloop")) t = m_text.next();
        if (!keyword(t, "endfacet")) return refuse(object, "expected \"endfacet\", got", t);
        if (m_corners.size() < 3)
            return m_diag.error(object, std::to_string(m_corners.size()) +
                                            " vertices; a facet needs 3 (line " +
                                            std::to_string(m_text.line()) + ")");
        LANTERN_TRY(checkCorners(m_corners.data(), m_corners.size(), m_facets, m_diag));
        const std::size_t added = 3 * (m_corners.size() - 2);
        LANTERN_TRY(reserveCharged(sink.prim.positions, added, m_diag, "facets"));
        LANTERN_TRY(reserveCharged(sink.prim.normals, added, m_diag, "facets"));
        sink.add(*normal, m_corners.data(), m_corners.size());
        ++m_facets;
        return {};
    }

    TextCursor m_text;
    const Diagnostics& m_diag;
    std::vector<glm::vec3> m_corners;
    std::uint64_t m_facets = 0;
};

} // namespace

Result<Scene> readStl(std::vector<unsigned char>& bytes, const LoadOptions&,
                      const Diagnostics& diag) {
    if (looksLikeBinaryStl(bytes.data(), bytes.size(), bytes.size())) return loadBinary(bytes, diag);
    TextCursor probe(bytes.data(), bytes.size());
    if (!keyword(probe.next(), "solid")) {
        const std::string count = bytes.size() >= kHeaderBytes
                                      ? std::to_string(readU32(bytes.data() + 80))
                                      : std::string("none");
        return diag.error("", "neither a binary STL (84 + 50 x N bytes, N the count at byte 80: " +
                                  count + "; the file has " + std::to_string(bytes.size()) +
                                  " bytes) nor an ASCII one (it does not start with \"solid\")");
    }
    auto meshes = AsciiReader(bytes, diag).read();
    if (!meshes) return std::move(meshes).error();
    return assembleScene("stl", std::move(*meshes), {}, {}, diag);
}

bool looksLikeBinaryStl(const unsigned char* head, std::size_t headSize, std::uint64_t size) {
    if (headSize < kHeaderBytes || size < kHeaderBytes) return false;
    return kHeaderBytes + kFacetBytes * std::uint64_t(readU32(head + 80)) == size;
}

} // namespace lantern::mesh
