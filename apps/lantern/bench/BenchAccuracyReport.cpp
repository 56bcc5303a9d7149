// The report of `lantern bench accuracy`: accuracy.csv (one line per configuration) and the
// markdown summary naming, per group and error budget, the fastest setting that meets it.
#include "bench/BenchAccuracy.h"
#include "bench/BenchHarness.h"

#include <algorithm>
#include <sstream>

namespace lantern::cli {
namespace {

std::string csvHeader() {
    return "scene,shininess,width,height,shading,segments,triangles,msaa,ms_per_frame,ms_min,"
           "ms_wall,ms_round_spread,first_frame_ms,pipelines_compiled,floor_ms,x_floor,rmse,psnr_"
           "db,max_error,"
           "interior_pixels,interior_rmse,interior_max,interior_p99,silhouette_pixels,"
           "silhouette_rmse,silhouette_max,silhouette_p99,peak_ratio,nonfinite,pareto_interior,"
           "pareto_whole,transparency,shadow_resolution,shadow_filter,wrong_shadow_share,shadow_cascades\n";
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
      << (r.paretoWhole ? 1 : 0) << ',' << r.transparency << ','
      << (r.shadowResolution > 0 ? std::to_string(r.shadowResolution) : "") << ',' << r.shadowFilter
      << ',' << (r.wrongShadowShare >= 0.0 ? num(r.wrongShadowShare, "%.5f") : "") << ','
      << (r.shadowCascades > 0 ? std::to_string(r.shadowCascades) : "") << '\n';
    return s.str();
}

std::string xFloor(const AccuracyRow& r) {
    return r.floorMs > 0.0 ? num(r.ms / r.floorMs, "%.1f") : "-";
}

// The title and how it was measured.
void methodMarkdown(std::ostringstream& md, const AccuracyMethod& how) {
    md << "# Speed against accuracy: `lantern bench accuracy`\n\n"
       << "Machine: " << how.machine << ".\n\n"
       << "Reproduce: `" << commandLine() << "`\n\n"
       << "Frame time: "
       << (how.gpuClock ? "the render pass on the device's timestamps" : "render() wall time")
       << ", median of " << how.plan.rounds << " rounds' medians of " << how.plan.frames
       << " frames after " << how.plan.warmup
       << " warm-up frames, every configuration interleaved with the others in each round. "
       << "Errors: linear RGB against a double-precision ray cast of the exact surfaces ("
       << how.referenceSamples << "x" << how.referenceSamples
       << " box filter for the whole image and silhouettes, the pixel centre for the interior; "
       << "references took " << num(how.referenceSeconds, "%.1f") << " s). "
       << "x floor: the frame time over the trivial shader's on the same geometry and pixels. "
       << how.spread << "\n\n";
}

// The two Pareto fronts of one group (`in`: its rows, fastest first).
void paretoMarkdown(std::ostringstream& md, const std::vector<const AccuracyRow*>& in) {
    md << "Pareto front, interior RMSE (shading alone):\n\n"
       << "| setting | triangles | ms | x floor | interior RMSE | interior max | peak ratio | "
          "whole RMSE | PSNR dB |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const AccuracyRow* r : in)
        if (r->paretoInterior)
            md << "| " << r->setting() << " | " << r->triangles << " | " << num(r->ms, "%.2f")
               << " | " << xFloor(*r) << " | " << num(r->error.interior.rmse, "%.2e") << " | "
               << num(r->error.interior.max, "%.2e") << " | " << num(r->error.peakRatio, "%.3f")
               << " | " << num(r->error.whole.rmse, "%.2e") << " | " << num(r->error.psnr, "%.1f")
               << " |\n";
    md << "\nPareto front, whole-image RMSE (shading, silhouettes and aliasing):\n\n"
       << "| setting | triangles | ms | x floor | whole RMSE | silhouette RMSE | interior RMSE "
          "|\n|---|---|---|---|---|---|---|\n";
    for (const AccuracyRow* r : in)
        if (r->paretoWhole)
            md << "| " << r->setting() << " | " << r->triangles << " | " << num(r->ms, "%.2f")
               << " | " << xFloor(*r) << " | " << num(r->error.whole.rmse, "%.2e") << " | "
               << num(r->error.silhouette.rmse, "%.2e") << " | "
               << num(r->error.interior.rmse, "%.2e") << " |\n";
}

// The fastest setting of one group (`in`: its rows, fastest first) within each error budget.
void budgetMarkdown(std::ostringstream& md, const std::vector<const AccuracyRow*>& in) {
    const double interiorBudgets[] = {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
    const double wholeBudgets[] = {3e-2, 1e-2, 5e-3, 3e-3, 2e-3, 1e-3, 5e-4};
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

// The shadow scene's rows (`in`: fastest first): each setting's share of pixels whose shadowed
// state is wrong, and the Pareto front of (ms, that share).
void shadowMarkdown(std::ostringstream& md, const std::vector<const AccuracyRow*>& in) {
    std::vector<const AccuracyRow*> rows;
    for (const AccuracyRow* r : in)
        if (r->wrongShadowShare >= 0.0) rows.push_back(r);
    if (rows.empty()) return;
    md << "Shadow maps against the exact shadow rays: the share of fully covered pixels whose "
          "shadowed state is wrong (front: no faster setting is as right):\n\n"
       << "| setting | ms | wrong shadow % | interior RMSE | whole RMSE | front |\n"
          "|---|---|---|---|---|---|\n";
    double best = 2.0;  // the smallest share of any faster row
    for (const AccuracyRow* r : rows) {
        const bool front = r->wrongShadowShare < best;
        best = std::min(best, r->wrongShadowShare);
        md << "| " << r->setting() << " | " << num(r->ms, "%.2f") << " | "
           << num(100.0 * r->wrongShadowShare, "%.3f") << " | " << num(r->error.interior.rmse, "%.2e")
           << " | " << num(r->error.whole.rmse, "%.2e") << " | " << (front ? "yes" : "") << " |\n";
    }
    md << "\n";
}

} // namespace

std::string accuracyCsv(const std::vector<AccuracyRow>& rows) {
    std::string csv = csvHeader();
    for (const AccuracyRow& r : rows)
        csv += csvRow(r);
    return csv;
}

std::string accuracySummaryMarkdown(const std::vector<AccuracyRow>& rows,
                                    const AccuracyMethod& how) {
    std::ostringstream md;
    methodMarkdown(md, how);
    std::vector<std::string> groups;
    for (const AccuracyRow& r : rows)
        if (std::find(groups.begin(), groups.end(), r.group()) == groups.end())
            groups.push_back(r.group());
    for (const std::string& g : groups) {
        std::vector<const AccuracyRow*> in;
        for (const AccuracyRow& r : rows)
            if (r.group() == g) in.push_back(&r);
        std::sort(in.begin(), in.end(),
                  [](const AccuracyRow* x, const AccuracyRow* y) { return x->ms < y->ms; });
        md << "## " << g << "\n\n";
        paretoMarkdown(md, in);
        budgetMarkdown(md, in);
        shadowMarkdown(md, in);
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

} // namespace lantern::cli
