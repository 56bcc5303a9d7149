// OFF (Geomview's Object File Format) into the scene model: the OFF, COFF, NOFF, STOFF headers
// and their combinations ([ST][C][N]OFF), counts, vertices (x y z [nx ny nz] [r g b [a]]
// [s t]), faces of any degree with an optional colour after their indices. Colours written as
// integers are 0-255, as decimals 0-1 (Geomview's rule). '#' starts a comment. A file without
// faces is a point cloud. 4OFF, nOFF and OFF BINARY are refused.
#include "io/FileAccess.h"
#include "io/mesh/MeshInternal.h"
#include "io/mesh/MeshLoad.h"

#include <array>

namespace lantern::mesh {
namespace {

struct OffHeader {
    bool texcoords = false, colors = false, normals = false;
    std::uint64_t vertices = 0, faces = 0;
};

class OffReader {
public:
    OffReader(const std::vector<unsigned char>& bytes, const Diagnostics& diag)
        : m_text(bytes.data(), bytes.size(), 0, '#'), m_diag(diag) {}

    Result<Scene> read() {
        LANTERN_TRY(header());
        LANTERN_TRY(vertices());
        LANTERN_TRY(faces());
        return indexedScene("off", std::move(m_mesh), m_diag);
    }

private:
    Error refuse(const std::string& object, const std::string& message) const {
        return m_diag.error(object, message + " (line " + std::to_string(m_text.line()) + ")");
    }

    Result<std::uint64_t> count(std::string_view token, const char* what) {
        std::int64_t n = 0;
        if (!parseInteger(token, n) || n < 0)
            return refuse("header", std::string("the ") + what + " count \"" +
                                        io::printable(token, 40) + "\" is not an integer >= 0");
        return std::uint64_t(n);
    }

    Result<void> keyword(std::string_view word) {
        // [ST][C][N][4][n]OFF: what each vertex line carries besides x y z.
        std::string_view w = word;
        auto take = [&](std::string_view prefix) {
            const bool has = w.substr(0, prefix.size()) == prefix;
            if (has) w.remove_prefix(prefix.size());
            return has;
        };
        m_head.texcoords = take("ST");
        m_head.colors = take("C");
        m_head.normals = take("N");
        if (take("4") || take("n"))
            return refuse("header", "\"" + io::printable(word, 40) +
                                        "\": homogeneous and n-dimensional OFF are not read");
        if (w != "OFF") return refuse("header", "\"" + io::printable(word, 40) + "\" is not an OFF keyword");
        return {};
    }

    Result<void> header() {
        std::string_view t = m_text.next();
        if (t.empty()) return m_diag.error("header", "the file is empty");
        std::int64_t ignored = 0;
        if (!parseInteger(t, ignored)) {  // a file may leave the keyword out
            LANTERN_TRY(keyword(t));
            t = m_text.nextOnLine();
            if (t == "BINARY") return refuse("header", "OFF BINARY is not read");
            if (t.empty()) t = m_text.next();
        }
        auto v = count(t, "vertex");
        if (!v) return std::move(v).error();
        auto f = count(m_text.next(), "face");
        if (!f) return std::move(f).error();
        m_text.skipLine();  // the edge count, which nothing needs
        m_head.vertices = *v;
        m_head.faces = *f;
        // Each vertex takes 6 bytes at least ("0 0 0\n"), each face 2 ("0\n").
        const std::uint64_t rest = m_text.remaining();
        if (*v > rest / 6 || *f > rest / 2 || *v * 6 + *f * 2 > rest)
            return refuse("header", std::to_string(*v) + " vertices and " + std::to_string(*f) +
                                        " faces need more than the " + std::to_string(rest) +
                                        " bytes left in the file");
        if (*v > std::uint64_t(UINT32_MAX))
            return refuse("header", "more than 2^32 - 1 vertices");
        m_mesh.hasFaces = *f > 0;
        return {};
    }

