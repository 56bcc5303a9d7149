// The OpenEXR writer (atomic) and reader, and writing by extension (the PNG writer: PngIo.cpp).
#include "io/image/ImageIo.h"

#include "io/image/AovChannels.h"
#include "io/image/CryptomatteExr.h"
#include "io/AtomicFile.h"
#include "io/image/ExrRead.h"
#include "io/image/ImageEncode.h"
#include "io/image/PngIo.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfFramesPerSecond.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfRationalAttribute.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <IexBaseExc.h>
#include <half.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace lantern {
namespace {

Imf::Compression toImf(ExrCompression c) {
    switch (c) {
    case ExrCompression::None: return Imf::NO_COMPRESSION;
    case ExrCompression::Rle: return Imf::RLE_COMPRESSION;
    case ExrCompression::Zips: return Imf::ZIPS_COMPRESSION;
    case ExrCompression::Zip: return Imf::ZIP_COMPRESSION;
    case ExrCompression::Piz: return Imf::PIZ_COMPRESSION;
    case ExrCompression::Pxr24: return Imf::PXR24_COMPRESSION;
    case ExrCompression::B44: return Imf::B44_COMPRESSION;
    case ExrCompression::B44a: return Imf::B44A_COMPRESSION;
    case ExrCompression::Dwaa: return Imf::DWAA_COMPRESSION;
    case ExrCompression::Dwab: return Imf::DWAB_COMPRESSION;
    }
    return Imf::ZIP_COMPRESSION;
}

// The threads compressing one file's line blocks, from OpenEXR's global pool (sized once to
// the cores); 0 has the calling thread compress them alone.
int exrThreads(int asked) {
    static std::once_flag once;
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    std::call_once(once, [cores] { Imf::setGlobalThreadCount(cores); });
    const int n = std::min(asked > 0 ? asked : cores, cores);
    return n > 1 ? n : 0;
}

} // namespace

Result<void> io::checkImage(const Image& image, const std::filesystem::path& path) {
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != image.pixelCount() * 4)
        return makeError(ErrorCode::InvalidInput, "image has no pixels or a wrong pixel count", {},
                         path.string());
    LANTERN_TRY(io::checkAovPlanes(image, path));
    return io::checkCryptomatte(image, path);
}

namespace {

// OpenEXR's output stream onto an AtomicFile, so that EXR bytes reach the disk through
// AtomicFile::write like every other output (one place where a full disk shows, and where
// the test hook can fill it). Buffered: OpenEXR writes its header a few bytes at a time.
// OpenEXR's OutputFile destructor rewrites the offset table and swallows any error doing so,
// so the stream keeps its first error and finish() reports it: a file whose table the disk
// refused is never committed.
class AtomicFileStream final : public Imf::OStream {
public:
    explicit AtomicFileStream(io::AtomicFile& file)
        : Imf::OStream(file.temporaryPath().c_str()), m_file(file) {
        m_buffer.reserve(kCapacity);
    }

    void write(const char c[], int n) override {
        if (m_error) throw Iex::IoExc(m_error->message);
        if (m_buffer.size() + std::size_t(n) > kCapacity) flush();
        if (std::size_t(n) >= kCapacity)
            check(m_file.write(c, std::size_t(n)));
        else
            m_buffer.insert(m_buffer.end(), c, c + n);
        m_position += std::uint64_t(n);
    }

    std::uint64_t tellp() override { return m_position; }

    void seekp(std::uint64_t position) override {
        flush();
        check(m_file.seek(position));
        m_position = position;
    }

    /// Writes what is buffered; the first error this stream met, if any.
    Result<void> finish() {
        if (!m_error) {
            try {
                flush();
            } catch (const Iex::BaseExc&) {
            }
        }
        if (m_error) return *m_error;
        return {};
    }

    const std::optional<Error>& error() const { return m_error; }

private:
    static constexpr std::size_t kCapacity = std::size_t(1) << 16;

    void flush() {
        if (m_buffer.empty()) return;
        auto written = m_file.write(m_buffer.data(), m_buffer.size());
        m_buffer.clear();
        check(std::move(written));
    }

    void check(Result<void> r) {
        if (r) return;
        m_error = std::move(r).error();
        throw Iex::IoExc(m_error->message);
    }

    io::AtomicFile& m_file;
    std::vector<char> m_buffer;
    std::uint64_t m_position = 0;
    std::optional<Error> m_error;
};

} // namespace

