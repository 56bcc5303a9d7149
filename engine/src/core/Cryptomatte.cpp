// Cryptomatte's name hashes (lantern/Cryptomatte.h): MurmurHash3 and the ids and keys made
// from it, shared by the renderer's id planes and the EXR writer's manifest.
#include <lantern/Cryptomatte.h>

#include <bit>
#include <cstdio>

namespace lantern {

std::uint32_t murmurHash3_32(std::string_view bytes, std::uint32_t seed) noexcept {
    // Austin Appleby's MurmurHash3_x86_32: little-endian 4-byte blocks, then the tail.
    constexpr std::uint32_t c1 = 0xcc9e2d51u, c2 = 0x1b873593u;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const std::size_t len = bytes.size(), blocks = len / 4;
    std::uint32_t h = seed;
    for (std::size_t i = 0; i < blocks; ++i) {
        const unsigned char* b = data + i * 4;
        std::uint32_t k = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                          std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
        k = std::rotl(k * c1, 15) * c2;
        h = std::rotl(h ^ k, 13) * 5u + 0xe6546b64u;
    }
    const unsigned char* tail = data + blocks * 4;
    std::uint32_t k = 0;
    switch (len & 3u) {
    case 3: k ^= std::uint32_t(tail[2]) << 16; [[fallthrough]];
    case 2: k ^= std::uint32_t(tail[1]) << 8; [[fallthrough]];
    case 1: k ^= tail[0]; h ^= std::rotl(k * c1, 15) * c2; break;
    default: break;
    }
    h ^= std::uint32_t(len);
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

std::uint32_t cryptomatteId(std::uint32_t hash) noexcept {
    const std::uint32_t exponent = (hash >> 23) & 0xffu;
    return exponent == 0 || exponent == 255 ? hash ^ (1u << 23) : hash;
}

float cryptomatteFloat(std::string_view name) noexcept {
    return std::bit_cast<float>(cryptomatteId(murmurHash3_32(name)));
}

std::string cryptomatteKey(std::string_view layerName) {
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", unsigned(murmurHash3_32(layerName)));
    return std::string(hex, 7);
}

} // namespace lantern
