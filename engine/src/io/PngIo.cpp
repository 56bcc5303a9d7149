// The PNG writer (atomic): 8-bit sRGB with straight alpha through libpng, from an Image or
// from a frame left where the renderer put it (FrameView).
#include <lantern/Io.h>
#include <lantern/Renderer.h>

#include "io/AtomicFile.h"
#include "io/ImageEncode.h"
#include "math/Srgb.h"

#include <png.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <system_error>
#include <thread>
#include <vector>

namespace lantern {

namespace {

// libpng's write state, destroyed however encoding ends.
struct PngWriteState {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    ~PngWriteState() { png_destroy_write_struct(&png, &info); }
};

// Rows handed to libpng as they are made: `ready` counts the rows made so far (another thread
// may be making them), and libpng takes row y once it is.
struct RowSource {
    unsigned char* const* rows;
    const std::atomic<int>* ready;
};

void waitForRow(const RowSource& source, int y) {
    for (int made = source.ready->load(std::memory_order_acquire); made <= y;
         made = source.ready->load(std::memory_order_acquire))
        source.ready->wait(made, std::memory_order_acquire);
}

// libpng reports errors by longjmp back here: this frame holds no object with a destructor and
// changes no local declared before setjmp; the caller owns the state, the rows and the output.
bool encodePng(PngWriteState* state, int width, int height, const RowSource& source,
               const io::PngEncoding& encoding, std::vector<unsigned char>* out) {
    if (!state->png || !state->info) return false;
    if (setjmp(png_jmpbuf(state->png))) return false;
    png_set_write_fn(
        state->png, out,
        [](png_structp p, png_bytep data, png_size_t size) {
            auto* bytes = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(p));
            bytes->insert(bytes->end(), data, data + size);
        },
        nullptr);
    png_set_IHDR(state->png, state->info, png_uint_32(width), png_uint_32(height), 8,
                 PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    // The pixels are sRGB-encoded: say so (sRGB chunk), with the gAMA and cHRM that decoders
    // without sRGB support read instead, so no viewer has to guess the colour space.
    png_set_sRGB_gAMA_and_cHRM(state->png, state->info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_compression_level(state->png, encoding.zlibLevel);
    png_set_filter(state->png, PNG_FILTER_TYPE_BASE,
                   encoding.everyFilter ? PNG_ALL_FILTERS : PNG_FILTER_UP);
    png_write_info(state->png, state->info);
    for (int y = 0; y < height; ++y) {
        waitForRow(source, y);
        png_write_row(state->png, source.rows[y]);
    }
    png_write_end(state->png, state->info);
    return true;
}

// One row of `width` premultiplied linear RGBA floats as 8-bit straight-alpha sRGB.
void pngRow(const math::Srgb8Encoder& srgb8, const float* src, std::size_t width,
            unsigned char* dst) {
    for (std::size_t i = 0; i < width; ++i) {
        const float* p = src + i * 4;
        const float a = std::clamp(std::isfinite(p[3]) ? p[3] : 0.0f, 0.0f, 1.0f);
        for (int c = 0; c < 3; ++c) {
            // PNG stores straight alpha: undo the premultiplication first.
            float v = std::isfinite(p[c]) ? p[c] : 0.0f;
            if (a > 0.0f && a < 1.0f) v /= a;
            dst[i * 4 + c] = srgb8(v);
        }
        dst[i * 4 + 3] = static_cast<unsigned char>(std::lround(a * 255.0f));
    }
}

// Pictures of at least this many pixels are converted on a second thread while libpng
// compresses the rows already converted (the two take about as long).
constexpr std::size_t kPipelinedPixels = std::size_t(1) << 18;

// The PNG bytes of a picture given row by row (row(y): width RGBA floats, y = 0 the top).
template <typename Row>
Result<std::vector<unsigned char>> encodePngRows(int width, int height, Row&& row,
                                                 const io::PngEncoding& encoding) {
    const std::size_t w = std::size_t(width);
    std::vector<unsigned char> pixels(w * std::size_t(height) * 4);
    std::vector<unsigned char*> rows(static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y) rows[std::size_t(y)] = pixels.data() + std::size_t(y) * w * 4;
    const math::Srgb8Encoder& srgb8 = math::srgb8Encoder();
    std::atomic<int> ready{0};
    auto convert = [&] {
        for (int y = 0; y < height; ++y) {
            pngRow(srgb8, row(y), w, rows[std::size_t(y)]);
            ready.store(y + 1, std::memory_order_release);
            ready.notify_all();
        }
    };
    std::thread converter;
    if (w * std::size_t(height) >= kPipelinedPixels && std::thread::hardware_concurrency() > 1) {
        try {
            converter = std::thread(convert);
        } catch (const std::system_error&) {  // no thread to be had: convert here
        }
    }
    if (!converter.joinable()) convert();
    std::vector<unsigned char> encoded;
    encoded.reserve(w * std::size_t(height) * 2);
    PngWriteState state;
    const bool ok = encodePng(&state, width, height, RowSource{rows.data(), &ready}, encoding,
                              &encoded);
    if (converter.joinable()) converter.join();
    if (!ok) return makeError(ErrorCode::IoError, "PNG encoding failed (libpng)");
    return encoded;
}

template <typename Row>
Result<void> writePngRows(const std::filesystem::path& path, int width, int height, Row&& row) {
    io::AtomicFile file(path);
    LANTERN_TRY(file.checkWritable());
    auto encoded = encodePngRows(width, height, row, io::PngEncoding{});
    if (!encoded) {
        Error e = std::move(encoded).error();
        e.file = path.string();
        return e;
    }
    LANTERN_TRY(file.writeAll(encoded->data(), encoded->size()));
    return file.commit();
}

} // namespace

std::vector<unsigned char> io::pngPixels(const Image& image) {
    const std::size_t w = std::size_t(image.width);
    std::vector<unsigned char> pixels(image.pixelCount() * 4);
    const math::Srgb8Encoder& srgb8 = math::srgb8Encoder();
    for (int y = 0; y < image.height; ++y)
        pngRow(srgb8, image.pixel(0, y), w, pixels.data() + std::size_t(y) * w * 4);
    return pixels;
}

Result<std::vector<unsigned char>> io::encodePng(const Image& image, const PngEncoding& encoding) {
    return encodePngRows(image.width, image.height, [&](int y) { return image.pixel(0, y); },
                         encoding);
}

Result<void> writePng(const std::filesystem::path& path, const Image& image) {
    LANTERN_TRY(io::checkImage(image, path));
    return writePngRows(path, image.width, image.height, [&](int y) { return image.pixel(0, y); });
}

Result<void> writePng(const std::filesystem::path& path, const FrameView& view) {
    if (!view.valid())
        return makeError(ErrorCode::Usage,
                         "the frame view is no longer valid (its renderer rendered again)", {},
                         path.string());
    return writePngRows(path, view.width(), view.height(), [&](int y) { return view.row(y); });
}

} // namespace lantern
