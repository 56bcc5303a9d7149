// The glTF loader's first pass, on the bytes before tinygltf sees them: the GLB container's
// chunk structure and the JSON nesting depth (files are read and URIs resolved confined to the
// scene's folder by io/FileAccess.cpp; the JSON document's own checks are in GltfJson.cpp).
#include "io/gltf/GltfInternal.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern::gltf {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A; // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;  // "BIN\0"

std::uint32_t readU32(const std::vector<unsigned char>& b, std::size_t offset) {
    // GLB is little-endian; assemble byte by byte so the host's order does not matter.
    return std::uint32_t(b[offset]) | std::uint32_t(b[offset + 1]) << 8 |
           std::uint32_t(b[offset + 2]) << 16 | std::uint32_t(b[offset + 3]) << 24;
}

std::string chunkName(std::uint32_t type) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        const char c = char((type >> (8 * i)) & 0xFF);
        s += (c >= 32 && c < 127) ? c : '?';
    }
    return "\"" + s + "\"";
}


} // namespace

std::string at(std::string_view array, std::size_t index) {
    return std::string(array) + "[" + std::to_string(index) + "]";
}

bool isGlb(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic;
}

Result<GlbLayout> parseGlb(const std::vector<unsigned char>& bytes, const Diagnostics& diag) {
    const std::size_t size = bytes.size();
    if (size < 12)
        return diag.error("GLB header", "file is " + std::to_string(size) +
                                            " bytes, shorter than the 12-byte GLB header");
    if (readU32(bytes, 0) != kGlbMagic) return diag.error("GLB header", "magic is not \"glTF\"");
    const std::uint32_t version = readU32(bytes, 4);
    if (version != 2)
        return diag.error("GLB header", "container version " + std::to_string(version) +
                                            " is not supported (only 2)");
    const std::uint32_t length = readU32(bytes, 8);
    if (length != size)
        return diag.error("GLB header", "declared length " + std::to_string(length) +
                                            " differs from the file size " + std::to_string(size));
    if (size < 20)
        return diag.error("GLB header", "no JSON chunk (the file ends after the header)");

    GlbLayout layout;
    bool haveJson = false;
    std::size_t chunkIndex = 0;
    std::size_t offset = 12;
    std::size_t understoodEnd = 0;
    while (offset < size) {
        const std::string object = "GLB " + at("chunks", chunkIndex);
        if (size - offset < 8)
            return diag.error(object, "truncated chunk header (" + std::to_string(size - offset) +
                                          " bytes left, 8 needed)");
        const std::uint32_t chunkLength = readU32(bytes, offset);
        const std::uint32_t chunkType = readU32(bytes, offset + 4);
        const std::size_t dataOffset = offset + 8;
        if (chunkLength > size - dataOffset)
            return diag.error(object, "chunk length " + std::to_string(chunkLength) +
                                          " runs past the end of the file");
        if (chunkLength % 4 != 0)
            return diag.error(object, "chunk length " + std::to_string(chunkLength) +
                                          " is not a multiple of 4");
        if (chunkIndex == 0) {
            if (chunkType != kChunkJson)
                return diag.error(object, "first chunk is " + chunkName(chunkType) +
                                              ", not the JSON chunk");
            if (chunkLength == 0) return diag.error(object, "JSON chunk is empty");
            layout.jsonOffset = dataOffset;
            layout.jsonLength = chunkLength;
            haveJson = true;
            understoodEnd = dataOffset + chunkLength;
        } else if (chunkType == kChunkJson) {
            return diag.error(object, "second JSON chunk (only one is allowed)");
        } else if (chunkType == kChunkBin) {
            if (layout.hasBin) return diag.error(object, "second BIN chunk (only one is allowed)");
            if (chunkIndex != 1)
                return diag.error(object, "BIN chunk must directly follow the JSON chunk");
            layout.hasBin = true;
            layout.binOffset = dataOffset;
            layout.binLength = chunkLength;
            understoodEnd = dataOffset + chunkLength;
        } else {
            diag.warn(object, "unknown chunk type " + chunkName(chunkType) + " ignored");
        }
        offset = dataOffset + chunkLength;
        ++chunkIndex;
    }
    if (!haveJson) return diag.error("GLB", "no JSON chunk");
    layout.tinygltfLength = understoodEnd;
    return layout;
}

