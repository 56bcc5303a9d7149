// `lantern render SCENE`: headless rendering to EXR/PNG (docs/cli.md).
#include "common/FidelityReport.h"
#include "common/TextFile.h"
#include "common/CliSupport.h"
#include "common/Commands.h"
#include "common/CompareCli.h"
#include "common/CvCameraCli.h"
#include "render/Batch.h"
#include "render/RenderArgs.h"
#include "render/RenderOutput.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>
#include <memory>
#include <optional>

namespace lantern::cli {
namespace {

// The frames of a sequence (--frames or --frame-list, --shard) and where they go.
Result<SequenceOptions> sequenceOptions(const RenderArgs& a, const ExrOptions& exr,
                                        const std::vector<std::string>& outputs) {
    SequenceOptions seq;
    if (!a.frameList.empty()) {
        auto list = parseFrameList(a.frameList);
        if (!list) return std::move(list).error();
        seq.frameList = std::move(*list);
    } else {
        auto range = parseFrameRange(a.frames);
        if (!range) return std::move(range).error();
        seq.frames = *range;
    }
    std::optional<Shard> given;
    if (!a.shard.empty()) {
        auto shard = parseShard(a.shard);
        if (!shard) return std::move(shard).error();
        given = *shard;
    }
    auto mine = workerShard(given);  // one of --processes' processes: its part
    if (!mine) return std::move(mine).error();
    if (*mine) seq.shard = **mine;
    seq.fps = a.fps;
    seq.outputs = outputs;
    seq.exr = exr;
    seq.encoderThreads = a.encoderThreads;
    seq.writeCamera = a.writeCamera;
    return seq;
}

// The AOV names of --aov (docs/aovs.md) into `aovs`.
Result<void> parseAovs(const std::vector<std::string>& items, AovSet& aovs) {
    for (const std::string& item : items)
        if (!enableAov(aovs, item))
            return makeError(ErrorCode::InvalidInput,
                             "unknown AOV \"" + item + "\" (" + aovNames() + ")", "--aov");
    return {};
}

// The options of the picture: size, scene, shading, camera, background and AOVs.
Result<RenderOptions> renderOptions(const RenderArgs& a) {
    RenderOptions options;
    options.width = a.width;
    options.height = a.height;
    options.root = a.sceneIndex;
    LANTERN_TRY(a.shading.apply(options));
    LANTERN_TRY(a.camera.apply(options));
    if (!a.background.empty()) {
        auto background = parseBackground(a.background);
        if (!background) return std::move(background).error();
        options.background = *background;
    }
    LANTERN_TRY(parseAovs(a.aovs, options.aovs));
    options.aovs.cryptomatteLevels = a.cryptomatteLevels;
    options.aovs.cryptomatteSamples = a.cryptomatteSamples;
    if (a.unlitExact) {
        if (options.msaa != 1)
            return makeError(ErrorCode::Usage, "--unlit-exact needs --msaa 1 (no anti-aliasing)",
                             "--unlit-exact");
        if (a.half)
            return makeError(ErrorCode::Usage,
                             "--unlit-exact needs 32-bit float channels: --half rounds the colours",
                             "--unlit-exact");
        options.unlitExact = true;
    }
    return options;
}

// --probe X,Y: a whole pixel inside the image.
Result<std::pair<int, int>> probePixel(const RenderArgs& a) {
    auto xy = parseNumbers(a.probe, 2, "--probe");
    if (!xy) return std::move(xy).error();
    const double x = (*xy)[0], y = (*xy)[1];
    if (x != std::floor(x) || y != std::floor(y) || x < 0 || y < 0 || x >= a.width ||
        y >= a.height)
        return makeError(ErrorCode::InvalidInput,
                         "pixel " + a.probe + " is not a whole pixel inside the " +
                             std::to_string(a.width) + "x" + std::to_string(a.height) + " image",
                         "--probe");
    return std::pair<int, int>{int(x), int(y)};
}

// --dry-run: what would be rendered and written, on stdout; nothing is.
int reportDryRun(const RenderArgs& a, const Scene& scene, const std::optional<SequenceOptions>& seq,
                 const SingleFrame& frame, const std::vector<std::string>& outputs) {
    std::vector<int> frames;
    if (seq)
        frames = sequenceFrames(*seq);
    else
        frames.push_back(frame.number);
    std::cout << "dry run: " << a.scenes.front() << " (" << scene.nodes.size() << " nodes, "
              << scene.meshes.size() << " meshes), " << frames.size() << " frame"
              << (frames.size() == 1 ? "" : "s") << " of " << a.width << "x" << a.height << "\n";
    const std::size_t shown = std::min<std::size_t>(frames.size(), 3);
    for (std::size_t i = 0; i < shown; ++i)
        for (const std::string& out : outputs) {
            std::cout << "  would write " << expandFramePattern(out, frames[i]) << "\n";
            if (a.writeCamera)
                std::cout << "  would write "
                          << cameraFilePath(expandFramePattern(out, frames[i])).string() << "\n";
        }
    if (frames.size() > shown)
        std::cout << "  ... and " << frames.size() - shown << " more frames\n";
    return kOk;
}

// --explain and --probe: what the renderer will do, and the lighting equation at one pixel
// (`probe`, checked by probePixel).
Result<void> explainAndProbe(const RenderArgs& a, Renderer& renderer, const Scene& scene,
                             const RenderOptions& options, double time,
                             const std::optional<std::pair<int, int>>& probe) {
    if (a.explain) {
        auto explained = renderer.explain(scene, options, time);
        if (!explained) return std::move(explained).error();
        std::cout << "features:\n";
        for (const auto& f : explained->features)
            std::cout << "  " << f << "\n";
        std::cout << "pipeline variants:\n";
        for (const auto& v : explained->variants)
            std::cout << "  " << v << "\n";
    }
    if (probe) {
        auto probed = renderer.probe(scene, options, time, probe->first, probe->second);
        if (!probed) return std::move(probed).error();
        printProbe(std::cout, *probed);
    }
    return {};
}

// True when every output is a PNG and nothing needs the float picture (a camera file, a
// comparison, AOV planes): the 8-bit rows are then made from the frame in place.
bool pngFromView(const RenderArgs& a, const RenderOptions& o, const std::vector<std::string>& patterns) {
    if (a.writeCamera || !a.compareRef.empty() || o.aovs.any() || o.aovs.anyCryptomatte()) return false;
    return std::all_of(patterns.begin(), patterns.end(), [](const std::string& p) {
        std::string ext = std::filesystem::path(p).extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        return ext == ".png";
    });
}

// One frame, written to every output with its '#' runs replaced by the frame number (the
// paths on stdout).
int renderFrame(const RenderArgs& a, const SingleFrame& frame, Renderer& renderer,
                const PreparedScene& prepared, const RenderOptions& options, ExrOptions exr,
                const std::vector<std::string>& patterns) {
    if (pngFromView(a, options, patterns)) {
        // Band by band (Renderer::renderBands): each band's rows are compressed while the
        // next band renders, and the device holds two bands of pixels, not the picture.
        std::vector<PngStream> streams;
        for (const std::string& pattern : patterns) {
            auto stream = PngStream::create(expandFramePattern(pattern, frame.number),
                                            options.width, options.height);
            if (!stream) return report(stream.error());
            streams.push_back(std::move(*stream));
        }
        auto rendered = renderer.renderBands(prepared, options, frame.time, 0,
                                             [&](const FrameView& band, int) -> Result<void> {
                                                 for (PngStream& s : streams)
                                                     LANTERN_TRY(s.write(band));
                                                 return {};
                                             });
        if (!rendered) return report(rendered.error());
        for (std::size_t i = 0; i < patterns.size(); ++i) {
            if (auto w = streams[i].finish(); !w) return report(w.error());
            std::cout << expandFramePattern(patterns[i], frame.number) << "\n";
        }
        return kOk;
    }
    auto image = renderer.render(prepared, options, frame.time);
    if (!image) return report(image.error());
    for (const auto& [key, value] : image->metadata)
        if (key == "lantern:warning") std::cerr << "lantern: warning: " << value << "\n";
    for (const std::string& pattern : patterns) {
        const std::string out = expandFramePattern(pattern, frame.number);
        std::uint64_t clamped = 0;
        exr.clampedCount = &clamped;
        // The camera first: a finished image always has its camera beside it.
        if (a.writeCamera)
            if (auto w = writeImageCamera(out, *image); !w) return report(w.error());
        if (auto w = writeImage(out, *image, exr); !w) return report(w.error());
        if (clamped > 0)
            std::cerr << "lantern: warning: " << out << ": " << clamped
                      << " values exceeded the half range and were clamped to 65504\n";
        std::cout << out << "\n";
    }
    if (!a.compareRef.empty())
        return compareRendered(a.compare, a.compareRef, *image,
                               expandFramePattern(patterns.front(), frame.number));
    return kOk;
}

// The first frame of a sequence (0 when the range or list does not parse: runSequence says why).
int firstFrame(const RenderArgs& a) {
    if (!a.frameList.empty()) {
        auto list = parseFrameList(a.frameList);
        return list && !list->empty() ? list->front() : 0;
    }
    auto range = parseFrameRange(a.frames);
    return range ? range->first : 0;
}

// The instant of a single-frame render and the number its '#' runs are replaced by: --frame N
// (time N / fps), or --time T (frame round(T * fps)), or frame 0 at time 0.
Result<SingleFrame> singleFrame(const RenderArgs& a) {
    if (!a.shard.empty()) return makeError(ErrorCode::Usage, "--shard needs --frames", "--shard");
    if (a.frameGiven && a.timeGiven)
        return makeError(ErrorCode::Usage, "give either --frame or --time", "--frame");
    if (a.frameGiven) return SingleFrame{double(a.frame) / a.fps, a.frame};
    const double number = std::round(a.time * a.fps);
    if (!std::isfinite(a.time) || std::abs(number) > 1e9)
        return makeError(ErrorCode::InvalidInput, "time must be a finite number of seconds",
                         "--time");
    return SingleFrame{a.time, int(number)};
}

// The options and the image size a camera file sets (into `a`), with --write-camera's checks.
Result<RenderOptions> renderOptionsAndSize(RenderArgs& a) {
    auto options = renderOptions(a);
    if (!options) return options;
    LANTERN_TRY(takeCameraSize(options->camera, a.widthGiven, a.heightGiven, a.width, a.height));
    options->width = a.width;
    options->height = a.height;
    if (a.writeCamera && !options->views.empty())
        return makeError(ErrorCode::Usage,
                         "a camera file describes one view: not with --viewport or --layout",
                         "--write-camera");
    return options;
}

// The EXR options (--half, --compression, --zip-level).
Result<ExrOptions> exrOptions(const RenderArgs& a) {
    ExrOptions exr;
    exr.half = a.half;
    const auto compression = parseExrCompression(a.compression);
    if (!compression)
        return makeError(ErrorCode::InvalidInput, "unknown compression \"" + a.compression + "\"",
                         "--compression");
    exr.compression = *compression;
    exr.zipLevel = a.zipLevel;
    return exr;
}

// A batch (render/Batch.h): many scenes times many views on one device.
int runBatchArgs(RenderArgs a) {
    const char* single = !a.compareRef.empty() ? "--compare"
                         : !a.probe.empty()    ? "--probe"
                         : a.explain           ? "--explain"
                                               : nullptr;
    if (auto c = checkBatchOptions(a.batch, a.camera, single); !c) return report(c.error());
    auto options = renderOptionsAndSize(a);
    if (!options) return report(options.error());
    auto exr = exrOptions(a);
    if (!exr) return report(exr.error());
    if (int(!a.frames.empty()) + int(!a.frameList.empty()) + int(a.frameGiven) + int(a.timeGiven) > 1)
        return report(makeError(ErrorCode::Usage,
                                "give one of --frames, --frame-list, --frame and --time", "--frames"));
    if (!(a.time >= 0.0 && a.time <= 1e9))
        return report(makeError(ErrorCode::InvalidInput,
                                "must be a number of seconds from 0 to 1e9", "--time"));
    BatchRequest r{a.scenes, a.batch.lists, a.batch.views, a.outputs};
    if (r.outputs.empty())
        r.outputs.push_back(std::string("out/{scene}") + (a.batch.views.empty() ? "" : "_{view}") +
                            (a.frames.empty() && a.frameList.empty() ? "" : "_####") + ".exr");
    if (auto p = checkImagePaths(r.outputs, "--output"); !p) return report(p.error());
    auto frames = batchFrames(a.frames, a.frameList, a.fps,
                              a.frameGiven ? std::optional<int>(a.frame) : std::nullopt, a.time);
    if (!frames) return report(frames.error());
    r.frames = std::move(*frames);
    if (!a.shard.empty()) {
        auto shard = parseShard(a.shard);
        if (!shard) return report(shard.error());
        r.shard = *shard;
    }
    auto mine = workerShard(r.shard);
    if (!mine) return report(mine.error());
    r.shard = *mine;
    r.overwrite = a.batch.overwrite;
    r.dryRun = a.dryRun;
    r.writeCamera = a.writeCamera;
    r.options = *options;
    r.exr = *exr;
    r.load = a.file.load(stderrSink(a.device.verbose));
    r.device = a.device.desc();
    r.verbose = a.device.verbose;
    r.checkDevice = [&a](const DeviceInfo& d) { return a.shading.checkDevice(d); };
    const int processes = processCount(a.batch.processes);
    return processes > 1 && !r.dryRun ? runProcesses(processes) : runBatch(r);
}

// --report FILE: what the file uses and how this render draws each (the shading it is
// drawn with decides what gouraud and flat approximate).
Result<void> writeFidelityReport(const RenderArgs& a, const Scene& scene, const RenderOptions& o) {
    // The shading the frame resolves (options over the scene's LANTERN_lighting, --gl-compat).
    auto explained = explainScene(scene, o, 0.0);
    if (!explained) return std::move(explained).error();
    ShadingMode shading = ShadingMode::Phong;
    for (const std::string& f : explained->features)
        if (f.rfind("shading:", 0) == 0)
            if (auto m = parseShadingMode(std::string_view(f).substr(8))) shading = *m;
    const auto parent = std::filesystem::path(a.report).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    return writeTextFile(a.report, sceneReport(a.scenes.front(), scene, shading).dump(2) + "\n");
}

// The renderer, made on a thread of its own while the scene loads (the two take about as long
// on a 2-core machine, docs/performance.md); none for --dry-run. A scene that fails to load is
// reported first; the renderer is then waited for and dropped.
std::future<Result<Renderer>> startRenderer(const RenderArgs& a) {
    if (a.dryRun) return {};
    return std::async(std::launch::async,
                      [device = a.device.desc()] { return Renderer::create(device); });
}

// --frames, --frame-list, --time and --frame: which go together, and --time's range.
Result<void> checkFrameOptions(const RenderArgs& a, bool sequence) {
    if (!a.frames.empty() && !a.frameList.empty())
        return makeError(ErrorCode::Usage, "--frames and --frame-list cannot be combined",
                         "--frame-list");
    if (sequence && (a.timeGiven || a.frameGiven))
        return makeError(ErrorCode::Usage,
                         std::string(a.timeGiven ? "--time" : "--frame") +
                             " and --frames/--frame-list cannot be combined",
                         a.timeGiven ? "--time" : "--frame");
    // CLI11's range check lets NaN through (every comparison with it is false).
    if (!(a.time >= 0.0 && a.time <= 1e9))
        return makeError(ErrorCode::InvalidInput, "must be a number of seconds from 0 to 1e9",
                         "--time");
    return {};
}

int run(RenderArgs a) {
    auto options = renderOptionsAndSize(a);
    if (!options) return report(options.error());
    auto exrChecked = exrOptions(a);
    if (!exrChecked) return report(exrChecked.error());
    const ExrOptions exr = *exrChecked;
    const bool sequence = !a.frames.empty() || !a.frameList.empty();
    if (auto r = checkFrameOptions(a, sequence); !r) return report(r.error());
    std::vector<std::string> outputs = a.outputs;
    if (outputs.empty()) outputs.push_back(sequence ? "out/frame_####.exr" : "out/render.exr");
    if (auto r = checkImagePaths(outputs, "--output"); !r) return report(r.error());
    SingleFrame frame;
    if (!sequence) {
        auto f = singleFrame(a);
        if (!f) return report(f.error());
        frame = *f;
        if (frame.number < 0 && std::any_of(outputs.begin(), outputs.end(), [](const auto& o) {
                return hasFramePattern(o);
            }))
            return report(makeError(ErrorCode::Usage,
                                    "the frame number of --time " + std::to_string(a.time) +
                                        " is negative; '#' runs need a frame >= 0",
                                    "--output"));
    }
    if (!a.compareRef.empty()) {
        if (sequence)
            return report(makeError(ErrorCode::Usage, "--compare renders one frame, not --frames", "--compare"));
        if (auto o = a.compare.options(); !o) return report(o.error());
    }
    std::optional<SequenceOptions> seq;
    if (sequence) {
        auto s = sequenceOptions(a, exr, outputs);
        if (!s) return report(s.error());
        seq = std::move(*s);
    }
    std::optional<std::pair<int, int>> probe;
    if (!a.probe.empty()) {
        auto xy = probePixel(a);
        if (!xy) return report(xy.error());
        probe = *xy;
    }

    const LoadOptions load = a.file.load(stderrSink(a.device.verbose));
    std::future<Result<Renderer>> pendingRenderer = startRenderer(a);
    auto scene = loadScene(a.scenes.front(), load);
    if (!scene) return report(scene.error());
    auto shared = std::make_shared<const Scene>(std::move(*scene));
    // A valid file may draw nothing: say why the image is only the background.
    if (auto why = nothingToDraw(*shared, options->root))
        std::cerr << "lantern: warning: " << a.scenes.front() << ": nothing to draw (" << *why
                  << "); the image is the background\n";

    if (!a.report.empty())
        if (auto r = writeFidelityReport(a, *shared, *options); !r) return report(r.error());
    if (a.dryRun) return reportDryRun(a, *shared, seq, frame, outputs);

    auto renderer = pendingRenderer.get();
    if (!renderer) return report(renderer.error());
    if (a.device.verbose)
        std::cerr << "lantern: device: " << renderer->device().name << " ("
                  << renderer->device().driver << ")\n";
    if (auto r = a.shading.checkDevice(renderer->device()); !r) return report(r.error());
    if (auto r = explainAndProbe(a, *renderer, *shared, *options, frame.time, probe); !r)
        return report(r.error());
    auto prepared = renderer->prepare(shared);
    if (!prepared) return report(prepared.error());
    if (auto r = makeParentFolders(outputs, sequence ? firstFrame(a) : frame.number, "--output");
        !r)
        return report(r.error());
    if (seq) return runSequence(*renderer, *prepared, *options, std::move(*seq));
    return renderFrame(a, frame, *renderer, *prepared, *options, exr, outputs);
}

} // namespace

Runner addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene headless to EXR/PNG");
    addRenderOptions(*cmd, *args);
    return [args, cmd]() {
        if (!cmd->parsed()) return -1;
        if (auto r = takeParsedRenderOptions(*cmd, *args); !r) return report(r.error());
        const RenderArgs& a = *args;
        const bool batch = wantsBatch(a.scenes, a.batch.lists, a.batch.views, a.outputs);
        const bool sequence = !a.frames.empty() || !a.frameList.empty();
        if (!batch && !sequence && a.batch.processes != 1)
            std::fprintf(stderr, "lantern: warning: --processes splits batches and sequences; "
                                 "one picture renders in one process\n");
        if (!batch && sequence && !a.dryRun)
            if (const int n = processCount(a.batch.processes); n > 1) return runProcesses(n);
        return batch ? runBatchArgs(a) : run(a);
    };
}

} // namespace lantern::cli
