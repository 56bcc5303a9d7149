// The comparison options and report of `lantern compare` and `lantern render --compare`.
#include "common/CompareCli.h"

#include "common/CliSupport.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>

namespace lantern::cli {
namespace {

std::string fmt(double v, int precision = 6) {
    if (std::isnan(v)) return "-";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s << std::setprecision(precision) << v;
    return s.str();
}

bool hasExtension(const std::string& path, std::initializer_list<const char*> exts) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char* e : exts)
        if (ext == e) return true;
    return false;
}

void print(const CompareReport& r) {
    std::cout << "reference " << r.reference << ", test " << r.test << ": " << r.width << "x"
              << r.height << ", " << (r.encoding == PixelEncoding::Srgb ? "sRGB" : "linear") << "\n";
    std::cout << std::left << std::setw(8) << "channel" << std::right << std::setw(13) << "max abs"
              << std::setw(14) << "at" << std::setw(13) << "mean abs" << std::setw(10) << "PSNR dB"
              << std::setw(10) << "SSIM" << std::setw(12) << "over tol %" << "\n";
    for (const ChannelStats& c : r.channels) {
        const std::string at =
            c.maxX >= 0 ? "(" + std::to_string(c.maxX) + "," + std::to_string(c.maxY) + ")" : "-";
        std::cout << std::left << std::setw(8) << c.name << std::right << std::setw(13)
                  << fmt(c.maxAbs) << std::setw(14) << at << std::setw(13) << fmt(c.meanAbs)
                  << std::setw(10) << fmt(c.psnr, 4) << std::setw(10) << fmt(c.ssim, 5)
                  << std::setw(12) << fmt(c.overShare * 100.0, 4) << "\n";
        if (c.nonFiniteRef + c.nonFiniteTest > 0)
            std::cout << "        NaN/Inf values: " << c.nonFiniteRef << " in the reference, "
                      << c.nonFiniteTest << " in the test\n";
    }
    std::cout << std::left << std::setw(8) << "all" << std::right << std::setw(13) << fmt(r.maxAbs)
              << std::setw(14) << "" << std::setw(13) << fmt(r.meanAbs) << std::setw(10)
              << fmt(r.psnr, 4) << std::setw(10) << fmt(r.ssim, 5) << std::setw(12)
              << fmt(r.overShare * 100.0, 4) << "  (tolerance " << fmt(r.tolerance) << ")\n";
    if (r.flip)
        std::cout << "FLIP (" << (r.flip->hdr ? "HDR" : "LDR") << ", " << fmt(r.flip->pixelsPerDegree, 4)
                  << " px/degree): mean " << fmt(r.flip->mean) << ", median " << fmt(r.flip->median)
                  << ", 95th percentile " << fmt(r.flip->p95) << ", max " << fmt(r.flip->max)
                  << (r.flip->hdr ? ", exposures " + fmt(r.flip->startExposure, 4) + " to " +
                                        fmt(r.flip->stopExposure, 4) + " (" +
                                        std::to_string(r.flip->exposures) + ")"
                                  : std::string())
                  << "\n";
    std::cout << r.summary << "\n";
}

} // namespace

void CompareCliOptions::add(CLI::App& app) {
    app.add_option("--metric", metric,
                   "What the thresholds judge: abs or flip (per pixel, with --fail-percent), "
                   "mae, psnr, ssim, flip-mean (whole image)")
        ->capture_default_str();
    app.add_option("--fail", fail,
                   "Failure threshold: per pixel for abs/flip; for psnr/ssim the lowest value "
                   "that passes, for mae/flip-mean the highest")
        ->capture_default_str();
    app.add_option("--fail-percent,--failpercent", failPercent,
                   "Percentage of pixels allowed over --fail (per-pixel metrics)")
        ->capture_default_str();
    app.add_option("--warn", warn, "Warning threshold (same meaning as --fail; exit 0)");
    app.add_option("--warn-percent,--warnpercent", warnPercent,
                   "Percentage of pixels allowed over --warn")
        ->capture_default_str();
    app.add_option("--tolerance", tolerance,
                   "Per-channel tolerance for the 'over tol' share (default: --fail for abs, "
                   "else 1e-6)");
    app.add_option("--flip", flip, "FLIP form: auto (LDR for PNG, HDR for EXR), ldr, hdr, off")
        ->capture_default_str();
    app.add_option("--ppd", ppd, "FLIP observer's pixels per degree")->capture_default_str();
    app.add_flag("--no-ssim", noSsim, "Skip SSIM");
    app.add_option("--diff", diff, "Write a heat map of the judged metric (.exr or .png)");
    app.add_option("--json", json, "Write the report as JSON");
    app.add_flag("--quiet", quiet, "Print only the verdict line");
}

