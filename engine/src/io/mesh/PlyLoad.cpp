// PLY (ASCII, binary little- and big-endian) into the scene model: the vertex element's
// x y z, nx ny nz, colours (red green blue [alpha]: integers divided by their type's maximum,
// decimals as they are) and texture coordinates (u v, s t, texture_u texture_v, texture_s
// texture_t), the face element's vertex_indices (or vertex_index) lists of any degree and
// integer types, and its red green blue [alpha] when present. Other elements are skipped with
// a warning. A file without a face element is a point cloud.
#include "io/FileAccess.h"
#include "io/mesh/MeshLoad.h"
#include "io/mesh/PlyHeader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <span>

namespace lantern::mesh {
namespace {

/// Reads values from the body, in the file's format; every read is bounds-checked.
class PlyValues {
public:
    PlyValues(const std::vector<unsigned char>& bytes, const PlyHeader& h)
        : m_bytes(bytes), m_format(h.format), m_pos(h.bodyOffset),
          m_text(bytes.data(), bytes.size(), h.bodyOffset) {}

    /// The next value as a double; false at the end of the data or on a token that is no number.
    bool read(PlyType type, double& out) {
        if (m_format == PlyFormat::Ascii) return parseNumber(m_text.next(), out);
        const std::size_t n = plySize(type);
        if (m_bytes.size() - m_pos < n) return false;
        unsigned char b[8];
        std::memcpy(b, m_bytes.data() + m_pos, n);
        m_pos += n;
        if (m_format == PlyFormat::BinaryBigEndian) std::reverse(b, b + n);
        out = decode(type, b);
        return true;
    }
    std::size_t remaining() const {
        return m_format == PlyFormat::Ascii ? m_text.remaining() : m_bytes.size() - m_pos;
    }
    /// Where the reader is, for messages: "line N" in ASCII, "byte N" in binary.
    std::string where() const {
        return m_format == PlyFormat::Ascii ? "line " + std::to_string(m_text.line())
                                            : "byte " + std::to_string(m_pos);
    }

private:
    static double decode(PlyType type, const unsigned char* b) {
        auto get = [b](auto v) {
            std::memcpy(&v, b, sizeof v);
            return double(v);
        };
        switch (type) {
        case PlyType::I8: return get(std::int8_t());
        case PlyType::U8: return get(std::uint8_t());
        case PlyType::I16: return get(std::int16_t());
        case PlyType::U16: return get(std::uint16_t());
        case PlyType::I32: return get(std::int32_t());
        case PlyType::U32: return get(std::uint32_t());
        case PlyType::F32: return get(float());
        case PlyType::F64: return get(double());
        }
        return 0.0;
    }
    const std::vector<unsigned char>& m_bytes;
    PlyFormat m_format;
    std::size_t m_pos;
    TextCursor m_text;
};

/// What a vertex or face property is read into.
enum class Role : std::uint8_t { Skip, X, Y, Z, NX, NY, NZ, R, G, B, A, U, V, Indices };
constexpr std::size_t kRoles = std::size_t(Role::Indices) + 1;

Role roleOf(const std::string& name, bool face) {
    static const std::pair<const char*, Role> kVertex[] = {
        {"x", Role::X}, {"y", Role::Y}, {"z", Role::Z}, {"nx", Role::NX}, {"ny", Role::NY},
        {"nz", Role::NZ}, {"red", Role::R}, {"green", Role::G}, {"blue", Role::B},
        {"alpha", Role::A}, {"diffuse_red", Role::R}, {"diffuse_green", Role::G},
        {"diffuse_blue", Role::B}, {"u", Role::U}, {"v", Role::V}, {"s", Role::U},
        {"t", Role::V}, {"texture_u", Role::U}, {"texture_v", Role::V}, {"texture_s", Role::U},
        {"texture_t", Role::V}};
    static const std::pair<const char*, Role> kFace[] = {
        {"vertex_indices", Role::Indices}, {"vertex_index", Role::Indices}, {"red", Role::R},
        {"green", Role::G}, {"blue", Role::B}, {"alpha", Role::A}};
    using Names = std::span<const std::pair<const char*, Role>>;
    for (const auto& [n, r] : face ? Names(kFace) : Names(kVertex))
        if (name == n) return r;
    return Role::Skip;
}

/// The largest value of an integer colour type (the divisor that maps it to 0-1); 1 for decimals.
double colourScale(PlyType t) {
    switch (t) {
    case PlyType::U8: case PlyType::I8: return 255.0;
    case PlyType::U16: case PlyType::I16: return 65535.0;
    case PlyType::U32: case PlyType::I32: return 4294967295.0;
    default: return 1.0;
    }
}

class PlyReader {
public:
    PlyReader(const std::vector<unsigned char>& bytes, PlyHeader header, const Diagnostics& diag)
        : m_header(std::move(header)), m_values(bytes, m_header), m_diag(diag) {}

