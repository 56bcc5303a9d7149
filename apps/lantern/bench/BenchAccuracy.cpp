// `lantern bench accuracy`: the speed-versus-accuracy sweep (numerics.md section 7). Shading
// mode x tessellation x MSAA x resolution (x shininess) on the analytic scenes S1 and S2, each
// configuration timed interleaved with the others and compared with a double-precision ray
// cast of the exact surfaces. Writes a CSV (one row per configuration) and a markdown summary
// naming, per error budget, the fastest setting that meets it (BenchAccuracyReport.cpp), and the
// plot (error against ms per frame, Pareto fronts marked) drawn by benchmarks/plot_accuracy.py.
#include "bench/BenchAccuracy.h"

#include "bench/BenchHarness.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <tuple>

namespace lantern::cli {

std::string AccuracyRow::group() const {
    return scene + ", shininess " + num(shininess, "%g") + ", " + std::to_string(width) + "x" +
           std::to_string(height);
}

std::string AccuracyRow::setting() const {
    return std::string(toString(shading)) + ", " + std::to_string(segments) +
           (scene == "spot" ? " subdivisions" : " segments") + ", " + std::to_string(msaa) + "x" +
           (transparency.empty() ? "" : ", " + transparency) +
           (shadowResolution > 0 ? ", " + std::to_string(shadowResolution) + " texels, " + shadowFilter +
                                       ", " + std::to_string(shadowCascades) + " cascade" +
                                       (shadowCascades == 1 ? "" : "s")
                                 : "");
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
    std::vector<std::string> transparency{"sorted", "exact", "weighted"};
    std::vector<int> shadowResolutions{256, 512, 1024, 2048, 4096};
    std::vector<std::string> shadowFilters{"hardware", "pcf"};
    std::vector<int> shadowCascades{1, 4};
    std::vector<int> widths{960, 1920}, heights{540, 1080};
    TimingOptions timing;
    int referenceSamples = 8;
    bool noFloor = false;
    std::vector<std::string> sections{"shading", "lod"};
    LodSection lod;
    DeviceOptions device;
    CLI::Option *segmentsOption = nullptr, *widthOption = nullptr, *heightOption = nullptr;
};

// The reduced sweep of --quick: every mode and scene, a few tessellations, small images.
void applyQuick(AccuracyArgs& a) {
    if (!a.timing.quick) return;
    if (!a.segmentsOption->count()) a.segments = {8, 16, 32, 64, 128, 256};
    if (!a.widthOption->count() && !a.heightOption->count()) a.widths = {480}, a.heights = {270};
    a.timing.applyQuick(a.timing.plan.rounds, 3);
    a.lod.applyQuick();
}

bool wants(const AccuracyArgs& a, const char* section) {
    return std::find(a.sections.begin(), a.sections.end(), section) != a.sections.end();
}

// The scene and shininess lists: known scenes, finite shininess, neither empty.
Result<void> checkScenes(const AccuracyArgs& a) {
    for (const std::string& s : a.scenes)
        if (std::find(benchSceneNames().begin(), benchSceneNames().end(), s) ==
            benchSceneNames().end())
            return makeError(ErrorCode::InvalidInput,
                             "\"" + s + "\" is not a benchmark scene (sphere, spot, crossing, "
                             "nested, beside, torus, foliage, shadow, field)", "--scenes");
    if (a.scenes.empty())
        return makeError(ErrorCode::InvalidInput, "the list is empty", "--scenes");
    for (double s : a.shininess)
        if (!(s >= 0.0) || !std::isfinite(s))
            return makeError(ErrorCode::InvalidInput, "shininess must be a finite number >= 0",
                             "--shininess");
    if (a.shininess.empty())
        return makeError(ErrorCode::InvalidInput, "the list is empty", "--shininess");
    return {};
}

// The sample counts of the list the device supports (the others left out with a warning).
Result<std::vector<int>> supportedMsaa(const Renderer& renderer, const std::vector<int>& wanted) {
    std::vector<int> msaa;
    for (int m : wanted) {
        const auto& supported = renderer.device().msaaSampleCounts;
        if (std::find(supported.begin(), supported.end(), m) != supported.end())
            msaa.push_back(m);
        else
            std::fprintf(stderr, "lantern: warning: %s does not support %dx MSAA; left out\n",
                         renderer.device().name.c_str(), m);
    }
    if (msaa.empty())
        return makeError(ErrorCode::Unsupported, "no sample count of the list is supported",
                         "--msaa");
    return msaa;
}

struct Prepared {
    BenchScene bench;
    PreparedScene prepared;
};
/// By scene, shininess and tessellation.
using PreparedScenes = std::map<std::tuple<std::string, double, int>, std::unique_ptr<Prepared>>;
/// By scene, shininess, width and height; "NAME/lit": a shadow scene without its shadows,
/// "NAME/soft": with PCSS's lights of a size (the pcss rows' reference).
using References = std::map<std::tuple<std::string, double, int, int>, ReferenceImage>;

// Every scene at every tessellation, uploaded once.
Result<PreparedScenes> prepareScenes(Renderer& renderer, const AccuracyArgs& a) {
    PreparedScenes scenes;
    for (const std::string& name : a.scenes)
        for (double s : a.shininess)
            for (int seg : a.segments) {
                auto p = std::make_unique<Prepared>();
                p->bench = makeBenchScene(name, s, seg);
                auto prepared = renderer.prepare(std::make_shared<const Scene>(p->bench.scene));
                if (!prepared) return std::move(prepared).error();
                p->prepared = *prepared;
                scenes[{name, s, seg}] = std::move(p);
            }
    return scenes;
}

// The references, one per scene, shininess and resolution (the exact surface does not
// depend on the tessellation or the shading mode).
Result<References> makeReferences(const AccuracyArgs& a, const PreparedScenes& scenes,
                                  const std::vector<std::pair<int, int>>& sizes) {
    References references;
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
                if (!ref) return std::move(ref).error();
                references[{name, s, w, h}] = std::move(*ref);
                if (isShadowScene(name)) {  // the same without the shadow: which pixels it darkens
                    Scene lit = b.scene;
                    for (Light& l : lit.lights) l.castShadows = false;
                    auto unshadowed = raycastReference(lit, o, 0.0, ro);
                    if (!unshadowed) return std::move(unshadowed).error();
                    references[{name + "/lit", s, w, h}] = std::move(*unshadowed);
                }
                const auto& f = a.shadowFilters;
                if (isShadowScene(name) && std::find(f.begin(), f.end(), "pcss") != f.end()) {
                    RenderOptions soft = o;  // lights of PCSS's default sizes
                    soft.shadows.filter = ShadowFilter::Pcss;
                    auto penumbra = raycastReference(b.scene, soft, 0.0, ro);
                    if (!penumbra) return std::move(penumbra).error();
                    references[{name + "/soft", s, w, h}] = std::move(*penumbra);
                }
                if (!a.timing.quiet)
                    std::fprintf(stderr, "reference %s, shininess %g, %dx%d: %.1f s\n",
                                 name.c_str(), s, w, h, msSince(t0) / 1000.0);
            }
    return references;
}

