// ObjBuild.h: an OBJ primitive built from corners (only io/mesh/Obj*.cpp include this): each
// (v, vt, vn, smoothing) corner welded into one vertex, polygons triangulated, the normals a
// file leaves out made per smoothing group (faceted where smoothing is off).
#pragma once

#include "io/mesh/ObjInternal.h"

#include <cstdint>

namespace lantern::mesh {

/// One corner's key: what makes two corners the same vertex.
struct CornerKey {
    std::int32_t v = 0, vt = -1, vn = -1;
    std::uint32_t group = 0;  ///< smoothing group; faceted corners get no key at all
    bool operator==(const CornerKey&) const = default;
};

/// Open addressing from corner keys to vertex indices; its table is charged as it grows.
class CornerTable {
public:
    /// The vertex of `key`, or `next` (which the caller then creates) when it is new.
    Result<std::uint32_t> find(const CornerKey& key, std::uint32_t next, const Diagnostics& diag);

private:
    Result<void> grow(const Diagnostics& diag);
    struct Slot {
        CornerKey key;
        std::uint32_t value = UINT32_MAX;  ///< UINT32_MAX: empty
    };
    std::vector<Slot> m_slots;  ///< key and value side by side: one cache line per probe
    std::size_t m_count = 0;
};

/// Builds one primitive (triangles, lines or points) of one material from the file's corners.
class ObjPrimitive {
public:
    ObjPrimitive(const tinyobj::attrib_t& attrib, Topology topology, int material,
                 const Diagnostics& diag);
    ObjPrimitive(const ObjPrimitive&) = delete;  // its triangulator refers to its positions
    ObjPrimitive& operator=(const ObjPrimitive&) = delete;
    /// A polygon (triangulated), a polyline (its segments) or points, from corners already
    /// checked against the file's counts. `group`: the smoothing group, 0 when off.
    Result<void> polygon(const tinyobj::index_t* corners, std::size_t n, std::uint32_t group);
    Result<void> polyline(const ObjCorner* corners, std::size_t n);
    /// The primitive, with the normals the file leaves out computed.
    Result<Primitive> finish();
    int material() const { return m_prim.material; }

private:
    Result<std::uint32_t> vertex(const CornerKey& key, bool faceted);
    Result<void> room(std::size_t corners);
    const tinyobj::attrib_t& m_attrib;
    const Diagnostics& m_diag;
    Primitive m_prim;
    CornerTable m_table;
    std::vector<std::uint8_t> m_hasNormal;
    std::vector<std::uint32_t> m_local;
    Triangulator m_triangulator;
    bool m_anyTexcoord = false, m_anyMissingNormal = false;
};

} // namespace lantern::mesh
