// Reads a Draco mesh stream's header and connectivity counts without decoding it, so that the
// counts can be checked against the glTF accessors before draco::Decoder allocates for them
// (the decoder trusts a stream's face count enough to allocate a corner table for it). The
// layout follows draco 1.5's decoders for bitstream 2.0-2.2: header, optional metadata, then the
// sequential or edgebreaker connectivity header.
#include "io/gltf/GltfInternal.h"

#include <cstring>

namespace lantern::gltf {
namespace {

constexpr std::uint16_t kMetadataFlag = 0x8000;
/// Deeper metadata nesting is refused (Draco itself stops at 1000; real files have none).
constexpr int kMaxMetadataDepth = 64;

/// A cursor that never reads past the end of the stream.
class Reader {
public:
    Reader(const unsigned char* data, std::size_t size) : m_data(data), m_size(size) {}
    std::size_t left() const { return m_size - m_pos; }
    bool skip(std::size_t n) {
        if (n > left()) return false;
        m_pos += n;
        return true;
    }
    bool u8(std::uint32_t& v) {
        if (left() < 1) return false;
        v = m_data[m_pos++];
        return true;
    }
    /// Little-endian, as Draco writes (it copies host integers on little-endian machines).
    bool uint(std::size_t bytes, std::uint32_t& v) {
        if (left() < bytes) return false;
        v = 0;
        for (std::size_t i = 0; i < bytes; ++i)
            v |= std::uint32_t(m_data[m_pos + i]) << (8 * i);
        m_pos += bytes;
        return true;
    }
    /// Draco's unsigned varint: 7 bits a byte, low bits first, at most 5 bytes, and the value
    /// truncated to 32 bits as its decoder does.
    bool varint(std::uint32_t& v) {
        std::size_t n = 0;
        while (true) {
            if (n == 5 || n >= left()) return false;
            if ((m_data[m_pos + n++] & 0x80) == 0) break;
        }
        v = 0;
        for (std::size_t i = n; i-- > 0;)
            v = (v << 7) | (m_data[m_pos + i] & 0x7F);
        m_pos += n;
        return true;
    }

private:
    const unsigned char* m_data;
    std::size_t m_size, m_pos = 0;
};

/// A metadata name: a length byte and that many bytes.
bool skipName(Reader& r) {
    std::uint32_t length = 0;
    return r.u8(length) && r.skip(length);
}

/// One metadata block and its sub-blocks (depth first, as Draco reads them): entries whose
/// sizes must lie within the stream (Draco allocates an entry's size before reading it).
bool skipMetadata(Reader& r, int depth) {
    if (depth > kMaxMetadataDepth) return false;
    std::uint32_t entries = 0, subBlocks = 0;
    if (!r.varint(entries)) return false;
    for (std::uint32_t i = 0; i < entries; ++i) {
        std::uint32_t size = 0;
        if (!skipName(r) || !r.varint(size) || size == 0 || !r.skip(size)) return false;
    }
    if (!r.varint(subBlocks) || subBlocks > r.left()) return false;
    for (std::uint32_t i = 0; i < subBlocks; ++i)
        if (!skipName(r) || !skipMetadata(r, depth + 1)) return false;
    return true;
}

/// The geometry metadata: per-attribute blocks, then the mesh's block.
bool skipGeometryMetadata(Reader& r) {
    std::uint32_t attributes = 0;
    if (!r.varint(attributes)) return false;
    for (std::uint32_t i = 0; i < attributes; ++i) {
        std::uint32_t id = 0;
        if (!r.varint(id) || !skipMetadata(r, 0)) return false;
    }
    return skipMetadata(r, 0);
}

/// Edgebreaker's connectivity header (MeshEdgebreakerDecoder::InitializeDecoder, then
/// MeshEdgeBreakerDecoderImpl::DecodeConnectivity).
Result<void> readEdgebreaker(Reader& r, int minor, DracoHeader& h, const std::string& object,
                             const Diagnostics& diag) {
    std::uint32_t traversal = 0, newVertices = 0, vertices = 0, faces = 0, attributeData = 0;
    std::uint32_t symbols = 0, splitSymbols = 0;
    const bool ok = r.u8(traversal) && (minor >= 2 || r.varint(newVertices)) &&
                    r.varint(vertices) && r.varint(faces) && r.u8(attributeData) &&
                    r.varint(symbols) && r.varint(splitSymbols);
    if (!ok) return diag.error(object, "the Draco stream ends inside its connectivity header");
    if (traversal > 2)
        return diag.error(object, "unknown Draco edgebreaker traversal " + std::to_string(traversal));
    h.faces = faces;
    // Every vertex lies on a face, there is at most one symbol a face, and split symbols are
    // among the symbols: anything else is a stream whose counts contradict each other.
    if (symbols > faces || splitSymbols > faces || vertices > 3 * std::uint64_t(faces))
        return diag.error(object, "the Draco stream's counts contradict each other (" +
                                      std::to_string(faces) + " faces, " +
                                      std::to_string(vertices) + " vertices, " +
                                      std::to_string(symbols) + " symbols, " +
                                      std::to_string(splitSymbols) + " split symbols)");
    h.vertices = std::uint64_t(vertices) + splitSymbols;
    return {};
}

} // namespace

Result<DracoHeader> readDracoHeader(const unsigned char* data, std::size_t size,
                                    const std::string& object, const Diagnostics& diag) {
    Reader r(data, size);
    if (size < 5 || std::memcmp(data, "DRACO", 5) != 0)
        return diag.error(object, "the data is not a Draco stream (no \"DRACO\" header)");
    r.skip(5);
    std::uint32_t major = 0, minor = 0, type = 0, method = 0, flags = 0;
    if (!r.u8(major) || !r.u8(minor) || !r.u8(type) || !r.u8(method) || !r.uint(2, flags))
        return diag.error(object, "the Draco stream ends inside its header");
    DracoHeader h;
    h.versionMajor = int(major);
    h.versionMinor = int(minor);
    if (major != 2 || minor > 2)
        return diag.error(object, "Draco bitstream version " + std::to_string(major) + "." +
                                      std::to_string(minor) +
                                      " is not supported (2.0 to 2.2, as the extension specifies)");
    if (type != 1)
        return diag.error(object, type == 0 ? "the Draco stream holds a point cloud, not a mesh"
                                            : "unknown Draco geometry type " + std::to_string(type));
    if (method > 1)
        return diag.error(object, "unknown Draco encoding method " + std::to_string(method));
    if ((flags & kMetadataFlag) && !skipGeometryMetadata(r))
        return diag.error(object, "the Draco stream's metadata is malformed, nested more than " +
                                      std::to_string(kMaxMetadataDepth) +
                                      " levels or runs past its end");
    h.edgebreaker = method == 1;
    if (h.edgebreaker) {
        LANTERN_TRY(readEdgebreaker(r, int(minor), h, object, diag));
        return h;
    }
    // Sequential: before 2.2 both counts are 32-bit integers, from 2.2 varints.
    std::uint32_t faces = 0, points = 0;
    const bool ok = minor >= 2 ? r.varint(faces) && r.varint(points)
                               : r.uint(4, faces) && r.uint(4, points);
    if (!ok) return diag.error(object, "the Draco stream ends inside its connectivity header");
    h.faces = faces;
    h.vertices = points;
    return h;
}

} // namespace lantern::gltf
