// The PNG writer (atomic): 8-bit sRGB with straight alpha through libpng, from an Image or
// from rows wherever they are (a frame left where the renderer put it), whole or band by band.
#include "io/image/PngIo.h"

#include "io/AtomicFile.h"
#include "io/image/ImageEncode.h"
#include "math/Srgb.h"

#include <png.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <optional>
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

// The header of an 8-bit RGBA sRGB picture, and the encoding's settings. libpng longjmps on
// error: call it inside a setjmp frame.
void writePngHeader(const PngWriteState& state, int width, int height,
                    const io::PngEncoding& encoding) {
    png_set_IHDR(state.png, state.info, png_uint_32(width), png_uint_32(height), 8,
                 PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    // The pixels are sRGB-encoded: say so (sRGB chunk), with the gAMA and cHRM that decoders
    // without sRGB support read instead, so no viewer has to guess the colour space.
    png_set_sRGB_gAMA_and_cHRM(state.png, state.info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_compression_level(state.png, encoding.zlibLevel);
    png_set_filter(state.png, PNG_FILTER_TYPE_BASE,
                   encoding.everyFilter ? PNG_ALL_FILTERS : PNG_FILTER_UP);
    png_write_info(state.png, state.info);
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
    writePngHeader(*state, width, height, encoding);
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
Result<std::vector<unsigned char>> encodePngRows(int width, int height, const io::PngRowFn& row,
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

} // namespace

Result<void> io::writePngRows(const std::filesystem::path& path, int width, int height,
                              const PngRowFn& row) {
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

// The file, libpng's state and the compressed bytes not yet written to the file. libpng's write
// callback appends to `pending`; past kFlushBytes they go to the file, and a failing write is
// kept in `error` while libpng is made to longjmp out.
struct io::PngBandWriter::Impl {
    static constexpr std::size_t kFlushBytes = std::size_t(1) << 18;

    explicit Impl(const std::filesystem::path& path) : file(path) {}

    io::AtomicFile file;
    PngWriteState state;
    int width = 0, height = 0, rowsWritten = 0;
    bool broken = false;  ///< an earlier call failed: the stream writes nothing more
    std::vector<unsigned char> pending, row;
    std::optional<Error> error;

    bool flush() {
        if (pending.empty()) return true;
        if (auto w = file.write(pending.data(), pending.size()); !w) {
            error = std::move(w).error();
            return false;
        }
        pending.clear();
        return true;
    }
    Error failure(const char* what) {
        broken = true;
        Error e = error ? *error : makeError(ErrorCode::IoError, what);
        e.file = file.destination().string();
        return e;
    }
};

namespace {

void appendToStream(png_structp png, png_bytep data, png_size_t size) {
    auto* s = static_cast<io::PngBandWriter::Impl*>(png_get_io_ptr(png));
    s->pending.insert(s->pending.end(), data, data + size);
    if (s->pending.size() >= io::PngBandWriter::Impl::kFlushBytes && !s->flush())
        png_error(png, "the PNG file could not be written");
}

// As encodePng: libpng longjmps back to these frames, which hold nothing with a destructor.
bool startStream(io::PngBandWriter::Impl* s) {
    if (!s->state.png || !s->state.info) return false;
    if (setjmp(png_jmpbuf(s->state.png))) return false;
    png_set_write_fn(s->state.png, s, appendToStream, nullptr);
    writePngHeader(s->state, s->width, s->height, io::PngEncoding{});
    return true;
}

bool streamRows(io::PngBandWriter::Impl* s, int rows, const io::PngRowFn* row) {
    if (setjmp(png_jmpbuf(s->state.png))) return false;
    const math::Srgb8Encoder& srgb8 = math::srgb8Encoder();
    for (int y = 0; y < rows; ++y) {
        pngRow(srgb8, (*row)(y), std::size_t(s->width), s->row.data());
        png_write_row(s->state.png, s->row.data());
    }
    return true;
}

bool endStream(io::PngBandWriter::Impl* s) {
    if (setjmp(png_jmpbuf(s->state.png))) return false;
    png_write_end(s->state.png, s->state.info);
    return true;
}

} // namespace

Result<io::PngBandWriter> io::PngBandWriter::create(const std::filesystem::path& path, int width,
                                                   int height) {
    if (width < 1 || height < 1)
        return makeError(ErrorCode::InvalidInput,
                         "a PNG of " + std::to_string(width) + "x" + std::to_string(height) +
                             " pixels is empty",
                         {}, path.string());
    PngBandWriter writer;
    writer.m_impl = std::make_unique<Impl>(path);
    Impl& s = *writer.m_impl;
    LANTERN_TRY(s.file.checkWritable());
    LANTERN_TRY(s.file.open());
    s.width = width;
    s.height = height;
    s.row.resize(std::size_t(width) * 4);
    if (!startStream(&s)) return s.failure("PNG encoding failed (libpng)");
    return writer;
}

io::PngBandWriter::PngBandWriter() = default;
io::PngBandWriter::PngBandWriter(PngBandWriter&&) noexcept = default;
io::PngBandWriter& io::PngBandWriter::operator=(PngBandWriter&&) noexcept = default;
io::PngBandWriter::~PngBandWriter() = default;

std::string io::PngBandWriter::file() const {
    return m_impl ? m_impl->file.destination().string() : std::string();
}

Result<void> io::PngBandWriter::write(int width, int rows, const PngRowFn& row) {
    if (!m_impl || m_impl->broken)
        return makeError(ErrorCode::Usage, "the PNG stream has failed or finished");
    Impl& s = *m_impl;
    if (width != s.width || rows > s.height - s.rowsWritten)
        return makeError(ErrorCode::Usage,
                         "a band of " + std::to_string(width) + "x" + std::to_string(rows) +
                             " does not fit the " + std::to_string(s.height - s.rowsWritten) +
                             " rows of " + std::to_string(s.width) + " pixels left",
                         {}, file());
    if (!streamRows(&s, rows, &row)) return s.failure("PNG encoding failed (libpng)");
    s.rowsWritten += rows;
    return {};
}

Result<void> io::PngBandWriter::finish() {
    if (!m_impl || m_impl->broken)
        return makeError(ErrorCode::Usage, "the PNG stream has failed or finished");
    Impl& s = *m_impl;
    if (s.rowsWritten != s.height)
        return makeError(ErrorCode::Usage,
                         std::to_string(s.rowsWritten) + " of " + std::to_string(s.height) +
                             " rows were written",
                         {}, file());
    if (!endStream(&s) || !s.flush()) return s.failure("PNG encoding failed (libpng)");
    s.broken = true;  // finished: nothing more goes in
    return s.file.commit();
}

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

Result<void> io::writePng(const std::filesystem::path& path, const Image& image) {
    LANTERN_TRY(io::checkImage(image, path));
    return writePngRows(path, image.width, image.height, [&](int y) { return image.pixel(0, y); });
}

} // namespace lantern
