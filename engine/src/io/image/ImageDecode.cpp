// Encoded images in (io/image/ImageDecode.h): the format from the first bytes, the header read
// by Lantern for PNG (so that a cut or empty header is named as such) and by the decoders for
// the others, pixels through stb_image and libwebp.
#include "io/image/ImageDecode.h"

#include <stb_image.h>
#include <webp/decode.h>

#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>

namespace lantern::io {
namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

Error invalid(std::string message) { return makeError(ErrorCode::InvalidInput, std::move(message)); }

std::uint32_t bigEndian32(const unsigned char* p) {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

ImageFormat sniff(const unsigned char* b, std::size_t n) {
    if (n >= 8 && std::memcmp(b, kPngSignature, 8) == 0) return ImageFormat::Png;
    if (n >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return ImageFormat::Jpeg;
    if (n >= 12 && std::memcmp(b, "RIFF", 4) == 0 && std::memcmp(b + 8, "WEBP", 4) == 0)
        return ImageFormat::Webp;
    return ImageFormat::Other;
}

// The first bytes as hex, for a file that is no image Lantern reads.
std::string firstBytes(const unsigned char* b, std::size_t n) {
    std::string out;
    for (std::size_t i = 0; i < n && i < 8; ++i) {
        char hex[4];
        std::snprintf(hex, sizeof hex, "%02X", unsigned(b[i]));
        out += (i ? " " : "") + std::string(hex);
    }
    return out;
}

std::string sizeText(std::uint64_t w, std::uint64_t h) {
    return std::to_string(w) + "x" + std::to_string(h);
}

// A PNG's IHDR, read here: stb's own reading of it ends in "unknown image type" when the
// header is cut, because every other format is tried after PNG fails.
Result<ImageInfo> inspectPng(const unsigned char* b, std::size_t n) {
    // Signature (8), IHDR length and type (8), width, height, depth, colour type (10 of 13).
    if (n < 26 || std::memcmp(b + 12, "IHDR", 4) != 0)
        return invalid(n < 26 ? "is a PNG cut short in its header (" + std::to_string(n) +
                                    " bytes)"
                              : "is a PNG whose first chunk is not IHDR (corrupt)");
    ImageInfo info;
    info.format = ImageFormat::Png;
    const std::uint32_t w = bigEndian32(b + 16), h = bigEndian32(b + 20);
    if (w == 0 || h == 0) return invalid("is a PNG of " + sizeText(w, h) + " pixels (empty)");
    if (w > std::uint32_t(INT_MAX) || h > std::uint32_t(INT_MAX))
        return invalid("is a PNG of " + sizeText(w, h) + " pixels, too large to read");
    info.width = int(w);
    info.height = int(h);
    info.sixteenBit = b[24] == 16;
    const int channelsOf[7] = {1, 0, 3, 3, 2, 0, 4};  // by colour type (3: palette, read as RGB)
    info.channels = b[25] <= 6 ? channelsOf[b[25]] : 0;
    if (info.channels == 0)
        return invalid("is a PNG with an invalid colour type " + std::to_string(b[25]));
    return info;
}

Result<ImageInfo> inspectWebp(const unsigned char* b, std::size_t n) {
    WebPBitstreamFeatures features;
    if (WebPGetFeatures(b, n, &features) != VP8_STATUS_OK)
        return invalid("is a WebP file whose header is cut short or corrupt");
    ImageInfo info;
    info.format = ImageFormat::Webp;
    info.width = features.width;
    info.height = features.height;
    info.channels = features.has_alpha ? 4 : 3;
    return info;
}

// Why data that was inspected did not decode: truncated when its end marker is missing.
Error notDecoded(const unsigned char* b, std::size_t n, const ImageInfo& info, const char* why) {
    static constexpr unsigned char iend[8] = {'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    if (info.format == ImageFormat::Png && (n < 12 || std::memcmp(b + n - 8, iend, 8) != 0))
        return invalid("is a PNG of " + sizeText(info.width, info.height) +
                       " pixels that is truncated (" + std::to_string(n) +
                       " bytes, no IEND chunk at the end)");
    if (info.format == ImageFormat::Jpeg && (n < 2 || b[n - 2] != 0xFF || b[n - 1] != 0xD9))
        return invalid("is a JPEG of " + sizeText(info.width, info.height) +
                       " pixels that is truncated (" + std::to_string(n) +
                       " bytes, no end-of-image marker)");
    return invalid(std::string("is a ") + imageFormatName(info.format) + " of " +
                   sizeText(info.width, info.height) + " pixels whose data is corrupt (" + why +
                   ")");
}

} // namespace

const char* imageFormatName(ImageFormat format) noexcept {
    switch (format) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::Webp: return "WebP";
    case ImageFormat::Other: break;
    }
    return "image";
}

Result<ImageInfo> inspectImage(const unsigned char* bytes, std::size_t size) {
    if (size == 0) return invalid("is empty (0 bytes)");
    if (size > std::size_t(INT_MAX)) return invalid("is too large to decode (over 2 GiB)");
    const ImageFormat format = sniff(bytes, size);
    if (format == ImageFormat::Png) return inspectPng(bytes, size);
    if (format == ImageFormat::Webp) return inspectWebp(bytes, size);
    ImageInfo info;
    info.format = format;
    if (!stbi_info_from_memory(bytes, int(size), &info.width, &info.height, &info.channels)) {
        if (format == ImageFormat::Jpeg)
            return invalid(std::string("is a JPEG whose header is cut short or corrupt (") +
                           stbi_failure_reason() + ")");
        return invalid("is not an image Lantern reads (PNG, JPEG or WebP; it starts with " +
                       firstBytes(bytes, size) + ")");
    }
    if (info.width <= 0 || info.height <= 0)
        return invalid(std::string("is a ") + imageFormatName(format) + " of " +
                       sizeText(std::uint64_t(std::max(info.width, 0)),
                                std::uint64_t(std::max(info.height, 0))) +
                       " pixels (empty)");
    return info;
}

Result<std::vector<std::uint8_t>> decodeRgba8(const unsigned char* bytes, std::size_t size,
                                              const ImageInfo& info) {
    const std::size_t count = std::size_t(info.width) * std::size_t(info.height) * 4;
    if (info.format == ImageFormat::Webp) {
        int w = 0, h = 0;
        std::unique_ptr<uint8_t, void (*)(void*)> p(WebPDecodeRGBA(bytes, size, &w, &h), &WebPFree);
        if (!p || w != info.width || h != info.height)
            return notDecoded(bytes, size, info, "libwebp could not decode it");
        return std::vector<std::uint8_t>(p.get(), p.get() + count);
    }
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> p(
        stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4), &stbi_image_free);
    if (!p || w != info.width || h != info.height)
        return notDecoded(bytes, size, info, p ? "its size changed" : stbi_failure_reason());
    return std::vector<std::uint8_t>(p.get(), p.get() + count);
}

} // namespace lantern::io
