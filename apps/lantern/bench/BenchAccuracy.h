// BenchAccuracy.h: the pieces of `lantern bench accuracy`: the analytic benchmark scenes
// (numerics.md section 7.1, S1 and S2), one result row per configuration, the Pareto fronts, the
// CSV and markdown report and the plot (drawn by benchmarks/plot_accuracy.py).
#pragma once

#include "bench/BenchHarness.h"

#include <cstdint>
#include <lantern/Lantern.h>
#include <lantern/Reference.h>
#include <string>
#include <vector>

namespace lantern::cli {

/// A benchmark scene and the analytic surfaces its meshes stand for.
struct BenchScene {
    Scene scene;
    std::vector<AnalyticShape> shapes;
    std::size_t triangles = 0;
};

/// The scene names makeBenchScene() knows: "sphere" (S1), "spot" (S2), the transparency
/// scenes "crossing" (T1), "nested" (T2), "beside" (T3), "torus" (T4) and "foliage" (T5),
/// and the shadow scenes "shadow" (H1) and "field" (H2).
const std::vector<std::string>& benchSceneNames();
/// H1 and H2: the scenes whose lights cast shadows, swept over the shadow options.
bool isShadowScene(const std::string& name);
/// T1 to T5: the scenes of blended surfaces, swept over the transparency methods.
bool isTransparencyScene(const std::string& name);

/// S1 "sphere": a unit sphere 4 units in front of a 40-degree camera, one point light at
/// eye-space (2, 2, 0), GL defaults (distant viewer, no attenuation, global ambient 0.2),
/// material ambient 0.2, diffuse 0.8, specular 1 with the given shininess.
/// S2 "spot": an 8 x 8 plane seen from above at an angle, lit by a GL spot 2 units above it
/// (cutoff 30 degrees, exponent 16, attenuation (1, 0.1, 0.01)), the same material.
/// T1 "crossing": two blended 2 x 2 squares (alpha 0.5) turned +-0.6 rad about Y through the
/// origin. T2 "nested": an opaque sphere (radius 0.4) inside blended spheres of radius 0.7
/// (alpha 0.5) and 1 (alpha 0.3). T3 "beside": a blended 6 x 6 floor (alpha 0.4) at y = -0.5
/// and a blended sphere (radius 0.5, alpha 0.6) standing on its far half. T4 "torus": a
/// blended torus (ring radius 1, tube 0.35, alpha 0.5) tilted 1.1 rad about X towards the
/// eye. T5 "foliage": six 1 x 1 leaves, alpha-masked by a 32 x 32 texture (an ellipse,
/// sampled nearest), tilted above a blended 6 x 6 pond (alpha 0.5) at y = -0.5. Blended and
/// masked materials are double-sided; the same light as S1, the camera looking at the origin.
/// H1 "shadow": an opaque sphere (radius 0.5) 1 above a 4 x 4 plane, lit by a directional light
/// 38.7 degrees above the plane that casts shadows (LANTERN_lights_shadow), seen from above at
/// an angle; the reference casts exact shadow rays. H2 "field": five such spheres 0.7 above
/// a 40 x 40 plane in a row from 12 to -12 along Z, a directional light from the side, the
/// camera 1.5 above the plane at Z = 18 looking at the origin (cascades matter here).
/// `segments`: sphere segments around (segments / 2 rings), or plane subdivisions per side.
BenchScene makeBenchScene(const std::string& name, double shininess, int segments);

/// One configuration of the accuracy sweep and what it measured.
struct AccuracyRow {
    std::string scene;
    double shininess = 0.0;
    int width = 0, height = 0;
    ShadingMode shading = ShadingMode::Phong;
    int segments = 0;
    std::size_t triangles = 0;
    int msaa = 1;
    /// The transparency scenes: "sorted", "exact" or "weighted" (--transparency); else empty.
    std::string transparency;
    /// The shadow scenes: texels per map side, "hardware", "pcf" or "pcss", and the
    /// directional light's cascades; else 0 and empty.
    int shadowResolution = 0;
    std::string shadowFilter;
    int shadowCascades = 0;
    /// The shadow scene: the share of the reference's fully covered plane and sphere pixels
    /// whose shadowed state (shadowWrongShare()) the render gets wrong; < 0: not measured.
    double wrongShadowShare = -1.0;
    double ms = 0.0;           ///< median of the rounds' median frame times
    double msMin = 0.0;        ///< fastest timed frame
    double msWall = 0.0;       ///< median render() wall time, readback included
    double spread = 0.0;       ///< (slowest - fastest round median) / ms: the drift seen
    double firstMs = 0.0;      ///< the first frame (pipeline JIT when it compiled variants)
    std::size_t pipelines = 0; ///< variants the first frame compiled
    double floorMs = -1.0; ///< the trivial shader on the same geometry and pixels; < 0: not timed
    ErrorMetrics error;
    std::uint64_t replacedNonFinite = 0; ///< NaN/Inf the renderer replaced while timing
    bool paretoInterior = false;         ///< on the front of (ms, interior RMSE) within its group
    bool paretoWhole = false; ///< on the front of (ms, whole-image RMSE) within its group

