// The level-of-detail section of `lantern bench accuracy`: one scene (a generated grid of
// tessellated spheres, or --lod-scene) rendered at every --lod-error bound, each bound timed
// interleaved with the exact frame (bound 0) in the same rounds, and each frame's error measured
// against that exact frame: RMSE of the linear RGB values and the mean FLIP that `lantern
// compare` reports for EXRs. The rows on the Pareto front of (frame time, FLIP mean) are marked.
#include "bench/BenchAccuracy.h"
#include "bench/BenchHarness.h"

#include <lantern/Compare.h>
#include <lantern/Io.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

namespace lantern::cli {

void LodSection::add(CLI::App& app) {
    app.add_option("--lod-errors", bounds,
                   "Level-of-detail section: --lod-error bounds in pixels (0, the exact frame, "
                   "is always timed as the reference)")
        ->delimiter(',')
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e6));
    app.add_option("--lod-scene", scene,
                   "Level-of-detail section: a scene file or builtin:NAME (default: a generated "
                   "grid of spheres, --lod-grid x --lod-grid, each --lod-segments around)");
    m_grid = app.add_option("--lod-grid", grid, "Spheres per side of the generated grid")
                 ->capture_default_str()
                 ->check(CLI::Range(1, 100));
    m_segments =
        app.add_option("--lod-segments", segments, "Segments around each sphere of the grid")
            ->capture_default_str()
            ->check(CLI::Range(8, 2048));
}

void LodSection::applyQuick() {
    if (!m_grid->count()) grid = 6;
    if (!m_segments->count()) segments = 64;
}

BenchScene makeLodGrid(int side, int segments) {
    BenchScene b = makeBenchScene("sphere", 64.0, segments);
    Scene& s = b.scene;
    s.sourcePath = "bench:lod-grid";
    const Node sphere = s.nodes[0];
    Node light = s.nodes[1];
    const double spacing = 2.5, half = 0.5 * spacing * (side - 1) + 1.0;
    // The 40-degree camera sees the whole grid, with a margin.
    const double distance = 1.15 * half / std::tan(20.0 * 3.14159265358979323846 / 180.0) + 1.0;
    light.translation = {0.5 * half, 0.8 * half, distance};
    s.nodes = {light};
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j) {
            Node n = sphere;
            n.name = "sphere " + std::to_string(i) + " " + std::to_string(j);
            n.translation = {(i - 0.5 * (side - 1)) * spacing, (j - 0.5 * (side - 1)) * spacing, 0.0};
            s.nodes.push_back(n);
        }
    s.cameras[0].lookAt = LookAt{{0.0, 0.0, distance}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    s.roots[0].nodes.clear();
    for (int i = 0; i < int(s.nodes.size()); ++i) s.roots[0].nodes.push_back(i);
    b.triangles *= std::size_t(side) * std::size_t(side);
    b.shapes.clear();  // no analytic reference: the exact frame is the reference
    return b;
}

namespace {

struct LodScene {
    std::string name;
    std::size_t triangles = 0; ///< 0: counted by the first frame's statistics
    PreparedScene prepared;
};

Result<LodScene> prepareLodScene(Renderer& renderer, const LodSection& lod) {
    LodScene out;
    Scene scene;
    if (lod.scene.empty()) {
        BenchScene grid = makeLodGrid(lod.grid, lod.segments);
        out.name = "generated grid of " + std::to_string(lod.grid) + " x " +
                   std::to_string(lod.grid) + " spheres of " + std::to_string(lod.segments) +
                   " segments";
        out.triangles = grid.triangles;
        scene = std::move(grid.scene);
    } else {
        auto loaded = loadScene(lod.scene);
        if (!loaded) return std::move(loaded).error();
        out.name = lod.scene;
        scene = std::move(*loaded);
    }
    auto prepared = renderer.prepare(std::make_shared<const Scene>(std::move(scene)));
    if (!prepared) return std::move(prepared).error();
    out.prepared = *prepared;
    return out;
}

// RMSE of the linear RGB values and the mean FLIP (HDR-FLIP for these linear images, as
// `lantern compare` computes it for EXRs) of `image` against `exact`.
Result<void> measureLod(const Image& exact, const Image& image, LodRow& row) {
    double sum = 0.0;
    const std::size_t n = image.pixelCount();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            const double d = double(image.rgba[4 * i + c]) - double(exact.rgba[4 * i + c]);
            sum += d * d;
        }
    row.rmse = n > 0 ? std::sqrt(sum / double(3 * n)) : 0.0;
    CompareOptions options;
    options.ssim = false;
    auto report = compareImages(toCompareImage(exact, PixelEncoding::Linear, "exact"),
                                toCompareImage(image, PixelEncoding::Linear, "level of detail"),
                                options);
    if (!report) return std::move(report).error();
    row.flipMean = report->flip ? report->flip->mean : 0.0;
    return {};
}

// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

void markLodFront(std::vector<LodRow>& rows) {
    for (LodRow& r : rows) {
        r.pareto = true;
        for (const LodRow& o : rows)
            if (&o != &r && o.width == r.width && o.height == r.height && o.ms <= r.ms &&
                o.flipMean <= r.flipMean && (o.ms < r.ms || o.flipMean < r.flipMean))
                r.pareto = false;
    }
}

} // namespace