std::optional<io::ExrCameraMatrices> io::exrCameraMatrices(const CameraMetadata& camera) {
    // OpenEXR's camera space is left-handed, looking down +Z: flip z.
    glm::dmat4 flipZ(1.0);
    flipZ[2][2] = -1.0;
    // NDC: (0,0) top-left to (1,1) bottom-right of the display window; Vulkan's clip
    // space already has y down.
    glm::dmat4 ndcFromClip(1.0);
    ndcFromClip[0][0] = 0.5, ndcFromClip[1][1] = 0.5;
    ndcFromClip[3][0] = 0.5, ndcFromClip[3][1] = 0.5;
    const glm::dmat4 worldToCamera = flipZ * camera.viewFromWorld;
    const glm::dmat4 worldToNdc = ndcFromClip * camera.clipFromView * camera.viewFromWorld;
    ExrCameraMatrices out;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            out.worldToCamera[i][j] = float(worldToCamera[i][j]);
            out.worldToNdc[i][j] = float(worldToNdc[i][j]);
            if (!std::isfinite(out.worldToCamera[i][j]) || !std::isfinite(out.worldToNdc[i][j]))
                return std::nullopt;
        }
    return out;
}

const char* toString(ExrCompression c) noexcept {
    switch (c) {
    case ExrCompression::None: return "none";
    case ExrCompression::Rle: return "rle";
    case ExrCompression::Zips: return "zips";
    case ExrCompression::Zip: return "zip";
    case ExrCompression::Piz: return "piz";
    case ExrCompression::Pxr24: return "pxr24";
    case ExrCompression::B44: return "b44";
    case ExrCompression::B44a: return "b44a";
    case ExrCompression::Dwaa: return "dwaa";
    case ExrCompression::Dwab: return "dwab";
    }
    return "?";
}

std::optional<ExrCompression> parseExrCompression(std::string_view t) noexcept {
    for (ExrCompression c : {ExrCompression::None, ExrCompression::Rle, ExrCompression::Zips,
                             ExrCompression::Zip, ExrCompression::Piz, ExrCompression::Pxr24,
                             ExrCompression::B44, ExrCompression::B44a, ExrCompression::Dwaa,
                             ExrCompression::Dwab})
        if (t == toString(c)) return c;
    return std::nullopt;
}

namespace {

// The RGBA values as half. Values beyond the half range clamp to +-65504 (never Inf), counted in
// `clamped`; non-finite values become 0.
std::vector<half> toHalves(const std::vector<float>& rgba, std::uint64_t& clamped) {
    constexpr float kHalfMax = 65504.0f;
    std::vector<half> halves(rgba.size());
    for (std::size_t i = 0; i < rgba.size(); ++i) {
        float v = rgba[i];
        if (!std::isfinite(v)) v = 0.0f;
        if (v > kHalfMax || v < -kHalfMax) {
            v = std::clamp(v, -kHalfMax, kHalfMax);
            ++clamped;
        }
        halves[i] = half(v);
    }
    return halves;
}

// R, G, B and A: as half (from `halves`, which must outlive the write) or as float (the image).
void addColorChannels(Imf::Header& header, Imf::FrameBuffer& fb, const Image& image, bool asHalf,
                      const std::vector<half>& halves) {
    const int w = image.width;
    const Imf::PixelType colorType = asHalf ? Imf::HALF : Imf::FLOAT;
    const char* names[4] = {"R", "G", "B", "A"};
    if (asHalf) {
        for (int c = 0; c < 4; ++c) {
            header.channels().insert(names[c], Imf::Channel(colorType));
            fb.insert(names[c], Imf::Slice(Imf::HALF,
                                           const_cast<char*>(
                                               reinterpret_cast<const char*>(halves.data() + c)),
                                           sizeof(half) * 4, sizeof(half) * 4 * std::size_t(w)));
        }
    } else {
        for (int c = 0; c < 4; ++c) {
            header.channels().insert(names[c], Imf::Channel(colorType));
            fb.insert(
                names[c],
                Imf::Slice(Imf::FLOAT,
                           const_cast<char*>(reinterpret_cast<const char*>(image.rgba.data() + c)),
                           sizeof(float) * 4, sizeof(float) * 4 * std::size_t(w)));
        }
    }
}

// The standard worldToCamera and worldToNDC attributes, when they are finite in float.
void addCameraAttributes(Imf::Header& header, const CameraMetadata& camera) {
    const auto m = io::exrCameraMatrices(camera);
    if (!m) return;
    // Imath's matrices transform row vectors, which makes their element [i][j] GLM's [i][j].
    auto toImath = [](const glm::mat4& f) {
        Imath::M44f r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                r[i][j] = f[i][j];
        return r;
    };
    Imf::addWorldToCamera(header, toImath(m->worldToCamera));
    Imf::addWorldToNDC(header, toImath(m->worldToNdc));
}

} // namespace