Result<JsonShape> scanJson(std::string_view json, const Diagnostics& diag) {
    JsonShape shape;
    int depth = 0;
    bool inString = false, escaped = false;
    std::size_t stringStart = 0;
    char previous = 0; // the last character outside strings that is not white space
    for (std::size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"') {
                inString = false;
                const std::uint64_t length = i - stringStart - 1;
                if (length > 15) shape.longStringBytes += length + 24; // heap block, rounded
            }
            continue;
        }
        if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
        if (c == '"') {
            inString = true;
            stringStart = i;
            ++shape.strings;
        } else if (c == '{' || c == '[') {
            ++(c == '{' ? shape.objects : shape.arrays);
            if (++depth > kMaxJsonDepth)
                return diag.error("JSON", "nested more than " + std::to_string(kMaxJsonDepth) +
                                              " levels deep (at byte " + std::to_string(i) + ")");
        } else if (c == '}' || c == ']') {
            --depth;
        } else if (c == ':') {
            ++shape.members;
        } else if (previous == 0 || previous == '[' || previous == ',' || previous == ':') {
            ++shape.scalars; // the first character of a number, true, false or null
        }
        previous = c;
    }
    return shape;
}

std::uint64_t JsonShape::values() const {
    return objects + arrays + scalars + (strings - std::min(strings, members));
}

std::uint64_t JsonShape::documentBytes() const {
    // nlohmann::json (std::map objects) on libstdc++ and glibc malloc, in heap blocks: an
    // object's map 64, a member's tree node (key and value) 96, an array's vector 32 and its
    // element slots 16 each, doubled for the vector's spare capacity; a string value's
    // std::string 48; long strings their bytes (counted by the scan).
    const std::uint64_t elements = values() - std::min(values(), members + 1);
    return 64 * objects + 96 * members + 32 * arrays + 32 * elements +
           48 * (strings - std::min(strings, members)) + longStringBytes + 64;
}

std::uint64_t JsonShape::contentBytes() const {
    // What a model built from the document holds beyond its objects' fixed size: a heap block
    // per array (index lists, matrices), 8 bytes per number, a std::string per string.
    return 32 * arrays + 8 * scalars + 32 * strings + longStringBytes;
}

Result<std::vector<unsigned char>> rebuildGlb(const std::vector<unsigned char>& bytes,
                                              const GlbLayout& layout, const std::string& json,
                                              const Diagnostics& diag) {
    std::string text = json;
    while (text.size() % 4 != 0)
        text += ' ';
    const std::uint64_t total =
        20 + std::uint64_t(text.size()) + (layout.hasBin ? 8 + std::uint64_t(layout.binLength) : 0);
    if (total > std::numeric_limits<std::uint32_t>::max())
        return diag.error("GLB", "files of 4 GiB or more cannot be read by tinygltf");
    std::vector<unsigned char> out;
    out.reserve(std::size_t(total));
    auto u32 = [&](std::uint64_t v) {
        for (int i = 0; i < 4; ++i)
            out.push_back((v >> (8 * i)) & 0xFF);
    };
    u32(kGlbMagic);
    u32(2);
    u32(total);
    u32(text.size());
    u32(kChunkJson);
    out.insert(out.end(), text.begin(), text.end());
    if (layout.hasBin) {
        u32(layout.binLength);
        u32(kChunkBin);
        const auto bin = bytes.begin() + std::ptrdiff_t(layout.binOffset);
        out.insert(out.end(), bin, bin + std::ptrdiff_t(layout.binLength));
    }
    return out;
}

} // namespace lantern::gltf
