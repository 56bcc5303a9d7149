// `lantern bench accuracy`: the speed-versus-accuracy sweep (numerics.md section 7). Shading
// mode x tessellation x MSAA x resolution (x shininess) on the analytic scenes S1 and S2, each
// configuration timed interleaved with the others and compared with a double-precision ray
// cast of the exact surfaces. Writes a CSV (one row per configuration), an SVG plot (error
// against ms per frame, Pareto fronts marked) and a markdown summary naming, per error budget,
// the fastest setting that meets it.
#include "bench/BenchAccuracy.h"

#include "bench/BenchHarness.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <tuple>

namespace lantern::cli {

std::string AccuracyRow::group() const {
    return scene + ", shininess " + num(shininess, "%g") + ", " + std::to_string(width) + "x" +
           std::to_string(height);
}

std::string AccuracyRow::setting() const {
    return std::string(toString(shading)) + ", " + std::to_string(segments) +
           (scene == "spot" ? " subdivisions" : " segments") + ", " + std::to_string(msaa) + "x";
}

void markParetoFronts(std::vector<AccuracyRow>& rows) {
    auto mark = [&](auto error, auto flag) {
        for (AccuracyRow& r : rows) {
            const double e = error(r);
            bool dominated = !std::isfinite(e);
            for (const AccuracyRow& o : rows) {
                if (dominated) break;
                if (&o == &r || o.group() != r.group()) continue;
                const double oe = error(o);
                dominated = o.ms <= r.ms && oe <= e && (o.ms < r.ms || oe < e);
            }
            flag(r) = !dominated;
        }
    };
    mark([](const AccuracyRow& r) { return r.error.interior.rmse; },
         [](AccuracyRow& r) -> bool& { return r.paretoInterior; });
    mark([](const AccuracyRow& r) { return r.error.whole.rmse; },
         [](AccuracyRow& r) -> bool& { return r.paretoWhole; });
}

namespace {

struct AccuracyArgs {
    std::vector<std::string> scenes{"sphere", "spot"};
    std::vector<double> shininess{128.0};
    std::vector<std::string> shading{"flat", "gouraud", "phong"};
    std::vector<int> segments{8, 16, 32, 64, 128, 256, 512};
    std::vector<int> msaa{1, 4};
    std::vector<std::string> resolutions{"960x540", "1920x1080"};
    TimingOptions timing;
    int referenceSamples = 8;
    bool noFloor = false;
    DeviceOptions device;
    CLI::Option *segmentsOption = nullptr, *resolutionsOption = nullptr;
};

// The reduced sweep of --quick: every mode and scene, a few tessellations, small images.
void applyQuick(AccuracyArgs& a) {
    if (!a.timing.quick) return;
    if (!a.segmentsOption->count()) a.segments = {8, 16, 32, 64, 128, 256};
    if (!a.resolutionsOption->count()) a.resolutions = {"480x270"};
    a.timing.applyQuick(a.timing.plan.rounds, 3);
}

std::string csvHeader() {
    return "scene,shininess,width,height,shading,segments,triangles,msaa,ms_per_frame,ms_min,"
           "ms_wall,ms_round_spread,first_frame_ms,pipelines_compiled,floor_ms,x_floor,rmse,psnr_"
           "db,max_error,"
           "interior_pixels,interior_rmse,interior_max,interior_p99,silhouette_pixels,"
           "silhouette_rmse,silhouette_max,silhouette_p99,peak_ratio,nonfinite,pareto_interior,"
           "pareto_whole\n";
}

std::string csvRow(const AccuracyRow& r) {
    const ErrorMetrics& e = r.error;
    const bool floor = r.floorMs > 0.0;
    std::ostringstream s;
    s << r.scene << ',' << num(r.shininess, "%g") << ',' << r.width << ',' << r.height << ','
      << toString(r.shading) << ',' << r.segments << ',' << r.triangles << ',' << r.msaa << ','
      << num(r.ms) << ',' << num(r.msMin) << ',' << num(r.msWall) << ',' << num(r.spread, "%.3f")
      << ',' << num(r.firstMs) << ',' << r.pipelines << ',' << (floor ? num(r.floorMs) : "") << ','
      << (floor ? num(r.ms / r.floorMs) : "") << ',' << num(e.whole.rmse) << ','
      << num(e.psnr, "%.2f") << ',' << num(e.whole.max) << ',' << e.interior.pixels << ','
      << num(e.interior.rmse) << ',' << num(e.interior.max) << ',' << num(e.interior.p99) << ','
      << e.silhouette.pixels << ',' << num(e.silhouette.rmse) << ',' << num(e.silhouette.max) << ','
      << num(e.silhouette.p99) << ',' << num(e.peakRatio) << ','
      << (e.nonFinite + r.replacedNonFinite) << ',' << (r.paretoInterior ? 1 : 0) << ','
      << (r.paretoWhole ? 1 : 0) << '\n';
    return s.str();
}

std::string xFloor(const AccuracyRow& r) {
    return r.floorMs > 0.0 ? num(r.ms / r.floorMs, "%.1f") : "-";
}

std::string summaryMarkdown(const std::vector<AccuracyRow>& rows, const AccuracyArgs& a,
                            const std::string& machine, bool gpuClock, double referenceSeconds,
                            const std::string& spread) {
    std::ostringstream md;
    md << "# Speed against accuracy: `lantern bench accuracy`\n\n"
       << "Machine: " << machine << ".\n\n"
       << "Reproduce: `" << commandLine() << "`\n\n"
       << "Frame time: "
       << (gpuClock ? "the render pass on the device's timestamps" : "render() wall time")
       << ", median of " << a.timing.plan.rounds << " rounds' medians of " << a.timing.plan.frames
       << " frames after " << a.timing.plan.warmup
       << " warm-up frames, every configuration interleaved with the others in each round. "
       << "Errors: linear RGB against a double-precision ray cast of the exact surfaces ("
       << a.referenceSamples << "x" << a.referenceSamples
       << " box filter for the whole image and silhouettes, the pixel centre for the interior; "
       << "references took " << num(referenceSeconds, "%.1f") << " s). "
       << "x floor: the frame time over the trivial shader's on the same geometry and pixels. "
       << spread << "\n\n";
    std::vector<std::string> groups;
    for (const AccuracyRow& r : rows)
        if (std::find(groups.begin(), groups.end(), r.group()) == groups.end())
            groups.push_back(r.group());
    const double interiorBudgets[] = {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
    const double wholeBudgets[] = {3e-2, 1e-2, 5e-3, 3e-3, 2e-3, 1e-3, 5e-4};
    for (const std::string& g : groups) {
        std::vector<const AccuracyRow*> in;
        for (const AccuracyRow& r : rows)
            if (r.group() == g) in.push_back(&r);
        std::sort(in.begin(), in.end(),
                  [](const AccuracyRow* x, const AccuracyRow* y) { return x->ms < y->ms; });
        md << "## " << g << "\n\n"
           << "Pareto front, interior RMSE (shading alone):\n\n"
           << "| setting | triangles | ms | x floor | interior RMSE | interior max | peak ratio | "
              "whole RMSE | PSNR dB |\n|---|---|---|---|---|---|---|---|---|\n";
        for (const AccuracyRow* r : in)
            if (r->paretoInterior)
                md << "| " << r->setting() << " | " << r->triangles << " | " << num(r->ms, "%.2f")
                   << " | " << xFloor(*r) << " | " << num(r->error.interior.rmse, "%.2e") << " | "
                   << num(r->error.interior.max, "%.2e") << " | " << num(r->error.peakRatio, "%.3f")
                   << " | " << num(r->error.whole.rmse, "%.2e") << " | "
                   << num(r->error.psnr, "%.1f") << " |\n";
        md << "\nPareto front, whole-image RMSE (shading, silhouettes and aliasing):\n\n"
           << "| setting | triangles | ms | x floor | whole RMSE | silhouette RMSE | interior RMSE "
              "|\n|---|---|---|---|---|---|---|\n";
        for (const AccuracyRow* r : in)
            if (r->paretoWhole)
                md << "| " << r->setting() << " | " << r->triangles << " | " << num(r->ms, "%.2f")
                   << " | " << xFloor(*r) << " | " << num(r->error.whole.rmse, "%.2e") << " | "
                   << num(r->error.silhouette.rmse, "%.2e") << " | "
                   << num(r->error.interior.rmse, "%.2e") << " |\n";
        auto fastest = [&](double budget, bool interior) -> const AccuracyRow* {
            for (const AccuracyRow* r : in) {
                const double e = interior ? r->error.interior.rmse : r->error.whole.rmse;
                if (e <= budget) return r;
            }
            return nullptr;
        };
        auto cell = [](const AccuracyRow* r) {
            return r ? r->setting() + " | " + num(r->ms, "%.2f")
                     : std::string("none in this sweep | -");
        };
        md << "\nThe fastest setting that meets each error budget:\n\n"
           << "| interior RMSE <= | fastest setting | ms |\n|---|---|---|\n";
        for (double b : interiorBudgets)
            md << "| " << num(b, "%g") << " | " << cell(fastest(b, true)) << " |\n";
        md << "\n| whole-image RMSE <= | fastest setting | ms |\n|---|---|---|\n";
        for (double b : wholeBudgets)
            md << "| " << num(b, "%g") << " | " << cell(fastest(b, false)) << " |\n";
        md << "\n";
    }
    md << "## First frames (pipeline JIT)\n\n| configuration | variants compiled | first frame ms "
          "| "
          "steady ms |\n|---|---|---|---|\n";
    for (const AccuracyRow& r : rows)
        if (r.pipelines > 0)
            md << "| " << r.group() << ", " << r.setting() << " | " << r.pipelines << " | "
               << num(r.firstMs, "%.1f") << " | " << num(r.ms, "%.2f") << " |\n";
    std::uint64_t nonFinite = 0;
    for (const AccuracyRow& r : rows)
        nonFinite += r.error.nonFinite + r.replacedNonFinite;
    md << "\nNon-finite values in all renders: " << nonFinite << ".\n";
    return md.str();
}

int run(AccuracyArgs& a) {
    applyQuick(a);
    for (const std::string& s : a.scenes)
        if (std::find(benchSceneNames().begin(), benchSceneNames().end(), s) ==
            benchSceneNames().end())
            return report(makeError(ErrorCode::InvalidInput,
                                    "\"" + s + "\" is not a benchmark scene (sphere, spot)",
                                    "--scenes"));
    if (a.scenes.empty())
        return report(makeError(ErrorCode::InvalidInput, "the list is empty", "--scenes"));
    for (double s : a.shininess)
        if (!(s >= 0.0) || !std::isfinite(s))
            return report(makeError(ErrorCode::InvalidInput,
                                    "shininess must be a finite number >= 0", "--shininess"));
    if (a.shininess.empty())
        return report(makeError(ErrorCode::InvalidInput, "the list is empty", "--shininess"));
    auto modes = parseShadingList(a.shading, "--shading");
    if (!modes) return report(modes.error());
    if (auto r = checkRange(a.segments, 3, 2048, "--segments"); !r) return report(r.error());
    if (auto r = checkRange(a.msaa, 1, 8, "--msaa"); !r) return report(r.error());
    std::vector<std::pair<int, int>> sizes;
    for (const std::string& text : a.resolutions) {
        auto size = parseResolution(text, "--resolutions");
        if (!size) return report(size.error());
        sizes.push_back(*size);
    }
    if (sizes.empty())
        return report(makeError(ErrorCode::InvalidInput, "the list is empty", "--resolutions"));
    if (auto f = makeOutputFolder(a.timing.output); !f) return report(f.error());

    const ColdShaderCache coldCache; // before the device: first frames pay the whole JIT
    auto renderer = Renderer::create(a.device.desc());
    if (!renderer) return report(renderer.error());
    std::vector<int> msaa;
    for (int m : a.msaa) {
        const auto& supported = renderer->device().msaaSampleCounts;
        if (std::find(supported.begin(), supported.end(), m) != supported.end())
            msaa.push_back(m);
        else
            std::fprintf(stderr, "lantern: warning: %s does not support %dx MSAA; left out\n",
                         renderer->device().name.c_str(), m);
    }
    if (msaa.empty())
        return report(makeError(ErrorCode::Unsupported, "no sample count of the list is supported",
                                "--msaa"));

    // Every scene at every tessellation, uploaded once.
    struct Prepared {
        BenchScene bench;
        PreparedScene prepared;
    };
    std::map<std::tuple<std::string, double, int>, std::unique_ptr<Prepared>> scenes;
    for (const std::string& name : a.scenes)
        for (double s : a.shininess)
            for (int seg : a.segments) {
                auto p = std::make_unique<Prepared>();
                p->bench = makeBenchScene(name, s, seg);
                auto prepared = renderer->prepare(std::make_shared<const Scene>(p->bench.scene));
                if (!prepared) return report(prepared.error());
                p->prepared = *prepared;
                scenes[{name, s, seg}] = std::move(p);
            }

    // The references, one per scene, shininess and resolution (the exact surface does not
    // depend on the tessellation or the shading mode).
    std::map<std::tuple<std::string, double, int, int>, ReferenceImage> references;
    const auto r0 = std::chrono::steady_clock::now();
    for (const std::string& name : a.scenes)
        for (double s : a.shininess)
            for (auto [w, h] : sizes) {
                const auto t0 = std::chrono::steady_clock::now();
                const BenchScene& b = scenes.at({name, s, a.segments[0]})->bench;
                RenderOptions o;
                o.width = w;
                o.height = h;
                ReferenceOptions ro;
                ro.shapes = b.shapes;
                ro.boxSamples = a.referenceSamples;
                auto ref = raycastReference(b.scene, o, 0.0, ro);
                if (!ref) return report(ref.error());
                references[{name, s, w, h}] = std::move(*ref);
                if (!a.timing.quiet)
                    std::fprintf(stderr, "reference %s, shininess %g, %dx%d: %.1f s\n",
                                 name.c_str(), s, w, h, msSince(t0) / 1000.0);
            }
    const double referenceSeconds = msSince(r0) / 1000.0;

    // Configurations ordered by image size and sample count (fewer target changes), each
    // shading mode beside the floor of the same geometry.
    std::vector<AccuracyRow> rows;
    std::vector<TimedConfig> configs;
    std::vector<int> rowOfConfig; // -1: a floor configuration
    std::map<std::tuple<std::string, int, int, int, int>, std::size_t> floorConfig;
    for (auto [w, h] : sizes)
        for (int m : msaa)
            for (const std::string& name : a.scenes)
                for (int seg : a.segments) {
                    for (double s : a.shininess) {
                        const Prepared& p = *scenes.at({name, s, seg});
                        for (ShadingMode mode : *modes) {
                            AccuracyRow row;
                            row.scene = name;
                            row.shininess = s;
                            row.width = w;
                            row.height = h;
                            row.shading = mode;
                            row.segments = seg;
                            row.triangles = p.bench.triangles;
                            row.msaa = m;
                            TimedConfig c;
                            c.label = row.group() + ", " + row.setting();
                            c.scene = &p.prepared;
                            c.options.width = w;
                            c.options.height = h;
                            c.options.msaa = m;
                            c.options.shading = mode;
                            rowOfConfig.push_back(int(rows.size()));
                            rows.push_back(row);
                            configs.push_back(std::move(c));
                        }
                    }
                    if (a.noFloor) continue;
                    TimedConfig f;
                    f.label = name + ", " + std::to_string(w) + "x" + std::to_string(h) +
                              ", floor, " + std::to_string(seg) + ", " + std::to_string(m) + "x";
                    f.scene = &scenes.at({name, a.shininess[0], seg})->prepared;
                    f.options.width = w;
                    f.options.height = h;
                    f.options.msaa = m;
                    f.options.features = FeatureMode::Floor;
                    floorConfig[{name, seg, m, w, h}] = configs.size();
                    rowOfConfig.push_back(-1);
                    configs.push_back(std::move(f));
                }
    for (std::size_t i = 0; i < configs.size(); ++i) {
        if (rowOfConfig[i] < 0) continue;
        AccuracyRow* row = &rows[std::size_t(rowOfConfig[i])];
        const ReferenceImage* ref =
            &references.at({row->scene, row->shininess, row->width, row->height});
        configs[i].inspect = [row, ref](const Image& image) -> Result<void> {
            auto e = measureError(image, *ref);
            if (!e) return std::move(e).error();
            row->error = *e;
            return {};
        };
    }
    if (!a.timing.quiet)
        std::fprintf(stderr, "timing %zu configurations, %d rounds of %d + %d frames each\n",
                     configs.size(), a.timing.plan.rounds, a.timing.plan.warmup,
                     a.timing.plan.frames);
    bool gpuClock = false;
    if (auto t = timeInterleaved(*renderer, configs, a.timing.plan, a.timing.quiet, &gpuClock); !t)
        return report(t.error());

    for (std::size_t i = 0; i < configs.size(); ++i) {
        if (rowOfConfig[i] < 0) continue;
        AccuracyRow& row = rows[std::size_t(rowOfConfig[i])];
        const TimedConfig& c = configs[i];
        row.ms = c.ms();
        row.msMin = c.minMs();
        row.msWall = c.msWall();
        row.spread = c.roundSpread();
        row.firstMs = c.firstFrameMs;
        row.pipelines = c.pipelinesCreated;
        row.replacedNonFinite = c.nonFinite;
        if (auto f = floorConfig.find({row.scene, row.segments, row.msaa, row.width, row.height});
            f != floorConfig.end())
            row.floorMs = configs[f->second].ms();
    }
    markParetoFronts(rows);

    std::string csv = csvHeader();
    for (const AccuracyRow& r : rows)
        csv += csvRow(r);
    const std::string machine = machineDescription(*renderer);
    std::vector<double> spreads;
    for (const TimedConfig& c : configs)
        spreads.push_back(c.roundSpread());
    const std::string md =
        summaryMarkdown(rows, a, machine, gpuClock, referenceSeconds, spreadSentence(spreads));
    const std::filesystem::path dir(a.timing.output);
    for (auto [name, text] : {std::pair{"accuracy.csv", csv}, std::pair{"accuracy.md", md},
                              std::pair{"accuracy.svg", accuracyPlotSvg(rows)}})
        if (auto w = writeTextFile((dir / name).string(), text); !w) return report(w.error());
    if (!a.timing.quiet) std::fputs(md.c_str(), stdout);
    std::printf("wrote %s, %s and %s\n", (dir / "accuracy.csv").c_str(),
                (dir / "accuracy.svg").c_str(), (dir / "accuracy.md").c_str());
    return kOk;
}

} // namespace

Runner addAccuracyBench(CLI::App& bench) {
    auto a = std::make_shared<AccuracyArgs>();
    CLI::App* cmd = bench.add_subcommand(
        "accuracy", "Sweep shading mode x tessellation x MSAA x resolution: ms per frame against "
                    "the error from an exact ray-cast reference (CSV, SVG plot, markdown summary)");
    cmd->add_option("--scenes", a->scenes, "Analytic scenes: sphere (S1), spot (S2)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--shininess", a->shininess, "Material shininess values")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--shading", a->shading, "Shading modes")
        ->delimiter(',')
        ->capture_default_str();
    a->segmentsOption = cmd->add_option("--segments", a->segments,
                                        "Tessellations: sphere segments around, plane subdivisions")
                            ->delimiter(',')
                            ->capture_default_str();
    cmd->add_option("--msaa", a->msaa, "Samples per pixel")->delimiter(',')->capture_default_str();
    a->resolutionsOption = cmd->add_option("--resolutions", a->resolutions, "Image sizes WxH")
                               ->delimiter(',')
                               ->capture_default_str();
    cmd->add_option("--reference-samples", a->referenceSamples,
                    "Reference box filter: N x N rays per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    cmd->add_flag("--no-floor", a->noFloor, "Do not time the trivial-shader floor");
    a->timing.output = "bench-accuracy";
    a->timing.add(*cmd, "Reduced sweep: segments 8 to 256, 480x270, 3 frames per round",
                  "Folder for accuracy.csv, accuracy.svg, accuracy.md");
    a->device.add(*cmd);
    return [a, cmd]() { return cmd->parsed() ? run(*a) : -1; };
}

} // namespace lantern::cli