// What is timed: a row per measured configuration, and the floors beside them.
struct Sweep {
    std::vector<AccuracyRow> rows;
    std::vector<TimedConfig> configs;
    std::vector<int> rowOfConfig; // -1: a floor configuration
    std::map<std::tuple<std::string, int, int, int, int>, std::size_t> floorConfig;
};

// What a scene sweeps besides shading, tessellation, size and samples: the transparency
// method (the transparency scenes) or the shadow maps' resolution and filter (the shadow scene).
struct Variant {
    std::string transparency;
    int shadowResolution = 0;
    std::string shadowFilter;
    int shadowCascades = 0;
};

std::vector<Variant> variantsOf(const AccuracyArgs& a, const std::string& name) {
    std::vector<Variant> out;
    if (isTransparencyScene(name))
        for (const std::string& t : a.transparency) out.push_back({t, 0, ""});
    else if (isShadowScene(name))
        for (int r : a.shadowResolutions)
            for (const std::string& f : a.shadowFilters)
                for (int c : a.shadowCascades) out.push_back({"", r, f, c});
    else
        out.push_back({});
    return out;
}

// The shading modes of one scene, shininess, tessellation, size, sample count and variant.
void addModes(Sweep& sweep, const std::vector<ShadingMode>& modes, const std::string& name,
              double s, int seg, int w, int h, int m, const Variant& variant, const Prepared& p) {
    for (ShadingMode mode : modes) {
        AccuracyRow row;
        row.scene = name;
        row.shininess = s;
        row.width = w;
        row.height = h;
        row.shading = mode;
        row.segments = seg;
        row.triangles = p.bench.triangles;
        row.msaa = m;
        row.transparency = variant.transparency;
        row.shadowResolution = variant.shadowResolution;
        row.shadowFilter = variant.shadowFilter;
        row.shadowCascades = variant.shadowCascades;
        TimedConfig c;
        c.label = row.group() + ", " + row.setting();
        c.scene = &p.prepared;
        c.options.width = w;
        c.options.height = h;
        c.options.msaa = m;
        c.options.shading = mode;
        if (!variant.transparency.empty())
            c.options.transparency = parseTransparencyMethod(variant.transparency);
        if (variant.shadowResolution > 0) {
            c.options.shadows.resolution = variant.shadowResolution;
            c.options.shadows.filter = parseShadowFilter(variant.shadowFilter);
            c.options.shadows.cascades = variant.shadowCascades;
        }
        sweep.rowOfConfig.push_back(int(sweep.rows.size()));
        sweep.rows.push_back(row);
        sweep.configs.push_back(std::move(c));
    }
}