    // c[0..n) as a colour: integers (every one written as such) 0-255, else decimals 0-1.
    Result<glm::vec4> colour(const double* c, std::size_t n, bool integers, const std::string& obj) {
        glm::vec4 rgba(1.0f);
        for (std::size_t i = 0; i < n; ++i) {
            const double value = integers ? c[i] / 255.0 : c[i];
            if (!(value >= 0.0 && value <= 1.0))
                return refuse(obj, "colour component " + shownNumber(c[i]) +
                                       (integers ? " is outside 0-255" : " is outside 0-1"));
            rgba[int(i)] = float(value);
        }
        return rgba;
    }

    // The numbers on the rest of a line (up to `limit`; more are ignored with a warning) into
    // `out`; bit i of `integers` set when number i was written as an integer.
    Result<std::size_t> lineNumbers(std::string_view first, double* out, std::size_t limit,
                                    std::uint32_t& integers, const std::string& obj) {
        std::size_t n = 0;
        integers = 0;
        for (std::string_view t = first; !t.empty(); t = m_text.nextOnLine()) {
            if (n == limit) {
                warnExtra(obj);
                break;
            }
            if (!parseNumber(t, out[n]))
                return refuse(obj, "\"" + io::printable(t, 40) + "\" is not a number");
            if (t.find_first_of(".eEnNiI") == std::string_view::npos) integers |= 1u << n;
            ++n;
        }
        m_text.skipLine();
        return n;
    }

    void warnExtra(const std::string& obj) {
        if (!m_warnedExtra) m_diag.warn(obj, "values beyond what the header declares are ignored");
        m_warnedExtra = true;
    }

    Result<void> vertex(std::uint64_t index) {
        const std::string obj = at("vertex", index);
        std::array<double, 12> v{};
        std::uint32_t integers = 0;
        const std::string_view first = m_text.next();
        if (first.empty()) return refuse(obj, "the file ends before it");
        auto n = lineNumbers(first, v.data(), v.size(), integers, obj);
        if (!n) return std::move(n).error();
        const std::size_t fixed = 3 + (m_head.normals ? 3 : 0) + (m_head.texcoords ? 2 : 0);
        const std::size_t colours = *n >= fixed ? *n - fixed : 0;
        if (*n < fixed || (m_head.colors && colours != 3 && colours != 4))
            return refuse(obj, std::to_string(*n) + " numbers; the header says each vertex has " +
                                   std::to_string(fixed) + (m_head.colors ? " and a colour of 3 or 4" : ""));
        if (!m_head.colors && colours > 0) warnExtra(obj);
        for (std::size_t i = 0; i < *n; ++i)
            if (!std::isfinite(v[i])) return refuse(obj, "value " + std::to_string(i) + " is not finite");
        m_mesh.positions.emplace_back(v[0], v[1], v[2]);
        std::size_t k = 3;
        if (m_head.normals) {
            m_mesh.normals.emplace_back(v[k], v[k + 1], v[k + 2]);
            k += 3;
        }
        if (m_head.colors) {
            const std::uint32_t mask = ((1u << colours) - 1u) << k;
            auto c = colour(v.data() + k, colours, (integers & mask) == mask, obj);
            if (!c) return std::move(c).error();
            m_mesh.colors.push_back(*c);
            k += colours;
        }
        if (m_head.texcoords) m_mesh.texcoords.emplace_back(float(v[k]), float(1.0 - v[k + 1]));
        return {};
    }

    Result<void> vertices() {
        const std::uint64_t each = sizeof(glm::vec3) + (m_head.normals ? sizeof(glm::vec3) : 0) +
                                   (m_head.colors ? sizeof(glm::vec4) : 0) +
                                   (m_head.texcoords ? sizeof(glm::vec2) : 0);
        LANTERN_TRY(m_diag.charge(m_head.vertices, each, "vertices",
                                  std::to_string(m_head.vertices) + " vertices"));
        m_mesh.positions.reserve(m_head.vertices);
        if (m_head.normals) m_mesh.normals.reserve(m_head.vertices);
        if (m_head.colors) m_mesh.colors.reserve(m_head.vertices);
        if (m_head.texcoords) m_mesh.texcoords.reserve(m_head.vertices);
        for (std::uint64_t i = 0; i < m_head.vertices; ++i) LANTERN_TRY(vertex(i));
        return {};
    }

