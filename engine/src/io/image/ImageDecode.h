// ImageDecode.h: encoded images read by the engine (textures of every scene format, PNG
// references of `lantern compare`): what a file is, from its first bytes, and its pixels.
// PNG and JPEG through stb_image, WebP through libwebp; what else stb_image reads (BMP, TGA,
// GIF, ...) is read as well. Every failure says what is wrong: empty, truncated, too large,
// or not an image Lantern reads, never stb's bare "unknown image type".
#pragma once

#include <lantern/Result.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lantern::io {

enum class ImageFormat { Png, Jpeg, Webp, Other };

/// "PNG", "JPEG", "WebP", "image".
const char* imageFormatName(ImageFormat format) noexcept;

/// What an encoded image's header says.
struct ImageInfo {
    ImageFormat format = ImageFormat::Other;
    int width = 0, height = 0;
    int channels = 0;         ///< as stored (1 grey .. 4 RGBA)
    bool sixteenBit = false;  ///< 16 bits per channel (PNG)
};

/// Reads the header without decoding. InvalidInput when the bytes are empty, are no image
/// Lantern reads (the first bytes quoted), declare 0 pixels on a side, or a header that is cut
/// short. The message has no file or object: the caller adds its own.
Result<ImageInfo> inspectImage(const unsigned char* bytes, std::size_t size);

/// Decodes to 8-bit RGBA (top row first). InvalidInput, saying truncated or corrupt and how,
/// when the data does not decode.
Result<std::vector<std::uint8_t>> decodeRgba8(const unsigned char* bytes, std::size_t size,
                                              const ImageInfo& info);

} // namespace lantern::io
