// Encoded images -> RGBA8 textures, checked and charged before decoding (io/image/TextureDecode.h).
#include "io/image/TextureDecode.h"

#include <climits>
#include <stb_image.h>

namespace lantern::io {

Result<Texture> decodeTexture(const unsigned char* bytes, std::size_t size,
                              const std::string& object, std::uint64_t maxBytes,
                              const Diagnostics& diag, int* fileChannels) {
    if (size > std::size_t(INT_MAX)) return diag.error(object, "encoded image is too large");
    int w = 0, h = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, int(size), &w, &h, &channels))
        return diag.error(object, std::string("cannot be decoded: ") + stbi_failure_reason());
    if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide)
        return diag.error(object, std::to_string(w) + "x" + std::to_string(h) +
                                      " is outside the supported texture size (1 to " +
                                      std::to_string(kMaxTextureSide) + " per side)");
    const std::uint64_t rgbaBytes = std::uint64_t(w) * std::uint64_t(h) * 4;
    if (rgbaBytes > maxBytes)
        return diag.error(object, "decoded image (" + std::to_string(rgbaBytes) +
                                      " bytes) exceeds --max-size (" +
                                      std::to_string(maxBytes) + " bytes)");
    // The header's declared size is charged before a pixel is decoded: stb's working memory
    // (the inflated rows at the file's channels and depth, the conversion to 4 channels at
    // that depth) and the result, then Lantern's copy.
    const std::uint64_t depth = stbi_is_16_bit_from_memory(bytes, int(size)) ? 2 : 1;
    const std::uint64_t perPixel = std::uint64_t(channels) * depth + 4 * depth + 4 + 4;
    LANTERN_TRY(diag.charge(std::uint64_t(w) * std::uint64_t(h), perPixel, object,
                            "decoding the " + std::to_string(w) + "x" + std::to_string(h) +
                                " image"));
    stbi_uc* pixels = stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4);
    if (!pixels)
        return diag.error(object, std::string("cannot be decoded: ") + stbi_failure_reason());
    Texture t;
    t.width = w;
    t.height = h;
    t.rgba8.assign(pixels, pixels + rgbaBytes);
    stbi_image_free(pixels);
    if (fileChannels) *fileChannels = channels;
    return t;
}

} // namespace lantern::io
