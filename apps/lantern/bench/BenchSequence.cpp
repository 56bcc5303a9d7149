// `lantern bench sequence`: the cost of each stage of a headless sequence and of the whole
// pipeline, per image size: render only (synchronous render() per frame, with its process CPU
// time), encode only per EXR compression (one thread, with the file size), and the full
// pipeline (double-buffered frames, encoders on every core). The pipeline is compared with
// the bound its stages set: max(render wall time, total CPU time of all stages / cores).
#include "bench/Bench.h"
#include "common/CliSupport.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <lantern/Sequence.h>
#include <sstream>
#include <sys/resource.h>
#include <thread>

namespace lantern::cli {
namespace {

double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           double(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

struct SequenceArgs {
    std::string scene = "builtin:spheres-animated";
    std::string frames = "0-119";
    double fps = 24.0;
    std::vector<int> widths = {1280, 1920}, heights = {720, 1080};
    std::vector<std::string> compressions = {"none", "rle",   "zips", "zip",
                                             "piz",  "pxr24", "b44",  "dwaa"};
    std::string pipelineCompression = "zip";
    int encodeSamples = 8;
    std::string tmp = "/tmp/lantern-bench-sequence";
    std::string markdown;
    DeviceOptions device;
};

struct Size {
    int width = 0, height = 0;
};

// Stage 1, render only: every frame, synchronously (plan, record, render, read back), keeping
// a few frames for the encode timings.
struct RenderTimes {
    std::vector<double> renderMs, gpuMs;
    std::vector<Image> samples;
    double wallMs = 0.0, cpuMs = 0.0; ///< per frame: mean wall time, mean process CPU time
};

Result<RenderTimes> timeRender(Renderer& renderer, const PreparedScene& prepared,
                               const RenderOptions& options, const FrameRange& range,
                               const SequenceArgs& a) {
    const int n = range.count();
    LANTERN_TRY(renderer.render(prepared, options, 0.0)); // warm-up
    RenderTimes t;
    const int sampleEvery = std::max(1, n / std::max(1, a.encodeSamples));
    const double cpu0 = cpuSeconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = range.first; k <= range.last; ++k) {
        const auto f0 = std::chrono::steady_clock::now();
        auto image = renderer.render(prepared, options, double(k) / a.fps);
        if (!image) return std::move(image).error();
        t.renderMs.push_back(msSince(f0));
        t.gpuMs.push_back(renderer.lastFrameStats().gpuMs);
        if ((k - range.first) % sampleEvery == 0 && int(t.samples.size()) < a.encodeSamples)
            t.samples.push_back(std::move(*image));
    }
    t.wallMs = msSince(t0) / n;
    t.cpuMs = (cpuSeconds() - cpu0) * 1000.0 / n;
    return t;
}

// Stage 2, encode only: per compression, one thread, float and half.
struct EncodeRow {
    std::string compression;
    double floatMs, floatMiB, halfMs, halfMiB;
};

Result<std::vector<EncodeRow>> timeEncode(const std::vector<Image>& samples,
                                          const SequenceArgs& a) {
    std::vector<EncodeRow> rows;
    for (const std::string& c : a.compressions) {
        auto comp = parseExrCompression(c);
        if (!comp)
            return makeError(ErrorCode::InvalidInput, "unknown compression " + c, "--compressions");
        EncodeRow row{c, 0, 0, 0, 0};
        for (bool half : {false, true}) {
            std::vector<double> ms;
            double bytes = 0;
            ExrOptions o;
            o.compression = *comp;
            o.half = half;
            const auto path = std::filesystem::path(a.tmp) / "encode.exr";
            for (const Image& img : samples) {
                const auto e0 = std::chrono::steady_clock::now();
                LANTERN_TRY(writeExr(path, img, o));
                ms.push_back(msSince(e0));
                bytes += double(std::filesystem::file_size(path));
            }
            (half ? row.halfMs : row.floatMs) = median(ms);
            (half ? row.halfMiB : row.floatMiB) = bytes / samples.size() / 1048576.0;
        }
        rows.push_back(row);
    }
    return rows;
}

// Stage 3, the full pipeline: double-buffered frames, encoders on every core.
Result<SequenceReport> timePipeline(Renderer& renderer, const PreparedScene& prepared,
                                    const RenderOptions& options, const FrameRange& range,
                                    const SequenceArgs& a) {
    SequenceOptions seq;
    seq.frames = range;
    seq.fps = a.fps;
    seq.outputs = {(std::filesystem::path(a.tmp) / "frame_####.exr").string()};
    auto pc = parseExrCompression(a.pipelineCompression);
    if (!pc)
        return makeError(ErrorCode::InvalidInput, "unknown compression", "--pipeline-compression");
    seq.exr.compression = *pc;
    auto full = renderer.renderSequence(prepared, options, seq);
    if (!full) return full;
    for (const auto& e : std::filesystem::directory_iterator(a.tmp))
        std::filesystem::remove(e.path());
    return full;
}

// One size's tables: the stages against the bound they set, and the compressions.
void sizeMarkdown(std::ostringstream& md, const SequenceArgs& a, const Size& size, int cores, int n,
                  const RenderTimes& render, const std::vector<EncodeRow>& rows,
                  const SequenceReport& full) {
    double pipelineEncodeMs = 0.0;
    for (const EncodeRow& r : rows)
        if (r.compression == a.pipelineCompression) pipelineEncodeMs = r.floatMs;
    const double fullMs = full.wallSeconds * 1000.0 / n;
    const double fullCpuMs = full.cpuSeconds * 1000.0 / n;
    const double bound = std::max(render.wallMs, (render.cpuMs + pipelineEncodeMs) / cores);
    md << "### " << size.width << "x" << size.height << "\n\n";
    md << "| stage | ms per frame |\n|---|---|\n";
    char line[256];
    std::snprintf(line, sizeof line, "| render only, wall (median / mean) | %.1f / %.1f |\n",
                  median(render.renderMs), render.wallMs);
    md << line;
    std::snprintf(line, sizeof line, "| render only, GPU render pass (median) | %.1f |\n",
                  median(render.gpuMs));
    md << line;
    std::snprintf(line, sizeof line, "| render only, process CPU time (mean) | %.1f |\n",
                  render.cpuMs);
    md << line;
    std::snprintf(line, sizeof line, "| encode only, %s float, one thread (median) | %.1f |\n",
                  a.pipelineCompression.c_str(), pipelineEncodeMs);
    md << line;
    std::snprintf(line, sizeof line, "| full pipeline, wall (%d encoder threads) | %.1f |\n", cores,
                  fullMs);
    md << line;
    std::snprintf(line, sizeof line, "| full pipeline, process CPU time | %.1f |\n", fullCpuMs);
    md << line;
    std::snprintf(line, sizeof line,
                  "| bound max(render wall, (render CPU + encode CPU) / %d cores) | %.1f |\n",
                  cores, bound);
    md << line;
    std::snprintf(line, sizeof line, "| full pipeline / bound | %.3f |\n\n", fullMs / bound);
    md << line;
    md << "| compression | float ms | float MiB | half ms | half MiB "
          "|\n|---|---|---|---|---|\n";
    for (const EncodeRow& r : rows) {
        std::snprintf(line, sizeof line, "| %s | %.1f | %.2f | %.1f | %.2f |\n",
                      r.compression.c_str(), r.floatMs, r.floatMiB, r.halfMs, r.halfMiB);
        md << line;
    }
    md << "\n";
}

int run(const SequenceArgs& a) {
    auto range = parseFrameRange(a.frames);
    if (!range) return report(range.error());
    auto loaded = loadScene(a.scene);
    if (!loaded) return report(loaded.error());
    auto renderer = Renderer::create(a.device.desc());
    if (!renderer) return report(renderer.error());
    auto prepared = renderer->prepare(std::make_shared<const Scene>(std::move(*loaded)));
    if (!prepared) return report(prepared.error());
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    std::filesystem::create_directories(a.tmp);
    std::ostringstream md;
    md << "Scene " << a.scene << ", frames " << a.frames << " at " << a.fps << " fps, device "
       << renderer->device().name << ", " << cores << " cores.\n\n";

    auto sizes = pairSizes(a.widths, a.heights);
    if (!sizes) return report(sizes.error());
    for (const auto& [width, height] : *sizes) {
        const Size size{width, height};
        RenderOptions options;
        options.width = size.width;
        options.height = size.height;
        auto render = timeRender(*renderer, *prepared, options, *range, a);
        if (!render) return report(render.error());
        auto encode = timeEncode(render->samples, a);
        if (!encode) return report(encode.error());
        auto full = timePipeline(*renderer, *prepared, options, *range, a);
        if (!full) return report(full.error());
        sizeMarkdown(md, a, size, cores, range->count(), *render, *encode, *full);
        std::fputs(md.str().c_str(), stdout);
        std::fflush(stdout);
        md.str("");
    }
    std::error_code ec;
    std::filesystem::remove_all(a.tmp, ec);
    return kOk;
}

} // namespace

Runner addSequenceBench(CLI::App& bench) {
    auto args = std::make_shared<SequenceArgs>();
    CLI::App* cmd = bench.add_subcommand(
        "sequence", "Time the stages of a headless sequence and the whole pipeline");
    cmd->add_option("scene", args->scene, "An animated scene")->capture_default_str();
    cmd->add_option("--frames", args->frames)->capture_default_str();
    cmd->add_option("--fps", args->fps)->capture_default_str();
    addSizeListOptions(*cmd, args->widths, args->heights);
    cmd->add_option("--compressions", args->compressions, "EXR compressions to time")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--pipeline-compression", args->pipelineCompression)->capture_default_str();
    cmd->add_option("--encode-samples", args->encodeSamples, "Frames each compression is timed on")
        ->capture_default_str();
    cmd->add_option("--tmp", args->tmp, "Scratch folder (removed afterwards)")
        ->capture_default_str();
    args->device.add(*cmd);
    return [args, cmd]() { return cmd->parsed() ? run(*args) : -1; };
}

} // namespace lantern::cli