// The trivial shader on the same geometry and pixels.
void addFloor(Sweep& sweep, const std::string& name, int seg, int w, int h, int m,
              const PreparedScene& prepared) {
    TimedConfig f;
    f.label = name + ", " + std::to_string(w) + "x" + std::to_string(h) + ", floor, " +
              std::to_string(seg) + ", " + std::to_string(m) + "x";
    f.scene = &prepared;
    f.options.width = w;
    f.options.height = h;
    f.options.msaa = m;
    f.options.features = FeatureMode::Floor;
    sweep.floorConfig[{name, seg, m, w, h}] = sweep.configs.size();
    sweep.rowOfConfig.push_back(-1);
    sweep.configs.push_back(std::move(f));
}

// Configurations ordered by image size and sample count (fewer target changes), each
// shading mode beside the floor of the same geometry; each row's error measured against its
// reference.
Sweep makeSweep(const AccuracyArgs& a, const PreparedScenes& scenes, const References& references,
                const std::vector<std::pair<int, int>>& sizes, const std::vector<int>& msaa,
                const std::vector<ShadingMode>& modes) {
    Sweep sweep;
    for (auto [w, h] : sizes)
        for (int m : msaa)
            for (const std::string& name : a.scenes)
                for (int seg : a.segments) {
                    for (double s : a.shininess)
                        for (const Variant& v : variantsOf(a, name))
                            addModes(sweep, modes, name, s, seg, w, h, m, v, *scenes.at({name, s, seg}));
                    if (!a.noFloor)
                        addFloor(sweep, name, seg, w, h, m,
                                 scenes.at({name, a.shininess[0], seg})->prepared);
                }
    for (std::size_t i = 0; i < sweep.configs.size(); ++i) {
        if (sweep.rowOfConfig[i] < 0) continue;
        AccuracyRow* row = &sweep.rows[std::size_t(sweep.rowOfConfig[i])];
        const std::string key = row->shadowFilter == "pcss" ? row->scene + "/soft" : row->scene;
        const ReferenceImage* ref = &references.at({key, row->shininess, row->width, row->height});
        const auto lit = references.find({row->scene + "/lit", row->shininess, row->width, row->height});
        const ReferenceImage* unshadowed = lit != references.end() ? &lit->second : nullptr;
        sweep.configs[i].inspect = [row, ref, unshadowed](const Image& image) -> Result<void> {
            auto e = measureError(image, *ref);
            if (!e) return std::move(e).error();
            row->error = *e;
            if (unshadowed) row->wrongShadowShare = shadowWrongShare(image, *ref, *unshadowed);
            return {};
        };
    }
    return sweep;
}

// The timings into the rows, and the Pareto fronts.
void collectTimes(Sweep& sweep) {
    for (std::size_t i = 0; i < sweep.configs.size(); ++i) {
        if (sweep.rowOfConfig[i] < 0) continue;
        AccuracyRow& row = sweep.rows[std::size_t(sweep.rowOfConfig[i])];
        const TimedConfig& c = sweep.configs[i];
        row.ms = c.ms();
        row.msMin = c.minMs();
        row.msWall = c.msWall();
        row.spread = c.roundSpread();
        row.firstMs = c.firstFrameMs;
        row.pipelines = c.pipelinesCreated;
        row.replacedNonFinite = c.nonFinite;
        if (auto f =
                sweep.floorConfig.find({row.scene, row.segments, row.msaa, row.width, row.height});
            f != sweep.floorConfig.end())
            row.floorMs = sweep.configs[f->second].ms();
    }
    markParetoFronts(sweep.rows);
}