    /// The comparable set: same scene, shininess and resolution.
    std::string group() const;
    /// "phong, 64 segments, 1x" for tables (", exact" after it for a transparency scene,
    /// ", 1024 texels, pcf" for the shadow scene).
    std::string setting() const;
};

/// The share of `shadowed`'s interior pixels whose state, lit or shadowed, `render` gets wrong:
/// a pixel is shadowed where its colour (R + G + B) falls below the unshadowed reference `lit`'s
/// by more than half the largest fall the exact shadow makes anywhere in the picture.
double shadowWrongShare(const Image& render, const ReferenceImage& shadowed, const ReferenceImage& lit);

/// Marks the Pareto fronts (no other row of the group is at least as fast and at least as
/// accurate, and better in one) for the interior and whole-image RMSE.
void markParetoFronts(std::vector<AccuracyRow>& rows);

/// accuracy.csv: a header line, then one line per row.
std::string accuracyCsv(const std::vector<AccuracyRow>& rows);

/// How the sweep was measured, as the summary's first paragraph says it.
struct AccuracyMethod {
    std::string machine;   ///< machineDescription()
    bool gpuClock = false; ///< frame times from the device's timestamps, else render() wall time
    TimingPlan plan;
    int referenceSamples = 0; ///< the references' box filter: N x N rays per pixel
    double referenceSeconds = 0.0;
    std::string spread; ///< spreadSentence() of the configurations' round spreads
};

/// accuracy.md: how it was measured; per group, the Pareto fronts and the fastest setting that
/// meets each error budget; the first frames' pipeline compiles; the non-finite values seen.
std::string accuracySummaryMarkdown(const std::vector<AccuracyRow>& rows,
                                    const AccuracyMethod& how);

/// The level-of-detail section's settings (--lod-errors, --lod-scene, --lod-grid, --lod-segments).
struct LodSection {
    std::vector<double> bounds{0.25, 0.5, 1.0, 2.0, 4.0, 8.0}; ///< besides 0, always timed
    std::string scene; ///< a scene file or builtin:NAME; empty: makeLodGrid(grid, segments)
    int grid = 10, segments = 160;

    void add(CLI::App& app);
    /// --quick: a 6 x 6 grid of 64-segment spheres unless the command line gave them.
    void applyQuick();

private:
    CLI::Option *m_grid = nullptr, *m_segments = nullptr;
};

/// The level-of-detail section's scene: side x side unit spheres (one mesh of `segments`
/// around, shared by every node) 2.5 apart in the plane z = 0, S1's light and material, the
/// 40-degree camera on +Z seeing the whole grid.
BenchScene makeLodGrid(int side, int segments);

/// One bound of the level-of-detail section at one image size.
struct LodRow {
    std::string scene;
    int width = 0, height = 0;
    double bound = 0.0; ///< --lod-error, pixels
    double ms = 0.0, msWall = 0.0, spread = 0.0; ///< as AccuracyRow's
    std::uint64_t triangles = 0, trianglesDrawn = 0; ///< clustered triangles, last timed frame
    double rmse = 0.0;     ///< linear RGB against the exact frame (bound 0)
    double flipMean = 0.0; ///< the FLIP mean of `lantern compare` against the exact frame
    std::uint64_t nonFinite = 0;
    bool pareto = false; ///< on the front of (ms, FLIP mean) within its image size
};

/// Times every bound (and 0) at every size interleaved, measures each against the exact frame
/// and marks the Pareto fronts. `gpuClock` as timeInterleaved's.
Result<std::vector<LodRow>> runLodSection(Renderer& renderer, const LodSection& lod,
                                          const std::vector<std::pair<int, int>>& sizes,
                                          const TimingOptions& timing, bool* gpuClock);
/// lod.csv: a header line, then one line per row.
std::string lodCsv(const std::vector<LodRow>& rows);
/// The "Level of detail" section of accuracy.md: a table per image size.
std::string lodSummaryMarkdown(const std::vector<LodRow>& rows, bool gpuClock);

/// The section whole: runLodSection, lod.csv in timing.output, and the section's markdown
/// (after a title, the machine and the command line when `withMachine`: the section alone).
Result<std::string> runLod(Renderer& renderer, const LodSection& lod,
                           const std::vector<std::pair<int, int>>& sizes,
                           const TimingOptions& timing, bool withMachine);

/// Where benchmarks/plot_accuracy.py is: installed beside the command (share/lantern), else the
/// source tree's; the bare name when neither exists.
std::string plotScriptPath();

/// What became of the plot: drawn, or why not and the command that draws it.
struct PlotOutcome {
    bool drawn = false;
    std::string message; ///< the command run, or why it was not (with the command to run)
};

/// Draws `csv` into `outputs` (.svg, .png) with plot_accuracy.py when python3 has matplotlib.
PlotOutcome plotAccuracy(const std::string& csv, const std::vector<std::string>& outputs);

} // namespace lantern::cli
