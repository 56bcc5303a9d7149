// MeshTestSupport.h: writing OBJ, MTL, PLY, STL, OFF and PNG files in a test, and loading any
// scene file through loadScene with its warnings captured (refusals are checked with
// GltfTestSupport.h's refusedWith).
#pragma once

#include "GltfTestSupport.h"

#include <glm/vec3.hpp>
#include <png.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace lantern::test {

inline std::filesystem::path writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
    return path;
}

/// Loads any scene file through loadScene (the format chosen by name, else by content).
inline LoadOutcome loadAny(const std::filesystem::path& path, LoadOptions options = {}) {
    LoadOutcome out;
    auto sink = out.warnings;
    options.log = [sink](LogLevel, std::string_view message) { sink->emplace_back(message); };
    out.scene = loadScene(path.string(), options);
    return out;
}

/// An 8-bit PNG of `channels` (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA), rows top first.
inline void writePng(const std::filesystem::path& path, int width, int height, int channels,
                     const std::vector<unsigned char>& pixels) {
    FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr) << path;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    const int types[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                         PNG_COLOR_TYPE_RGBA};
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, types[channels],
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
        png_write_row(png, pixels.data() + std::size_t(y) * std::size_t(width * channels));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
}

/// Little- or big-endian bytes of a value, appended.
template <typename T>
void putValue(std::vector<unsigned char>& out, T value, bool bigEndian = false) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (bigEndian) std::reverse(b, b + sizeof(T));
    out.insert(out.end(), b, b + sizeof(T));
}

/// A binary STL: `header` (cut or padded to 80 bytes), the count, and per facet its normal and
/// three corners (attribute word 0).
inline std::vector<unsigned char> binaryStl(const std::string& header,
                                            const std::vector<std::array<glm::vec3, 4>>& facets) {
    std::vector<unsigned char> out(80, ' ');
    std::memcpy(out.data(), header.data(), std::min<std::size_t>(80, header.size()));
    putValue(out, std::uint32_t(facets.size()));
    for (const auto& f : facets) {
        for (const glm::vec3& v : f)
            for (int i = 0; i < 3; ++i) putValue(out, v[i]);
        putValue(out, std::uint16_t(0));
    }
    return out;
}

inline void writeBytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
    GltfBuilder::writeBytes(path, bytes);
}

/// A triangle's three corners in the XY plane, counter-clockwise seen from +Z.
inline const std::vector<glm::vec3>& unitTriangle() {
    static const std::vector<glm::vec3> t = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    return t;
}

} // namespace lantern::test
