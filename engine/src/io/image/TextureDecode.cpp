// Encoded images -> RGBA8 textures, checked and charged before decoding (io/image/TextureDecode.h).
#include "io/image/TextureDecode.h"

#include "io/image/ImageDecode.h"

namespace lantern::io {

Result<Texture> decodeTexture(const unsigned char* bytes, std::size_t size,
                              const std::string& object, std::uint64_t maxBytes,
                              const Diagnostics& diag, int* fileChannels) {
    auto info = inspectImage(bytes, size);
    if (!info) return diag.error(object, info.error().message);
    const int w = info->width, h = info->height;
    if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide)
        return diag.error(object, std::to_string(w) + "x" + std::to_string(h) +
                                      " is outside the supported texture size (1 to " +
                                      std::to_string(kMaxTextureSide) + " per side)");
    const std::uint64_t rgbaBytes = std::uint64_t(w) * std::uint64_t(h) * 4;
    if (rgbaBytes > maxBytes)
        return diag.error(object, "decoded image (" + std::to_string(rgbaBytes) +
                                      " bytes) exceeds --max-size (" +
                                      std::to_string(maxBytes) + " bytes)");
    // The header's declared size is charged before a pixel is decoded: the decoder's working
    // memory (the inflated rows at the file's channels and depth, the conversion to 4 channels
    // at that depth) and the result, then Lantern's copy.
    const std::uint64_t depth = info->sixteenBit ? 2 : 1;
    const std::uint64_t perPixel = std::uint64_t(info->channels) * depth + 4 * depth + 4 + 4;
    LANTERN_TRY(diag.charge(std::uint64_t(w) * std::uint64_t(h), perPixel, object,
                            "decoding the " + std::to_string(w) + "x" + std::to_string(h) +
                                " image"));
    auto pixels = decodeRgba8(bytes, size, *info);
    if (!pixels) return diag.error(object, pixels.error().message);
    Texture t;
    t.width = w;
    t.height = h;
    t.rgba8 = std::move(*pixels);
    if (fileChannels) *fileChannels = info->channels;
    return t;
}

} // namespace lantern::io
