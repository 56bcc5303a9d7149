// Images read for comparison: every channel of an EXR, or a PNG's stored values, by name.
#include "io/image/ImageIo.h"

#include "io/FileAccess.h"
#include "io/image/ExrRead.h"
#include "io/image/ImageDecode.h"
#include "io/image/ImageEncode.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace lantern {
namespace {

Result<CompareImage> readExrChannels(const std::filesystem::path& path) {
    return io::withExrFile<CompareImage>(path, [&](Imf::InputFile& in, const io::ExrWindow& window,
                                                   int w, int h) -> Result<CompareImage> {
        CompareImage img;
        img.width = int(w);
        img.height = int(h);
        img.encoding = PixelEncoding::Linear;
        img.source = path.string();
        std::vector<std::string> others;
        for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
            if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
                return makeError(ErrorCode::InvalidInput,
                                 std::string("channel ") + it.name() +
                                     " is subsampled; only full-resolution channels can be compared",
                                 {}, path.string());
            others.emplace_back(it.name());
        }
        for (const char* name : {"R", "G", "B", "A"})
            if (auto f = std::find(others.begin(), others.end(), name); f != others.end()) {
                img.channels.emplace_back(name);
                others.erase(f);
            }
        img.channels.insert(img.channels.end(), others.begin(), others.end());
        if (img.channels.empty())
            return makeError(ErrorCode::InvalidInput, "the file has no channels", {}, path.string());
        const std::size_t nc = img.channels.size();
        if (std::size_t(w) * std::size_t(h) * nc > (std::size_t(1) << 32))
            return makeError(ErrorCode::OutOfMemory, "too many values to compare", {}, path.string());
        img.values.assign(std::size_t(w) * std::size_t(h) * nc, 0.0f);
        Imf::FrameBuffer fb;
        const std::size_t xs = nc * sizeof(float), ys = xs * std::size_t(w);
        for (std::size_t c = 0; c < nc; ++c) {
            fb.insert(img.channels[c],
                      Imf::Slice(Imf::FLOAT, io::exrSliceBase(img.values.data() + c, window, xs, ys), xs, ys));
        }
        in.setFrameBuffer(fb);
        in.readPixels(window.minY, window.maxY);
        return img;
    });
}

Result<CompareImage> readPngChannels(const std::filesystem::path& path) {
    auto bytes = io::readRegularFile(path, std::uint64_t(1) << 32, false);
    if (!bytes) {
        Error e = std::move(bytes).error();
        e.message = "the file " + e.message;
        e.file = path.string();
        return e;
    }
    const auto refuse = [&](const std::string& why) {
        return makeError(ErrorCode::InvalidInput, "not a readable PNG file: it " + why, {},
                         path.string());
    };
    // Why stb_image could not decode what was inspected (truncated, corrupt).
    const auto undecoded = [&](const io::ImageInfo& info) {
        auto again = io::decodeRgba8(bytes->data(), bytes->size(), info);
        return refuse(again ? std::string("could not be decoded") : again.error().message);
    };
    auto info = io::inspectImage(bytes->data(), bytes->size());
    if (!info) return refuse(info.error().message);
    if ((long long)info->width * info->height > (1LL << 31))
        return refuse("is " + std::to_string(info->width) + "x" + std::to_string(info->height) +
                      " pixels, more than 2^31 to compare");
    const int size = int(bytes->size());
    int w = 0, h = 0;
    CompareImage img;
    img.width = info->width;
    img.height = info->height;
    img.encoding = PixelEncoding::Srgb;
    img.source = path.string();
    const std::size_t n = std::size_t(info->width) * std::size_t(info->height);
    int got = 0;
    if (info->sixteenBit) {
        std::unique_ptr<stbi_us, void (*)(void*)> p(
            stbi_load_16_from_memory(bytes->data(), size, &w, &h, &got, 0), &stbi_image_free);
        if (!p) return undecoded(*info);
        img.values.resize(n * std::size_t(got));
        for (std::size_t i = 0; i < img.values.size(); ++i) img.values[i] = float(p.get()[i]) / 65535.0f;
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> p(
            stbi_load_from_memory(bytes->data(), size, &w, &h, &got, 0), &stbi_image_free);
        if (!p) return undecoded(*info);
        img.values.resize(n * std::size_t(got));
        for (std::size_t i = 0; i < img.values.size(); ++i) img.values[i] = float(p.get()[i]) / 255.0f;
    }
    switch (got) {
    case 1: img.channels = {"Y"}; break;
    case 2: img.channels = {"Y", "A"}; break;
    case 3: img.channels = {"R", "G", "B"}; break;
    default: img.channels = {"R", "G", "B", "A"}; break;
    }
    return img;
}

} // namespace

Result<CompareImage> io::readCompareImage(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        return makeError(ErrorCode::InvalidInput, "no such file", {}, path.string());
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".exr") return readExrChannels(path);
    if (ext == ".png") return readPngChannels(path);
    return makeError(ErrorCode::InvalidInput, "unknown image type \"" + ext + "\" (compare reads .exr or .png)",
                     {}, path.string());
}

CompareImage io::toCompareImage(const Image& image, PixelEncoding encoding, std::string source) {
    CompareImage out;
    out.width = image.width;
    out.height = image.height;
    out.encoding = encoding;
    out.source = std::move(source);
    const std::size_t n = image.pixelCount();
    if (encoding == PixelEncoding::Srgb) {
        const std::vector<unsigned char> bytes = io::pngPixels(image);
        out.channels = {"R", "G", "B", "A"};
        out.values.resize(bytes.size());
        for (std::size_t i = 0; i < bytes.size(); ++i) out.values[i] = float(bytes[i]) / 255.0f;
        return out;
    }
    out.channels = {"R", "G", "B", "A"};
    const bool depth = image.depth.size() == n, normal = image.normal.size() == n * 3;
    if (depth) out.channels.emplace_back("Z");
    if (normal) out.channels.insert(out.channels.end(), {"N.X", "N.Y", "N.Z"});
    const std::size_t nc = out.channels.size();
    out.values.resize(n * nc);
    for (std::size_t i = 0; i < n; ++i) {
        float* p = out.values.data() + i * nc;
        std::copy_n(image.rgba.data() + i * 4, 4, p);
        std::size_t c = 4;
        if (depth) p[c++] = image.depth[i];
        if (normal) std::copy_n(image.normal.data() + i * 3, 3, p + c);
    }
    return out;
}

} // namespace lantern
