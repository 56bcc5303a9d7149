// `lantern bench frame`: per-frame timing of one scene: the first frame (pipeline JIT) apart,
// then the median and minimum of N frames for render only (GPU timestamps, the wall time of
// Renderer::render, which includes readback into an Image, and of Renderer::renderView, which
// leaves the pixels where the device put them) and for render + EXR write. The camera options
// are render's. Benchmarks, not tests.
#include "bench/Bench.h"
#include "common/CliSupport.h"
#include "common/Commands.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <utility>

namespace lantern::cli {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double minimum(const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
}

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

namespace {

struct FrameArgs {
    std::string scene = "builtin:spheres";
    int width = 1280, height = 720;
    int runs = 15;
    int warmup = 2;
    std::string compression = "zip";
    bool half = false;
    std::string outDir = "/tmp";
    std::vector<std::string> aovs;  ///< --aov: time the data passes too (docs/aovs.md)
    std::string up = "y";           ///< --up
    ShadingOptions shading;
    CameraOptions camera;
    DeviceOptions device;
};

// The wall time of one renderView() frame, each row's first pixel read, as a host reading the
// frame in place would.
Result<double> timeRenderView(Renderer& renderer, const PreparedScene& scene,
                              const RenderOptions& options) {
    static volatile float sink = 0.0f;
    const auto t0 = std::chrono::steady_clock::now();
    auto view = renderer.renderView(scene, options, 0.0);
    if (!view) return std::move(view).error();
    for (int y = 0; y < view->height(); ++y) sink = sink + view->row(y)[0];
    return msSince(t0);
}

// The process's resident set now and at its peak (/proc/self/status VmRSS, VmHWM), bytes.
std::pair<std::uint64_t, std::uint64_t> residentBytes() {
    std::ifstream status("/proc/self/status");
    std::uint64_t now = 0, peak = 0;
    for (std::string line; std::getline(status, line);) {
        const auto kib = [&] { return std::strtoull(line.c_str() + 6, nullptr, 10) * 1024; };
        if (line.rfind("VmRSS:", 0) == 0) now = kib();
        if (line.rfind("VmHWM:", 0) == 0) peak = kib();
    }
    return {now, peak};
}

// The last frame's draws and clustered triangles, and the memory per triangle: the host
// scene's arrays, the device memory of the scene alone (after prepare) and with the frames'
// targets and the levels of detail, and the process's resident set.
void printCounts(const Renderer& renderer, const PreparedScene& prepared,
                 std::uint64_t sceneDeviceBytes) {
    const FrameStats& stats = renderer.lastFrameStats();
    std::printf("%-34s %10zu\n", "draw calls per frame", stats.draws);
    if (stats.clusterTriangles > 0)  // the culling pass's (and the levels of detail's) share
        std::printf("%-34s %10llu of %llu (%.1f%%)\n", "clustered triangles drawn",
                    static_cast<unsigned long long>(stats.clusterTrianglesDrawn),
                    static_cast<unsigned long long>(stats.clusterTriangles),
                    100.0 * double(stats.clusterTrianglesDrawn) / double(stats.clusterTriangles));
    const SceneSummary summary = summarize(prepared.scene());
    const double triangles = double(std::max<std::size_t>(summary.triangles, 1));
    const auto [rss, peak] = residentBytes();
    std::printf("%-34s %10s %10s\n", "memory", "MiB", "B/triangle");
    for (auto [what, bytes] : {std::pair<const char*, std::uint64_t>{"host: scene arrays", summary.hostBytes},
                               {"device: scene (after prepare)", sceneDeviceBytes},
                               {"device: all (after the frames)", renderer.deviceMemoryBytes()},
                               {"process resident now", rss},
                               {"process resident peak", peak}})
        std::printf("%-34s %10.1f %10.1f\n", what, double(bytes) / 1048576.0, double(bytes) / triangles);
}

int runFrame(const FrameArgs& a) {
    RenderOptions options;
    options.width = a.width;
    options.height = a.height;
    if (auto r = a.shading.apply(options); !r) return report(r.error());
    if (auto r = a.camera.apply(options); !r) return report(r.error());
    for (const std::string& name : a.aovs)
        if (!enableAov(options.aovs, name))
            return report(makeError(ErrorCode::InvalidInput,
                                    "unknown AOV \"" + name + "\" (" + aovNames() + ")", "--aov"));
    auto compression = parseExrCompression(a.compression);
    if (!compression)
        return report(makeError(ErrorCode::InvalidInput, "unknown compression", "--compression"));
    LoadOptions load;
    load.up = upAxisOf(a.up);
    auto scene = loadScene(a.scene, load);
    if (!scene) return report(scene.error());
    auto renderer = Renderer::create(a.device.desc());
    if (!renderer) return report(renderer.error());
    if (auto r = a.shading.checkDevice(renderer->device()); !r) return report(r.error());
    auto prepared = renderer->prepare(std::make_shared<const Scene>(std::move(*scene)));
    if (!prepared) return report(prepared.error());
    const std::uint64_t sceneDeviceBytes = renderer->deviceMemoryBytes();

    std::vector<double> wall, gpu, write, total, inPlace;  // inPlace: renderView, not with AOVs
    double firstMs = 0.0;
    const auto path = std::filesystem::path(a.outDir) / "lantern-bench-frame.exr";
    ExrOptions exr;
    exr.compression = *compression;
    exr.half = a.half;
    for (int i = 0; i < a.warmup + a.runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        auto image = renderer->render(*prepared, options, 0.0);
        if (!image) return report(image.error());
        const double renderMs = msSince(t0);
        const auto t1 = std::chrono::steady_clock::now();
        if (auto w = writeExr(path, *image, exr); !w) return report(w.error());
        const double writeMs = msSince(t1);
        if (i == 0) firstMs = renderMs;
        if (i < a.warmup) continue;
        wall.push_back(renderMs);
        gpu.push_back(renderer->lastFrameStats().gpuMs);
        write.push_back(writeMs);
        total.push_back(renderMs + writeMs);
        if (options.aovs.any()) continue;  // renderView returns colour only
        auto viewMs = timeRenderView(*renderer, *prepared, options);  // interleaved: same load
        if (!viewMs) return report(viewMs.error());
        inPlace.push_back(*viewMs);
    }
    std::error_code ec;
    std::filesystem::remove(path, ec);
    std::string aovs;
    for (const std::string& name : a.aovs) aovs += (aovs.empty() ? "" : ",") + name;
    std::printf("scene %s, %dx%d, %s, aov %s, device %s, %d runs after %d warm-up\n",
                a.scene.c_str(), a.width, a.height,
                a.shading.shading.empty() ? "scene shading" : a.shading.shading.c_str(),
                aovs.empty() ? "none" : aovs.c_str(), renderer->device().name.c_str(), a.runs,
                a.warmup);
    std::printf("%-34s %10s %10s\n", "", "median ms", "min ms");
    printCounts(*renderer, *prepared, sceneDeviceBytes);
    std::printf("%-34s %10.2f\n", "first frame (pipeline JIT)", firstMs);
    std::printf("%-34s %10.2f %10.2f\n", "render only: GPU render pass", median(gpu), minimum(gpu));
    std::printf("%-34s %10.2f %10.2f\n", "render only: render() + readback", median(wall),
                minimum(wall));
    if (!inPlace.empty())
        std::printf("%-34s %10.2f %10.2f\n", "render only: renderView (no copy)", median(inPlace),
                    minimum(inPlace));
    std::printf("%-34s %10.2f %10.2f\n",
                ("EXR write (" + a.compression + (a.half ? ", half)" : ", float)")).c_str(),
                median(write), minimum(write));
    std::printf("%-34s %10.2f %10.2f\n", "render + EXR write", median(total), minimum(total));
    return kOk;
}

} // namespace

Runner addBenchCommand(CLI::App& app) {
    CLI::App* bench = app.add_subcommand("bench", "Measure speed (and accuracy) on this machine");
    bench->require_subcommand(1);
    auto args = std::make_shared<FrameArgs>();
    CLI::App* frame = bench->add_subcommand("frame", "Time the frames of one scene");
    frame->add_option("scene", args->scene, "Scene file (glTF, GLB, OBJ, PLY, STL, OFF) or builtin:NAME")->capture_default_str();
    addSizeOptions(*frame, args->width, args->height);
    frame->add_option("--runs", args->runs, "Timed frames")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
    frame
        ->add_option("--warmup", args->warmup, "Frames before timing (the first is reported apart)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    frame->add_option("--compression", args->compression, "EXR compression for the write timing")
        ->capture_default_str();
    frame->add_flag("--half", args->half, "Time half-float EXR writes");
    frame->add_option("--aov", args->aovs, "AOVs to render and write too, comma-separated")
        ->delimiter(',');
    frame->add_option("--tmp", args->outDir, "Folder for the temporary EXR")->capture_default_str();
    addUpOption(*frame, args->up);
    args->shading.add(*frame);
    args->camera.add(*frame);
    args->device.add(*frame);
    std::vector<Runner> more = addMoreBenchCommands(*bench);
    return [args, frame, more]() {
        if (frame->parsed()) return runFrame(*args);
        for (const Runner& r : more)
            if (int code = r(); code >= 0) return code;
        return -1;
    };
}

} // namespace lantern::cli