Result<void> io::writeExr(const std::filesystem::path& path, const Image& image,
                          const ExrOptions& options) {
    LANTERN_TRY(io::checkImage(image, path));
    if (options.zipLevel < 1 || options.zipLevel > 9 || options.threads < 0)
        return makeError(ErrorCode::InvalidInput, "zip level outside 1..9 or negative threads", {}, path.string());
    io::AtomicFile file(path);
    LANTERN_TRY(file.checkWritable());
    AtomicFileStream stream(file);
    std::vector<half> halves;
    std::uint64_t clamped = 0;
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = toImf(options.compression);
        header.zipCompressionLevel() = options.zipLevel;
        Imf::FrameBuffer fb;
        if (options.half) halves = toHalves(image.rgba, clamped);
        addColorChannels(header, fb, image, options.half, halves);
        std::vector<io::AovChannel> aovs = io::aovChannels(image);
        io::cryptomatteChannels(image, aovs);
        for (const io::AovChannel& c : aovs) {
            const Imf::PixelType type = c.uint ? Imf::UINT : Imf::FLOAT;
            header.channels().insert(c.name, Imf::Channel(type));
            fb.insert(c.name, Imf::Slice(type, c.first, c.xStride, c.xStride * std::size_t(image.width)));
        }
        for (const auto& [key, value] : image.metadata) header.insert(key, Imf::StringAttribute(value));
        for (const auto& [key, value] : io::cryptomatteAttributes(image))
            header.insert(key, Imf::StringAttribute(value));
        if (image.camera) addCameraAttributes(header, *image.camera);
        if (image.framesPerSecond > 0.0)
            Imf::addFramesPerSecond(header, Imf::guessExactFps(image.framesPerSecond));
        // The OutputFile is destroyed (writing its offset table) before the stream finishes.
        Imf::OutputFile out(stream, header, exrThreads(options.threads));
        out.setFrameBuffer(fb);
        out.writePixels(image.height);
    } catch (const std::exception& e) {
        // A full disk shows up here as the stream's exception: report the stream's own error,
        // which names the errno, rather than OpenEXR's rewording of it.
        if (stream.error()) return *stream.error();
        return makeError(ErrorCode::IoError, std::string("OpenEXR could not write the file: ") + e.what(),
                         {}, path.string());
    }
    LANTERN_TRY(stream.finish());
    if (options.clampedCount) *options.clampedCount = clamped;
    return file.commit();
}


Result<Image> io::readExr(const std::filesystem::path& path) {
    return withExrFile<Image>(path, [&](Imf::InputFile& in, const ExrWindow& window, int w,
                                        int h) -> Result<Image> {
        Image img{w, h};
        Imf::FrameBuffer fb;
        const char* names[4] = {"R", "G", "B", "A"};
        auto base = [&](float* p, std::size_t comps) {
            return io::exrSliceBase(p, window, comps * sizeof(float), comps * sizeof(float) * std::size_t(w));
        };
        for (int c = 0; c < 4; ++c)
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base(img.rgba.data() + c, 4), 16, 16 * std::size_t(w), 1, 1,
                                           c == 3 ? 1.0 : 0.0));
        const Imf::ChannelList& channels = in.header().channels();
        for (auto it = in.header().begin(); it != in.header().end(); ++it)
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                img.metadata.emplace_back(it.name(), s->value());
        auto has = [&](const char* name) { return channels.findChannel(name) != nullptr; };
        std::vector<io::AovChannel> aovs = io::aovChannelsToRead(img, has);
        auto crypto = io::cryptomatteChannelsToRead(img, img.metadata, has, path);
        if (!crypto) return std::move(crypto).error();
        aovs.insert(aovs.end(), crypto->begin(), crypto->end());
        for (const io::AovChannel& c : aovs) {
            // exrSliceBase only does byte arithmetic on its pointer; UINT values are 4 bytes too.
            char* first = io::exrSliceBase(reinterpret_cast<float*>(c.first), window, c.xStride,
                                           c.xStride * std::size_t(w));
            fb.insert(c.name, Imf::Slice(c.uint ? Imf::UINT : Imf::FLOAT, first, c.xStride,
                                         c.xStride * std::size_t(w)));
        }
        in.setFrameBuffer(fb);
        in.readPixels(window.minY, window.maxY);
        return img;
    });
}

Result<void> io::writeImage(const std::filesystem::path& path, const Image& image,
                            const ExrOptions& exrOptions) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".exr") return writeExr(path, image, exrOptions);
    if (ext == ".png") return io::writePng(path, image);
    return makeError(ErrorCode::InvalidInput,
                     "unknown image type \"" + ext + "\" (use .exr or .png)", "--output", path.string());
}

} // namespace lantern