    Result<Scene> read() {
        for (const PlyElement& e : m_header.elements) {
            if (e.name == "vertex") LANTERN_TRY(vertices(e));
            else if (e.name == "face") LANTERN_TRY(faces(e));
            else LANTERN_TRY(skip(e));
        }
        if (m_vertexElement < 0) return m_diag.error("header", "has no vertex element");
        return indexedScene("ply", std::move(m_mesh), m_diag);
    }

private:
    Error refuse(const std::string& object, const std::string& message) const {
        return m_diag.error(object, message + " (" + m_values.where() + ")");
    }

    /// The next value of `type`, in record `index` of element `e` (named only in an error).
    Result<double> value(PlyType type, const PlyElement& e, std::uint64_t index) {
        double v = 0.0;
        if (!m_values.read(type, v))
            return refuse(element(e, index), m_values.remaining() ? "a value is not a number"
                                                                  : "the file ends inside it");
        return v;
    }

    Result<std::uint64_t> listCount(const PlyProperty& p, const PlyElement& e, std::uint64_t index) {
        auto n = value(p.countType, e, index);
        if (!n) return std::move(n).error();
        // Each entry takes a byte at least: so many never fit in the rest of the file.
        if (!(*n >= 0.0) || *n != std::floor(*n) || *n > double(m_values.remaining()))
            return refuse(element(e, index), "list \"" + p.name + "\" has " + shownNumber(*n) +
                                                 " entries, not a count the rest of the file can hold");
        return std::uint64_t(*n);
    }

    /// Reads past property `p` (a value, or a whole list) of record `index`.
    Result<void> skipProperty(const PlyProperty& p, const PlyElement& e, std::uint64_t index) {
        std::uint64_t n = 1;
        if (p.list) {
            auto c = listCount(p, e, index);
            if (!c) return std::move(c).error();
            n = *c;
        }
        for (std::uint64_t k = 0; k < n; ++k)
            if (auto v = value(p.type, e, index); !v) return std::move(v).error();
        return {};
    }

    Result<void> skip(const PlyElement& e) {
        if (e.properties.empty()) return {};
        if (e.count > 0)
            m_diag.warn(element(e, 0).substr(0, element(e, 0).size() - 2),
                        "element skipped (" + std::to_string(e.count) + " records)");
        for (std::uint64_t i = 0; i < e.count; ++i)
            for (const PlyProperty& p : e.properties) LANTERN_TRY(skipProperty(p, e, i));
        return {};
    }

    static std::string element(const PlyElement& e, std::uint64_t index) {
        return io::printable(e.name, 40) + " " + std::to_string(index);
    }

    Result<void> prepareVertices(const PlyElement& e, std::array<PlyType, kRoles>& types);
    Result<void> vertices(const PlyElement& e);
    Result<void> storeVertex(const std::array<double, kRoles>& v, std::uint64_t index);
    Result<void> faces(const PlyElement& e);
    Result<void> face(const PlyElement& e, const std::vector<Role>& roles, std::uint64_t index,
                      Triangulator& triangulator);