// The shading section's report: accuracy.csv, and its part of accuracy.md.
Result<std::string> shadingReport(const AccuracyArgs& a, const Renderer& renderer,
                                  const Sweep& sweep, bool gpuClock, double referenceSeconds) {
    AccuracyMethod how;
    how.machine = machineDescription(renderer);
    how.gpuClock = gpuClock;
    how.plan = a.timing.plan;
    how.referenceSamples = a.referenceSamples;
    how.referenceSeconds = referenceSeconds;
    std::vector<double> spreads;
    for (const TimedConfig& c : sweep.configs)
        spreads.push_back(c.roundSpread());
    how.spread = spreadSentence(spreads);
    const auto csv = std::filesystem::path(a.timing.output) / "accuracy.csv";
    LANTERN_TRY(writeTextFile(csv.string(), accuracyCsv(sweep.rows)));
    std::printf("wrote %s\n", csv.c_str());
    return accuracySummaryMarkdown(sweep.rows, how);
}

// The shading section: references, the interleaved sweep, the report.
Result<std::string> runShading(const AccuracyArgs& a, Renderer& renderer,
                               const std::vector<std::pair<int, int>>& sizes,
                               const std::vector<ShadingMode>& modes) {
    auto msaa = supportedMsaa(renderer, a.msaa);
    if (!msaa) return std::move(msaa).error();
    auto scenes = prepareScenes(renderer, a);
    if (!scenes) return std::move(scenes).error();
    const auto r0 = std::chrono::steady_clock::now();
    auto references = makeReferences(a, *scenes, sizes);
    if (!references) return std::move(references).error();
    const double referenceSeconds = msSince(r0) / 1000.0;

    Sweep sweep = makeSweep(a, *scenes, *references, sizes, *msaa, modes);
    if (!a.timing.quiet)
        std::fprintf(stderr, "timing %zu configurations, %d rounds of %d + %d frames each\n",
                     sweep.configs.size(), a.timing.plan.rounds, a.timing.plan.warmup,
                     a.timing.plan.frames);
    bool gpuClock = false;
    LANTERN_TRY(timeInterleaved(renderer, sweep.configs, a.timing.plan, a.timing.quiet, &gpuClock));
    collectTimes(sweep);
    return shadingReport(a, renderer, sweep, gpuClock, referenceSeconds);
}

Result<void> checkSections(const AccuracyArgs& a) {
    for (const std::string& s : a.sections)
        if (s != "shading" && s != "lod")
            return makeError(ErrorCode::InvalidInput,
                             "\"" + s + "\" is not a section (shading, lod)", "--sections");
    if (a.sections.empty())
        return makeError(ErrorCode::InvalidInput, "the list is empty", "--sections");
    return {};
}

int run(AccuracyArgs& a) {
    applyQuick(a);
    if (auto r = checkSections(a); !r) return report(r.error());
    if (auto r = checkScenes(a); !r) return report(r.error());
    auto modes = parseShadingList(a.shading, "--shading");
    if (!modes) return report(modes.error());
    if (auto r = checkRange(a.segments, 3, 2048, "--segments"); !r) return report(r.error());
    if (auto r = checkRange(a.msaa, 1, 8, "--msaa"); !r) return report(r.error());
    auto sizes = pairSizes(a.widths, a.heights);
    if (!sizes) return report(sizes.error());
    if (auto f = makeOutputFolder(a.timing.output); !f) return report(f.error());

    const ColdShaderCache coldCache; // before the device: first frames pay the whole JIT
    auto renderer = Renderer::create(a.device.desc());
    if (!renderer) return report(renderer.error());
    std::string md;
    if (wants(a, "shading")) {
        auto shading = runShading(a, *renderer, *sizes, *modes);
        if (!shading) return report(shading.error());
        md = *shading;
    }
    if (wants(a, "lod")) {
        auto lod = runLod(*renderer, a.lod, *sizes, a.timing, md.empty());
        if (!lod) return report(lod.error());
        md += *lod;
    }
    const auto mdPath = std::filesystem::path(a.timing.output) / "accuracy.md";
    if (auto w = writeTextFile(mdPath.string(), md); !w) return report(w.error());
    if (!a.timing.quiet) std::fputs(md.c_str(), stdout);
    std::printf("wrote %s\n", mdPath.c_str());
    std::fflush(stdout);
    if (!wants(a, "shading")) return kOk;
    // The plot is a view of the CSV: without matplotlib the run still succeeds and says how to
    // draw it later.
    const std::filesystem::path dir(a.timing.output);
    const PlotOutcome plot = plotAccuracy(
        (dir / "accuracy.csv").string(), {(dir / "accuracy.svg").string(), (dir / "accuracy.png").string()});
    if (!plot.drawn) std::fprintf(stderr, "lantern: warning: %s\n", plot.message.c_str());
    return kOk;
}

} // namespace