Result<CompareOptions> CompareCliOptions::options() const {
    CompareOptions o;
    const auto m = parseCompareMetric(metric);
    if (!m)
        return makeError(ErrorCode::Usage,
                         "unknown metric \"" + metric + "\" (abs, flip, mae, psnr, ssim, flip-mean)",
                         "--metric");
    o.thresholds.metric = *m;
    o.thresholds.fail = fail;
    o.thresholds.failPercent = failPercent;
    o.thresholds.warn = warn;
    o.thresholds.warnPercent = warnPercent;
    if (!std::isfinite(fail)) return makeError(ErrorCode::Usage, "must be a finite number", "--fail");
    if (!(failPercent >= 0 && failPercent <= 100))
        return makeError(ErrorCode::Usage, "must be between 0 and 100", "--fail-percent");
    if (warn && !std::isfinite(*warn)) return makeError(ErrorCode::Usage, "must be a finite number", "--warn");
    if (!(warnPercent >= 0 && warnPercent <= 100))
        return makeError(ErrorCode::Usage, "must be between 0 and 100", "--warn-percent");
    if (!(ppd > 0 && std::isfinite(ppd))) return makeError(ErrorCode::Usage, "must be > 0", "--ppd");
    o.pixelsPerDegree = ppd;
    o.pixelTolerance = tolerance;
    o.ssim = !noSsim;
    if (flip == "auto")
        o.flip = FlipForm::Auto;
    else if (flip == "ldr")
        o.flip = FlipForm::Ldr;
    else if (flip == "hdr")
        o.flip = FlipForm::Hdr;
    else if (flip == "off")
        o.flip = FlipForm::Off;
    else
        return makeError(ErrorCode::Usage, "unknown FLIP form \"" + flip + "\" (auto, ldr, hdr, off)", "--flip");
    if (!diff.empty() && !hasExtension(diff, {".exr", ".png"}))
        return makeError(ErrorCode::Usage, "the heat map is written as .exr or .png", "--diff");
    o.keepMaps = !diff.empty();
    return o;
}

int CompareCliOptions::finish(const Result<CompareReport>& report) const {
    if (!report) return cli::report(report.error());
    if (quiet)
        std::cout << report->summary << "\n";
    else
        print(*report);
    if (!diff.empty()) {
        const Image heat = compareHeatMap(*report);
        if (auto w = writeImage(diff, heat); !w) return cli::report(w.error());
    }
    if (!json.empty()) {
        std::ofstream out(json, std::ios::binary | std::ios::trunc);
        out << compareReportJson(*report);
        out.close();
        if (!out)
            return cli::report(makeError(ErrorCode::IoError, "cannot write the JSON report", "--json", json));
    }
    return report->status == CompareStatus::Fail ? kRefused : kOk;
}

int compareRendered(const CompareCliOptions& options, const std::string& reference,
                    const Image& image, const std::string& renderName) {
    auto o = options.options();
    if (!o) return report(o.error());
    auto ref = readCompareImage(reference);
    if (!ref) return report(ref.error());
    const CompareImage test = toCompareImage(image, ref->encoding, renderName);
    return options.finish(compareImages(*ref, test, *o));
}

} // namespace lantern::cli
