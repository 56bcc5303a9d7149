// Image encoding and texture preparation on the host, part of lantern_microbench: EXR and PNG
// writes (what a sequence's encode stage and a one-shot PNG pay), the sRGB quantiser, and the
// host-made mip chain of a texture. Compare rows of one run (ratios), never absolute numbers
// across runs (docs/performance.md).
#include "gpu/TextureMips.h"
#include "io/image/ImageEncode.h"
#include "math/Srgb.h"

#include <lantern/Lantern.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using namespace lantern;
namespace fs = std::filesystem;

// A smooth gradient with a highlight, like a rendered frame; with a depth plane when asked.
Image renderedLikeImage(int w, int h, bool depth) {
    Image image(w, h);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            float* p = image.pixel(x, y);
            const double dx = (x - 0.625 * w) / (w / 10.7), dy = (y - 0.42 * h) / (w / 10.7);
            const float highlight = float(std::exp(-(dx * dx + dy * dy)));
            p[0] = 0.2f + 0.6f * float(x) / float(image.width) + highlight;
            p[1] = 0.1f + 0.5f * float(y) / float(image.height) + highlight;
            p[2] = 0.3f + highlight;
            p[3] = 1.0f;
        }
    if (depth)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) image.depth.push_back(3.0f + 0.002f * float(x) + 0.001f * float(y * y % 97));
    return image;
}

// Times writeExr of `image` with `options`; the file's size is a counter.
void timeExrWrites(benchmark::State& state, const Image& image, const ExrOptions& options) {
    const fs::path path = fs::temp_directory_path() /
                          ("lantern-microbench-" + std::to_string(::getpid()) + ".exr");
    for (auto _ : state) {
        auto written = writeExr(path, image, options);
        if (!written) {
            state.SkipWithError(written.error().describe().c_str());
            break;
        }
    }
    std::error_code ec;
    state.counters["MiB"] = double(fs::file_size(path, ec)) / (1024.0 * 1024.0);
    fs::remove(path, ec);
}

// Writing a 640x360 float EXR per compression, one thread: the encode stage of a sequence.
void BM_WriteExr(benchmark::State& state) {
    const auto compression = ExrCompression(state.range(0));
    ExrOptions options;
    options.compression = compression;
    options.threads = 1;
    timeExrWrites(state, renderedLikeImage(640, 360, false), options);
    state.SetLabel(toString(compression));
}
BENCHMARK(BM_WriteExr)
    ->Arg(int(ExrCompression::None))
    ->Arg(int(ExrCompression::Zip))
    ->Arg(int(ExrCompression::Piz))
    ->Arg(int(ExrCompression::Dwaa))
    ->Unit(benchmark::kMillisecond);

// A 1920x1080 float EXR with depth, zip, side by side: OpenEXR's default zlib level (4) and
// Lantern's (2), on one thread (Arg 1) and on OpenEXR's pool over every core (Arg 0).
void BM_WriteExr1080p(benchmark::State& state) {
    ExrOptions options;
    options.zipLevel = int(state.range(0));
    options.threads = int(state.range(1));
    timeExrWrites(state, renderedLikeImage(1920, 1080, true), options);
    state.SetLabel("zip level " + std::to_string(options.zipLevel) +
                   (options.threads == 1 ? ", 1 thread" : ", every core"));
}
BENCHMARK(BM_WriteExr1080p)
    ->Args({4, 1})
    ->Args({2, 1})
    ->Args({4, 0})
    ->Args({2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The float-to-8-bit sRGB conversion of a 1920x1080 PNG (io::pngPixels's inner step), with
// the formula (std::pow per channel, Arg 0) and with the step table Lantern uses (Arg 1), side
// by side in one run.
void BM_Srgb8(benchmark::State& state) {
    const bool table = state.range(0) == 1;
    std::vector<float> values(std::size_t(1920) * 1080 * 3);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = float(i % 4099) / 4098.0f * 1.2f;  // 0 to 1.2, every code
    std::vector<unsigned char> out(values.size());
    for (auto _ : state) {
        if (table)
            for (std::size_t i = 0; i < values.size(); ++i) out[i] = math::srgb8(values[i]);
        else
            for (std::size_t i = 0; i < values.size(); ++i) out[i] = math::srgb8Reference(values[i]);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetLabel(table ? "step table" : "pow");
}
BENCHMARK(BM_Srgb8)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A 1920x1080 PNG encoded (conversion and libpng, in memory), a rendered-like image: with
// libpng's default compression (level 6, every filter per row: Arg 0) and with Lantern's
// (level 2, the Up filter: Arg 1), side by side in one run. KiB: the file's size.
void BM_WritePng(benchmark::State& state) {
    Image image(1920, 1080);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            float* p = image.pixel(x, y);
            const double dx = (x - 960.0) / 400.0, dy = (y - 540.0) / 400.0;
            const double r2 = dx * dx + dy * dy;
            const float lit = r2 < 1.0 ? float(0.1 + 0.8 * std::max(0.0, 0.5 * dx + 0.7 * std::sqrt(1.0 - r2))) : 0.02f;
            p[0] = lit;
            p[1] = 0.8f * lit;
            p[2] = 0.6f * lit;
            p[3] = 1.0f;
        }
    io::PngEncoding encoding;
    if (state.range(0) == 0) encoding = io::PngEncoding{6, true};
    std::size_t bytes = 0;
    for (auto _ : state) {
        auto encoded = io::encodePng(image, encoding);
        if (!encoded) {
            state.SkipWithError(encoded.error().describe().c_str());
            break;
        }
        bytes = encoded->size();
    }
    state.counters["KiB"] = double(bytes) / 1024.0;
    state.SetLabel(state.range(0) == 0 ? "libpng default (6, all filters)" : "Lantern (2, up)");
}
BENCHMARK(BM_WritePng)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The whole mip chain of a 1024x1024 RGBA8 texture made on the host (gpu/TextureMips.h), as
// colour (sRGB, averaged in linear light: Arg 1) and as data (Arg 0): what a textured model's
// upload pays per texture.
void BM_TextureMips(benchmark::State& state) {
    const bool srgb = state.range(0) == 1;
    const int side = 1024;
    std::vector<std::uint8_t> level0(std::size_t(side) * side * 4);
    for (std::size_t i = 0; i < level0.size(); ++i)
        level0[i] = std::uint8_t((i * 2654435761u) >> 24);
    std::vector<std::uint8_t> from, to;
    for (auto _ : state) {
        const std::uint8_t* src = level0.data();
        int w = side, h = side;
        for (std::uint32_t m = 1; m < gpu::mipLevelCount(side, side); ++m) {
            const int nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
            to.resize(std::size_t(nw) * std::size_t(nh) * 4);
            gpu::downsampleRgba8(src, w, h, to.data(), nw, nh, srgb);
            from.swap(to);
            src = from.data();
            w = nw;
            h = nh;
        }
        benchmark::DoNotOptimize(from.data());
    }
    state.SetLabel(srgb ? "srgb" : "data");
}
BENCHMARK(BM_TextureMips)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