Result<std::vector<LodRow>> runLodSection(Renderer& renderer, const LodSection& lod,
                                          const std::vector<std::pair<int, int>>& sizes,
                                          const TimingOptions& timing, bool* gpuClock) {
    auto scene = prepareLodScene(renderer, lod);
    if (!scene) return std::move(scene).error();
    std::vector<double> bounds = lod.bounds;
    bounds.push_back(0.0);
    std::sort(bounds.begin(), bounds.end());
    bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());
    std::vector<LodRow> rows;
    std::vector<TimedConfig> configs;
    rows.reserve(sizes.size() * bounds.size());  // the inspectors hold pointers into it
    for (auto [w, h] : sizes) {
        auto exact = std::make_shared<Image>();  // bound 0 runs first in each round
        for (double bound : bounds) {
            rows.push_back({scene->name, w, h, bound});
            LodRow* row = &rows.back();
            TimedConfig c;
            c.label = "level of detail, " + std::to_string(w) + "x" + std::to_string(h) +
                      ", --lod-error " + num(bound, "%g");
            c.scene = &scene->prepared;
            c.options.width = w;
            c.options.height = h;
            c.options.lodError = bound;
            c.inspect = [exact, row](const Image& image) -> Result<void> {
                if (row->bound == 0.0) {
                    *exact = image;
                    return {};
                }
                return measureLod(*exact, image, *row);
            };
            configs.push_back(std::move(c));
        }
    }
    if (!timing.quiet)
        std::fprintf(stderr, "level of detail: %s, %zu configurations\n", scene->name.c_str(),
                     configs.size());
    LANTERN_TRY(timeInterleaved(renderer, configs, timing.plan, timing.quiet, gpuClock));
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const TimedConfig& c = configs[i];
        rows[i].ms = c.ms();
        rows[i].msWall = c.msWall();
        rows[i].spread = c.roundSpread();
        rows[i].triangles = c.clusterTriangles;
        rows[i].trianglesDrawn = c.clusterTrianglesDrawn;
        rows[i].nonFinite = c.nonFinite;
    }
    markLodFront(rows);
    return rows;
}

std::string lodCsv(const std::vector<LodRow>& rows) {
    std::ostringstream s;
    s << "scene,width,height,lod_error,ms_per_frame,ms_wall,ms_round_spread,clustered_triangles,"
         "clustered_triangles_drawn,rmse,flip_mean,nonfinite,pareto\n";
    for (const LodRow& r : rows)
        s << csvField(r.scene) << ',' << r.width << ',' << r.height << ',' << num(r.bound, "%g")
          << ',' << num(r.ms) << ',' << num(r.msWall) << ',' << num(r.spread, "%.3f") << ','
          << r.triangles << ',' << r.trianglesDrawn << ',' << num(r.rmse) << ','
          << num(r.flipMean) << ',' << r.nonFinite << ',' << (r.pareto ? 1 : 0) << '\n';
    return s.str();
}

std::string lodSummaryMarkdown(const std::vector<LodRow>& rows, bool gpuClock) {
    if (rows.empty()) return {};
    std::ostringstream md;
    md << "## Level of detail\n\n" << rows[0].scene
       << ": each `--lod-error` bound timed interleaved with the exact frame (bound 0) in the "
          "same rounds ("
       << (gpuClock ? "GPU render pass" : "render() wall time")
       << "), its error measured against the exact frame: RMSE of the linear RGB values and the "
          "FLIP mean of `lantern compare`. Front: on the Pareto front of (ms, FLIP mean).\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const LodRow& r = rows[i];
        const bool first = i == 0 || rows[i - 1].width != r.width || rows[i - 1].height != r.height;
        if (first)
            md << "\n### " << r.width << "x" << r.height
               << "\n\n| --lod-error | ms per frame | exact / this | triangles drawn | RMSE | "
                  "FLIP mean | front |\n|---|---|---|---|---|---|---|\n";
        const LodRow* exact = &r;
        for (std::size_t j = i; j-- > 0 && rows[j].width == r.width && rows[j].height == r.height;)
            exact = &rows[j];
        const double share = r.triangles > 0 ? 100.0 * double(r.trianglesDrawn) / double(r.triangles) : 0.0;
        md << "| " << num(r.bound, "%g") << " | " << num(r.ms) << " | " << num(exact->ms / r.ms, "%.2f")
           << " | " << num(share, "%.1f") << " % | " << num(r.rmse) << " | " << num(r.flipMean)
           << " | " << (r.pareto ? "yes" : "") << " |\n";
    }
    return md.str();
}

Result<std::string> runLod(Renderer& renderer, const LodSection& lod,
                           const std::vector<std::pair<int, int>>& sizes,
                           const TimingOptions& timing, bool withMachine) {
    bool gpuClock = false;
    auto rows = runLodSection(renderer, lod, sizes, timing, &gpuClock);
    if (!rows) return std::move(rows).error();
    const auto csv = std::filesystem::path(timing.output) / "lod.csv";
    LANTERN_TRY(writeTextFile(csv.string(), lodCsv(*rows)));
    std::printf("wrote %s\n", csv.c_str());
    const std::string head = withMachine ? "# Level of detail against the exact frame\n\n" +
                                               machineDescription(renderer) + "\n\nReproduce: `" +
                                               commandLine() + "`\n\n"
                                         : "\n";
    return head + lodSummaryMarkdown(*rows, gpuClock);
}

} // namespace lantern::cli