Runner addAccuracyBench(CLI::App& bench) {
    auto a = std::make_shared<AccuracyArgs>();
    CLI::App* cmd = bench.add_subcommand(
        "accuracy", "Sweep shading mode x tessellation x MSAA x resolution: ms per frame against "
                    "the error from an exact ray-cast reference (CSV, markdown summary, plot)");
    cmd->add_option("--scenes", a->scenes, "Analytic scenes: sphere (S1), spot (S2); transparency: crossing (T1), nested (T2), "
                    "beside (T3), torus (T4), foliage (T5); shadows: shadow (H1), field (H2)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--shininess", a->shininess, "Material shininess values")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--shading", a->shading, help::kShadingList)
        ->delimiter(',')
        ->capture_default_str();
    a->segmentsOption = cmd->add_option("--segments", a->segments,
                                        "Tessellations: sphere segments around, plane subdivisions")
                            ->delimiter(',')
                            ->capture_default_str();
    cmd->add_option("--msaa", a->msaa, help::kMsaaList)->delimiter(',')->capture_default_str();
    cmd->add_option("--shadow-resolution", a->shadowResolutions,
                    "Shadow map sizes for the shadow scene (texels per side)")
        ->delimiter(',')
        ->capture_default_str()
        ->check(CLI::Range(16, 16384));
    cmd->add_option("--shadow-filter", a->shadowFilters,
                    "Shadow filters for the shadow scenes: hardware, pcf, pcss (against lights "
                    "of the default sizes, --shadow-light-radius and --shadow-sun-radius of render)")
        ->delimiter(',')
        ->capture_default_str()
        ->check(CLI::IsMember({"hardware", "pcf", "pcss"}));
    cmd->add_option("--shadow-cascades", a->shadowCascades,
                    "Cascades of the shadow scenes' directional light")
        ->delimiter(',')
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    cmd->add_option("--transparency", a->transparency,
                    "Transparency methods for the transparency scenes: sorted, exact, weighted")
        ->delimiter(',')
        ->capture_default_str()
        ->check(CLI::IsMember({"sorted", "exact", "weighted"}));
    a->widthOption = cmd->add_option("--width", a->widths, help::kWidthList)
                         ->delimiter(',')
                         ->capture_default_str();
    a->heightOption = cmd->add_option("--height", a->heights, help::kHeightList)
                          ->delimiter(',')
                          ->capture_default_str();
    cmd->add_option("--reference-samples", a->referenceSamples,
                    "Reference box filter: N x N rays per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    cmd->add_flag("--no-floor", a->noFloor, "Do not time the trivial-shader floor");
    cmd->add_option("--sections", a->sections,
                    "shading (the analytic scenes against ray-cast references), lod (levels of "
                    "detail against the exact frame)")
        ->delimiter(',')
        ->capture_default_str();
    a->lod.add(*cmd);
    a->timing.output = "bench-accuracy";
    a->timing.add(*cmd, "Reduced sweep: segments 8 to 256, 480x270, 3 frames per round; a 6 x 6 "
                        "grid of 64-segment spheres",
                  "Folder for accuracy.csv, lod.csv, accuracy.md and the plot (accuracy.svg, .png)");
    a->device.add(*cmd);
    return [a, cmd]() { return cmd->parsed() ? run(*a) : -1; };
}

} // namespace lantern::cli
