// lantern_comparebench: what `lantern compare` costs per metric on a synthetic EXR pair
// (default 1920x1080 RGBA float: smooth shapes, an HDR highlight, noise; the test image
// differs by small noise in 5% of its pixels). docs/testing-with-lantern.md has the results
// and the command. The file read is timed apart from the metrics.
#include <lantern/Lantern.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <string>

namespace {

using namespace lantern;
namespace fs = std::filesystem;

struct Pair {
    fs::path ref, test;
    CompareImage a, b;
};

// The pair for width x height, written once as EXR files and read back.
const Pair& pair(int w, int h) {
    static std::map<std::pair<int, int>, Pair> pairs;
    auto [it, fresh] = pairs.try_emplace({w, h});
    if (!fresh) return it->second;
    Image ref(w, h), test(w, h);
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> noise(-0.01f, 0.01f), pick(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = ref.pixel(x, y);
            const float u = float(x) / float(w), v = float(y) / float(h);
            p[0] = 0.5f + 0.4f * std::sin(12.0f * u) * std::cos(7.0f * v);
            p[1] = 0.5f + 0.4f * std::sin(5.0f * u + 9.0f * v);
            p[2] = ((x / 32 + y / 32) % 2) ? 0.8f : 0.1f;
            const float d = (u - 0.7f) * (u - 0.7f) + (v - 0.3f) * (v - 0.3f);
            if (d < 0.01f) p[0] = p[1] = p[2] = 8.0f;  // an HDR highlight
            p[3] = 1.0f;
            float* q = test.pixel(x, y);
            for (int c = 0; c < 4; ++c) q[c] = p[c] + (c < 3 && pick(rng) < 0.05f ? noise(rng) : 0.0f);
        }
    Pair& pr = it->second;
    const fs::path dir = fs::temp_directory_path();
    pr.ref = dir / ("lantern_comparebench_ref_" + std::to_string(w) + ".exr");
    pr.test = dir / ("lantern_comparebench_test_" + std::to_string(w) + ".exr");
    if (!writeExr(pr.ref, ref) || !writeExr(pr.test, test)) std::abort();
    pr.a = *readCompareImage(pr.ref);
    pr.b = *readCompareImage(pr.test);
    return pr;
}

void BM_CompareReadExrPair(benchmark::State& state) {
    const Pair& p = pair(int(state.range(0)), int(state.range(1)));
    for (auto _ : state) {
        auto a = readCompareImage(p.ref);
        auto b = readCompareImage(p.test);
        benchmark::DoNotOptimize(a->values.data());
        benchmark::DoNotOptimize(b->values.data());
    }
}

// metric: 0 abs (max, mean, PSNR, shares: always computed), 1 + SSIM, 2 + LDR-FLIP, 3 + HDR-FLIP
void BM_Compare(benchmark::State& state, int metric) {
    const Pair& p = pair(int(state.range(0)), int(state.range(1)));
    CompareOptions o;
    o.ssim = metric == 1;
    o.flip = metric == 2 ? FlipForm::Ldr : metric == 3 ? FlipForm::Hdr : FlipForm::Off;
    double abs = 0, ssim = 0, flip = 0, exposures = 0;
    for (auto _ : state) {
        auto r = compareImages(p.a, p.b, o);
        if (!r) std::abort();
        abs += r->secondsAbs;
        ssim += r->secondsSsim;
        flip += r->secondsFlip;
        exposures = r->flip ? r->flip->exposures : 0;
    }
    const double n = double(state.iterations());
    state.counters["abs_ms"] = 1e3 * abs / n;
    if (metric == 1) state.counters["ssim_ms"] = 1e3 * ssim / n;
    if (metric >= 2) state.counters["flip_ms"] = 1e3 * flip / n;
    if (metric == 3) state.counters["exposures"] = exposures;
}

#define LANTERN_COMPARE_SIZES ->Args({1920, 1080})->Args({64, 64})->Unit(benchmark::kMillisecond)->UseRealTime()
BENCHMARK(BM_CompareReadExrPair) LANTERN_COMPARE_SIZES;
BENCHMARK_CAPTURE(BM_Compare, abs, 0) LANTERN_COMPARE_SIZES;
BENCHMARK_CAPTURE(BM_Compare, ssim, 1) LANTERN_COMPARE_SIZES;
BENCHMARK_CAPTURE(BM_Compare, flip_ldr, 2) LANTERN_COMPARE_SIZES;
BENCHMARK_CAPTURE(BM_Compare, flip_hdr, 3) LANTERN_COMPARE_SIZES;

} // namespace

BENCHMARK_MAIN();