    PlyHeader m_header;
    PlyValues m_values;
    const Diagnostics& m_diag;
    IndexedMesh m_mesh;
    int m_vertexElement = -1;
    std::uint64_t m_vertexCount = 0;
    bool m_normals = false, m_colors = false, m_alpha = false, m_texcoords = false;
    std::array<double, kRoles> m_scale{};  ///< colour divisors per role
    std::vector<std::uint32_t> m_corners;
};

Result<void> PlyReader::prepareVertices(const PlyElement& e, std::array<PlyType, kRoles>& types) {
    std::array<bool, kRoles> has{};
    for (const PlyProperty& p : e.properties) {
        const Role r = roleOf(p.name, false);
        if (r == Role::Skip) continue;
        if (p.list) return m_diag.error("header", "vertex property \"" + p.name + "\" is a list");
        has[std::size_t(r)] = true;
        types[std::size_t(r)] = p.type;
        m_scale[std::size_t(r)] = colourScale(p.type);
    }
    auto all = [&](std::initializer_list<Role> roles, const char* what) -> Result<bool> {
        std::size_t n = 0;
        for (Role r : roles) n += has[std::size_t(r)];
        if (n != 0 && n != roles.size())
            return m_diag.error("header", std::string("the vertex element has some of ") + what + " but not all");
        return n != 0;
    };
    auto xyz = all({Role::X, Role::Y, Role::Z}, "x, y, z");
    auto normals = all({Role::NX, Role::NY, Role::NZ}, "nx, ny, nz");
    auto colors = all({Role::R, Role::G, Role::B}, "red, green, blue");
    auto uv = all({Role::U, Role::V}, "the texture coordinates (u v, s t, texture_u texture_v)");
    for (auto* r : {&xyz, &normals, &colors, &uv})
        if (!*r) return std::move(*r).error();
    if (!*xyz) return m_diag.error("header", "the vertex element has no x, y, z");
    m_normals = *normals;
    m_colors = *colors;
    m_alpha = *colors && has[std::size_t(Role::A)];
    m_texcoords = *uv;
    return {};
}

Result<void> PlyReader::vertices(const PlyElement& e) {
    if (m_vertexElement >= 0) return m_diag.error("header", "has two vertex elements");
    m_vertexElement = int(&e - m_header.elements.data());
    m_vertexCount = e.count;
    if (e.count > std::uint64_t(UINT32_MAX)) return m_diag.error("header", "more than 2^32 - 1 vertices");
    std::array<PlyType, kRoles> types{};
    LANTERN_TRY(prepareVertices(e, types));
    const std::uint64_t each = sizeof(glm::vec3) + (m_normals ? sizeof(glm::vec3) : 0) +
                               (m_colors ? sizeof(glm::vec4) : 0) + (m_texcoords ? sizeof(glm::vec2) : 0);
    LANTERN_TRY(m_diag.charge(e.count, each, "vertices", std::to_string(e.count) + " vertices"));
    m_mesh.positions.reserve(e.count);
    if (m_normals) m_mesh.normals.reserve(e.count);
    if (m_colors) m_mesh.colors.reserve(e.count);
    if (m_texcoords) m_mesh.texcoords.reserve(e.count);
    std::vector<Role> roles;
    for (const PlyProperty& p : e.properties) roles.push_back(roleOf(p.name, false));
    std::array<double, kRoles> v{};
    for (std::uint64_t i = 0; i < e.count; ++i) {
        for (std::size_t k = 0; k < roles.size(); ++k) {
            const PlyProperty& p = e.properties[k];
            if (p.list || roles[k] == Role::Skip) {  // lists are never a vertex's own (checked)
                LANTERN_TRY(skipProperty(p, e, i));
                continue;
            }
            auto x = value(p.type, e, i);
            if (!x) return std::move(x).error();
            v[std::size_t(roles[k])] = *x;
        }
        LANTERN_TRY(storeVertex(v, i));
    }
    return {};
}

Result<void> PlyReader::storeVertex(const std::array<double, kRoles>& v, std::uint64_t index) {
    auto get = [&](Role r) { return v[std::size_t(r)]; };
    const glm::vec3 p(get(Role::X), get(Role::Y), get(Role::Z));
    if (!finite(p)) return refuse(at("vertex", index), "x, y, z are not finite");
    m_mesh.positions.push_back(p);
    if (m_normals) {
        const glm::vec3 n(get(Role::NX), get(Role::NY), get(Role::NZ));
        if (!finite(n)) return refuse(at("vertex", index), "nx, ny, nz are not finite");
        m_mesh.normals.push_back(n);
    }
    if (m_colors) {
        glm::vec4 c(1.0f);
        for (Role r : {Role::R, Role::G, Role::B, Role::A}) {
            if (r == Role::A && !m_alpha) break;
            const double x = get(r) / m_scale[std::size_t(r)];
            if (!(x >= 0.0 && x <= 1.0))
                return refuse(at("vertex", index), "colour component " + shownNumber(get(r)) +
                                                       " is outside its range (0-1, or 0 to the integer type's maximum)");
            c[int(r) - int(Role::R)] = float(x);
        }
        m_mesh.colors.push_back(c);
    }
    if (m_texcoords) {
        const glm::vec2 uv(get(Role::U), 1.0 - get(Role::V));  // PLY's v grows upwards
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
            return refuse(at("vertex", index), "texture coordinates are not finite");
        m_mesh.texcoords.push_back(uv);
    }
    return {};
}

Result<void> PlyReader::faces(const PlyElement& e) {
    if (m_vertexElement < 0)
        return m_diag.error("header", "the face element comes before the vertex element");
    std::vector<Role> roles;
    std::array<bool, kRoles> has{};
    for (const PlyProperty& p : e.properties) {
        roles.push_back(roleOf(p.name, true));
        if (roles.back() == Role::Indices && (!p.list || !plyInteger(p.type)))
            return m_diag.error("header", "face property \"" + p.name + "\" is not a list of integers");
        if (roles.back() != Role::Indices && roles.back() != Role::Skip && p.list) roles.back() = Role::Skip;
        has[std::size_t(roles.back())] = true;
        m_scale[std::size_t(roles.back())] = colourScale(p.type);
    }
    if (!has[std::size_t(Role::Indices)])
        return m_diag.error("header", "the face element has no vertex_indices list");
    m_mesh.hasFaces = e.count > 0;  // "element face 0": a point cloud, as many scanners write
    if (has[std::size_t(Role::R)] && has[std::size_t(Role::G)] && has[std::size_t(Role::B)]) {
        LANTERN_TRY(m_diag.charge(e.count, sizeof(glm::vec4), "faces", "the faces' colours"));
        m_mesh.faceColors.assign(e.count, glm::vec4(1.0f));
    } else {
        std::replace_if(roles.begin(), roles.end(), [](Role r) { return r != Role::Indices; }, Role::Skip);
    }
    Triangulator triangulator(m_mesh.positions, m_diag);
    for (std::uint64_t i = 0; i < e.count; ++i) LANTERN_TRY(face(e, roles, i, triangulator));
    if (m_mesh.faceColors.empty()) m_mesh.faceOfTriangle.clear();
    return {};
}

Result<void> PlyReader::face(const PlyElement& e, const std::vector<Role>& roles,
                             std::uint64_t index, Triangulator& triangulator) {
    for (std::size_t k = 0; k < roles.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        if (roles[k] == Role::Skip) {
            LANTERN_TRY(skipProperty(p, e, index));
        } else if (roles[k] != Role::Indices) {
            auto c = value(p.type, e, index);
            if (!c) return std::move(c).error();
            const double x = *c / m_scale[std::size_t(roles[k])];
            if (!(x >= 0.0 && x <= 1.0))
                return refuse(at("face", index), "colour component " + shownNumber(*c) + " is outside its range");
            m_mesh.faceColors[index][int(roles[k]) - int(Role::R)] = float(x);
        } else {
            auto n = listCount(p, e, index);
            if (!n) return std::move(n).error();
            m_corners.clear();
            LANTERN_TRY(reserveCharged(m_corners, std::size_t(*n), m_diag, "faces"));
            for (std::uint64_t c = 0; c < *n; ++c) {
                auto v = value(p.type, e, index);
                if (!v) return std::move(v).error();
                if (!(*v >= 0.0) || *v >= double(m_vertexCount) || *v != std::floor(*v))
                    return refuse(at("face", index), "corner " + std::to_string(c) + " is " + shownNumber(*v) +
                                                         ", not a vertex index (0 to " + std::to_string(m_vertexCount) + " - 1)");
                m_corners.push_back(std::uint32_t(*v));
            }
        }
    }
    const std::size_t triangles = m_corners.size() >= 3 ? m_corners.size() - 2 : 0;
    LANTERN_TRY(reserveCharged(m_mesh.indices, 3 * triangles, m_diag, "faces"));
    LANTERN_TRY(reserveCharged(m_mesh.faceOfTriangle, triangles, m_diag, "faces"));
    const std::size_t made = triangulator.add(m_corners.data(), m_corners.size(), m_mesh.indices);
    m_mesh.faceOfTriangle.insert(m_mesh.faceOfTriangle.end(), made, std::uint32_t(index));
    return {};
}

} // namespace

Result<Scene> readPly(std::vector<unsigned char>& bytes, const LoadOptions&,
                      const Diagnostics& diag) {
    auto header = readPlyHeader(bytes, diag);
    if (!header) return std::move(header).error();
    return PlyReader(bytes, std::move(*header), diag).read();
}

} // namespace lantern::mesh
