// OBJ corners into vertices and primitives (io/mesh/ObjBuild.h).
#include "io/mesh/ObjBuild.h"

#include <climits>

namespace lantern::mesh {
namespace {

std::uint64_t hashOf(const CornerKey& k) {
    std::uint64_t h = (std::uint64_t(std::uint32_t(k.v)) << 32) ^ std::uint32_t(k.vt);
    h ^= (std::uint64_t(std::uint32_t(k.vn)) << 32 | k.group) * 0x9E3779B97F4A7C15ull;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 29);
}

constexpr std::uint32_t kEmpty = UINT32_MAX;

} // namespace

Result<void> CornerTable::grow(const Diagnostics& diag) {
    const std::size_t size = std::max<std::size_t>(1024, m_slots.size() * 2);
    LANTERN_TRY(diag.charge(size, sizeof(Slot), "faces", "welding the corners into vertices"));
    std::vector<Slot> slots(size);
    for (const Slot& old : m_slots) {
        if (old.value == kEmpty) continue;
        std::size_t j = hashOf(old.key) & (size - 1);
        while (slots[j].value != kEmpty) j = (j + 1) & (size - 1);
        slots[j] = old;
    }
    diag.release(m_slots.size() * sizeof(Slot));
    m_slots = std::move(slots);
    return {};
}

Result<std::uint32_t> CornerTable::find(const CornerKey& key, std::uint32_t next,
                                        const Diagnostics& diag) {
    if (2 * (m_count + 1) > m_slots.size()) LANTERN_TRY(grow(diag));
    const std::size_t mask = m_slots.size() - 1;
    for (std::size_t j = hashOf(key) & mask;; j = (j + 1) & mask) {
        Slot& slot = m_slots[j];
        if (slot.value == kEmpty) {
            slot = Slot{key, next};
            ++m_count;
            return next;
        }
        if (slot.key == key) return slot.value;
    }
}

ObjPrimitive::ObjPrimitive(const tinyobj::attrib_t& attrib, Topology topology, int material,
                           const Diagnostics& diag)
    : m_attrib(attrib), m_diag(diag), m_triangulator(m_prim.positions, diag) {
    m_prim.topology = topology;
    m_prim.material = material;
}

Result<void> ObjPrimitive::room(std::size_t corners) {
    const char* obj = "faces";
    LANTERN_TRY(reserveCharged(m_prim.positions, corners, m_diag, obj));
    LANTERN_TRY(reserveCharged(m_prim.normals, corners, m_diag, obj));
    LANTERN_TRY(reserveCharged(m_prim.texcoords, corners, m_diag, obj));
    LANTERN_TRY(reserveCharged(m_hasNormal, corners, m_diag, obj));
    if (!m_attrib.colors.empty()) LANTERN_TRY(reserveCharged(m_prim.colors, corners, m_diag, obj));
    return reserveCharged(m_local, corners, m_diag, obj);
}

Result<std::uint32_t> ObjPrimitive::vertex(const CornerKey& key, bool faceted) {
    const auto next = std::uint32_t(m_prim.positions.size());
    if (next == UINT32_MAX) return m_diag.error("faces", "more than 2^32 - 1 vertices in one primitive");
    if (!faceted) {
        auto found = m_table.find(key, next, m_diag);
        if (!found || *found != next) return found;
    }
    const float* p = &m_attrib.vertices[3 * std::size_t(key.v)];
    m_prim.positions.emplace_back(p[0], p[1], p[2]);
    if (!m_attrib.colors.empty()) {
        const float* c = &m_attrib.colors[3 * std::size_t(key.v)];
        m_prim.colors.emplace_back(c[0], c[1], c[2], 1.0f);
    }
    if (key.vt >= 0) {
        const float* t = &m_attrib.texcoords[2 * std::size_t(key.vt)];
        m_prim.texcoords.emplace_back(t[0], 1.0f - t[1]);  // OBJ's v grows upwards
        m_anyTexcoord = true;
    } else {
        m_prim.texcoords.emplace_back(0.0f, 0.0f);
    }
    if (key.vn >= 0) {
        const float* n = &m_attrib.normals[3 * std::size_t(key.vn)];
        m_prim.normals.emplace_back(n[0], n[1], n[2]);
    } else {
        m_prim.normals.emplace_back(0.0f);
        m_anyMissingNormal = true;
    }
    m_hasNormal.push_back(key.vn >= 0);
    return next;
}

Result<void> ObjPrimitive::polygon(const tinyobj::index_t* corners, std::size_t n,
                                   std::uint32_t group) {
    LANTERN_TRY(room(n));
    m_local.clear();
    for (std::size_t i = 0; i < n; ++i) {
        const tinyobj::index_t& c = corners[i];
        // Smoothing off and no normal: the corner is the face's own (a faceted face).
        const bool faceted = c.normal_index < 0 && group == 0;
        const CornerKey key{c.vertex_index, c.texcoord_index, c.normal_index,
                            c.normal_index >= 0 ? 0u : group};
        auto v = vertex(key, faceted);
        if (!v) return std::move(v).error();
        m_local.push_back(*v);
    }
    const std::size_t triangles = n >= 3 ? n - 2 : 0;
    LANTERN_TRY(reserveCharged(m_prim.indices, 3 * triangles, m_diag, "faces"));
    m_triangulator.add(m_local.data(), n, m_prim.indices);
    return {};
}

Result<void> ObjPrimitive::polyline(const ObjCorner* corners, std::size_t n) {
    LANTERN_TRY(room(n));
    m_local.clear();
    for (std::size_t i = 0; i < n; ++i) {
        auto v = vertex(CornerKey{std::int32_t(corners[i].v), std::int32_t(corners[i].vt), -1, 0}, false);
        if (!v) return std::move(v).error();
        m_local.push_back(*v);
    }
    const bool points = m_prim.topology == Topology::Points;
    const std::size_t elements = points ? n : n >= 2 ? 2 * (n - 1) : 0;
    LANTERN_TRY(reserveCharged(m_prim.indices, elements, m_diag, points ? "points" : "lines"));
    for (std::size_t i = 0; i < n; ++i) {
        if (points) {
            m_prim.indices.push_back(m_local[i]);
        } else if (i + 1 < n) {
            m_prim.indices.push_back(m_local[i]);
            m_prim.indices.push_back(m_local[i + 1]);
        }
    }
    return {};
}

Result<Primitive> ObjPrimitive::finish() {
    if (!m_anyTexcoord) m_prim.texcoords.clear();
    if (m_prim.topology != Topology::Triangles) {
        m_prim.normals.clear();  // lines and points name no normals: drawn unlit
    } else if (m_anyMissingNormal) {
        // Welded per smoothing group, faceted corners apart: angle-weighted normals over the
        // primitive are smooth within a group and the face's own elsewhere.
        LANTERN_TRY(m_diag.charge(m_prim.positions.size(), sizeof(glm::dvec3) + sizeof(glm::vec3),
                                  "faces", "computing the normals"));
        const std::vector<glm::vec3> computed = computeSmoothNormals(m_prim.positions, m_prim.indices);
        for (std::size_t i = 0; i < computed.size(); ++i)
            if (!m_hasNormal[i]) m_prim.normals[i] = computed[i];
    }
    return std::move(m_prim);
}

} // namespace lantern::mesh