    Result<void> faceColour(std::uint64_t index, const std::string& obj) {
        std::array<double, 4> c{};
        std::uint32_t integers = 0;
        const std::string_view first = m_text.nextOnLine();
        auto n = lineNumbers(first, c.data(), c.size(), integers, obj);
        if (!n) return std::move(n).error();
        if (*n == 0) return {};
        if (*n != 3 && *n != 4) {
            if (!m_warnedIndex) m_diag.warn(obj, "a colour of " + std::to_string(*n) +
                                                     " values (a colour map index?) is ignored");
            m_warnedIndex = true;
            return {};
        }
        auto rgba = colour(c.data(), *n, integers == (1u << *n) - 1u, obj);
        if (!rgba) return std::move(rgba).error();
        if (m_mesh.faceColors.empty()) {
            LANTERN_TRY(m_diag.charge(m_head.faces, sizeof(glm::vec4), "faces", "the faces' colours"));
            m_mesh.faceColors.assign(m_head.faces, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
        }
        m_mesh.faceColors[index] = *rgba;
        return {};
    }

    Result<void> face(std::uint64_t index, Triangulator& triangulator) {
        const std::string obj = at("face", index);
        const std::string_view t = m_text.next();
        std::int64_t degree = 0;
        if (t.empty()) return refuse(obj, "the file ends before it");
        if (!parseInteger(t, degree) || degree < 0)
            return refuse(obj, "the corner count \"" + io::printable(t, 40) + "\" is not an integer >= 0");
        if (std::uint64_t(degree) > m_text.remaining() / 2)
            return refuse(obj, std::to_string(degree) + " corners are more than the rest of the file holds");
        m_corners.clear();
        LANTERN_TRY(reserveCharged(m_corners, std::size_t(degree), m_diag, "faces"));
        for (std::int64_t c = 0; c < degree; ++c) {
            const std::string_view s = m_text.next();
            std::int64_t i = 0;
            if (!parseInteger(s, i) || i < 0 || std::uint64_t(i) >= m_head.vertices)
                return refuse(obj, "corner " + std::to_string(c) + ": \"" + io::printable(s, 40) +
                                       "\" is not a vertex index (0 to " +
                                       std::to_string(m_head.vertices) + " - 1)");
            m_corners.push_back(std::uint32_t(i));
        }
        LANTERN_TRY(faceColour(index, obj));
        const std::size_t triangles = degree >= 3 ? std::size_t(degree) - 2 : 0;
        LANTERN_TRY(reserveCharged(m_mesh.indices, 3 * triangles, m_diag, "faces"));
        LANTERN_TRY(reserveCharged(m_mesh.faceOfTriangle, triangles, m_diag, "faces"));
        const std::size_t made = triangulator.add(m_corners.data(), m_corners.size(), m_mesh.indices);
        m_mesh.faceOfTriangle.insert(m_mesh.faceOfTriangle.end(), made, std::uint32_t(index));
        return {};
    }

    Result<void> faces() {
        Triangulator triangulator(m_mesh.positions, m_diag);
        for (std::uint64_t i = 0; i < m_head.faces; ++i) LANTERN_TRY(face(i, triangulator));
        return {};
    }

    TextCursor m_text;
    const Diagnostics& m_diag;
    OffHeader m_head;
    IndexedMesh m_mesh;
    std::vector<std::uint32_t> m_corners;
    bool m_warnedExtra = false, m_warnedIndex = false;
};

} // namespace

Result<Scene> readOff(std::vector<unsigned char>& bytes, const LoadOptions&,
                      const Diagnostics& diag) {
    return OffReader(bytes, diag).read();
}

} // namespace lantern::mesh
