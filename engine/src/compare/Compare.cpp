// compareImages: the per-channel statistics, SSIM and FLIP, judged against idiff-style
// thresholds; the heat map and the JSON report.
#include <lantern/Compare.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace lantern {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ",") + x;
    return s;
}

std::string sizeText(const CompareImage& i) {
    return std::to_string(i.width) + "x" + std::to_string(i.height);
}

const char* encodingText(PixelEncoding e) {
    return e == PixelEncoding::Srgb ? "8/16-bit sRGB (PNG)" : "linear float (EXR)";
}

Result<void> checkComparable(const CompareImage& ref, const CompareImage& test) {
    for (const CompareImage* i : {&ref, &test})
        if (i->width <= 0 || i->height <= 0 || i->channels.empty() ||
            i->values.size() != i->pixelCount() * i->channels.size())
            return makeError(ErrorCode::InvalidInput, "image has no pixels, no channels or a wrong value count",
                             {}, i->source);
    if (ref.width != test.width || ref.height != test.height)
        return makeError(ErrorCode::InvalidInput,
                         "sizes differ: reference " + ref.source + " is " + sizeText(ref) + ", test " +
                             test.source + " is " + sizeText(test),
                         {}, test.source);
    std::vector<std::string> a = ref.channels, b = test.channels;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    if (a != b || std::adjacent_find(a.begin(), a.end()) != a.end())
        return makeError(ErrorCode::InvalidInput,
                         "channels differ: reference " + ref.source + " has " + join(ref.channels) +
                             ", test " + test.source + " has " + join(test.channels),
                         {}, test.source);
    if (ref.encoding != test.encoding)
        return makeError(ErrorCode::InvalidInput,
                         std::string("encodings differ: reference ") + ref.source + " is " +
                             encodingText(ref.encoding) + ", test " + test.source + " is " +
                             encodingText(test.encoding) + " (compare EXR with EXR, PNG with PNG)",
                         {}, test.source);
    return {};
}

std::vector<std::string> colourChannelsOf(const CompareImage& image) {
    if (image.channelIndex("R") >= 0 && image.channelIndex("G") >= 0 && image.channelIndex("B") >= 0)
        return {"R", "G", "B"};
    if (image.channelIndex("Y") >= 0) return {"Y"};
    return image.channels;
}

bool perPixel(CompareMetric m) { return m == CompareMetric::Abs || m == CompareMetric::Flip; }

// Whether `value` passes `limit` for a whole-image metric.
bool exceeds(CompareMetric m, double value, double limit) {
    if (m == CompareMetric::Psnr || m == CompareMetric::Ssim) return !(value >= limit);
    return !(value <= limit);
}

std::string number(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

} // namespace

const char* toString(CompareMetric m) noexcept {
    switch (m) {
    case CompareMetric::Abs: return "abs";
    case CompareMetric::Flip: return "flip";
    case CompareMetric::Mae: return "mae";
    case CompareMetric::Psnr: return "psnr";
    case CompareMetric::Ssim: return "ssim";
    case CompareMetric::FlipMean: return "flip-mean";
    }
    return "abs";
}

std::optional<CompareMetric> parseCompareMetric(std::string_view t) noexcept {
    for (CompareMetric m : {CompareMetric::Abs, CompareMetric::Flip, CompareMetric::Mae,
                            CompareMetric::Psnr, CompareMetric::Ssim, CompareMetric::FlipMean})
        if (t == toString(m)) return m;
    return std::nullopt;
}

const char* toString(CompareStatus s) noexcept {
    return s == CompareStatus::Pass ? "pass" : s == CompareStatus::Warn ? "warn" : "fail";
}

Result<CompareReport> compareImages(const CompareImage& ref, const CompareImage& test,
                                    const CompareOptions& options) {
    LANTERN_TRY(checkComparable(ref, test));
    const CompareThresholds& th = options.thresholds;
    if (!std::isfinite(th.fail) || !std::isfinite(th.failPercent) || th.failPercent < 0 ||
        (th.warn && !std::isfinite(*th.warn)) || !std::isfinite(th.warnPercent) || th.warnPercent < 0)
        return makeError(ErrorCode::Usage, "thresholds must be finite and percentages >= 0");
    if ((th.metric == CompareMetric::Flip || th.metric == CompareMetric::FlipMean) &&
        options.flip == FlipForm::Off)
        return makeError(ErrorCode::Usage, std::string("metric ") + toString(th.metric) + " needs FLIP, which is off");
    if (th.metric == CompareMetric::Ssim && !options.ssim)
        return makeError(ErrorCode::Usage, "metric ssim needs SSIM, which is off");

    CompareReport rep;
    rep.reference = ref.source;
    rep.test = test.source;
    rep.width = ref.width;
    rep.height = ref.height;
    rep.encoding = ref.encoding;
    rep.thresholds = th;
    rep.colourChannels = colourChannelsOf(ref);
    rep.tolerance = options.pixelTolerance >= 0 ? options.pixelTolerance
                    : th.metric == CompareMetric::Abs ? th.fail
                                                      : 1e-6;
    const std::size_t n = ref.pixelCount(), nc = ref.channels.size();
    std::vector<std::size_t> testIndex(nc);
    for (std::size_t c = 0; c < nc; ++c) testIndex[c] = std::size_t(test.channelIndex(ref.channels[c]));

    // --- Absolute errors, PSNR, shares over the tolerance ---------------------------------
    auto start = std::chrono::steady_clock::now();
    rep.channels.resize(nc);
    std::vector<double> sum(nc, 0.0), sumSq(nc, 0.0);
    std::vector<std::uint64_t> over(nc, 0), finite(nc, 0);
    std::vector<float> absMap(n, 0.0f);
    std::vector<unsigned char> mismatch(n, 0);
    std::uint64_t overAny = 0;
    double sumAll = 0.0;
    std::uint64_t finiteAll = 0;
    for (std::size_t c = 0; c < nc; ++c) rep.channels[c].name = ref.channels[c];
    for (std::size_t i = 0; i < n; ++i) {
        const float* a = ref.values.data() + i * nc;
        const float* b = test.values.data() + i * test.channels.size();
        float pixelMax = 0.0f;
        bool bad = false, overHere = false;
        for (std::size_t c = 0; c < nc; ++c) {
            const float x = a[c], y = b[testIndex[c]];
            ChannelStats& s = rep.channels[c];
            const bool fx = std::isfinite(x), fy = std::isfinite(y);
            if (!fx) ++s.nonFiniteRef;
            if (!fy) ++s.nonFiniteTest;
            if (!fx || !fy) {
                // The same Inf (or NaN in both) matches; anything else is a mismatch.
                const bool same = (std::isnan(x) && std::isnan(y)) || x == y;
                if (!same) {
                    bad = true;
                    ++over[c];
                }
                continue;
            }
            const double e = std::abs(double(y) - double(x));
            sum[c] += e;
            sumSq[c] += e * e;
            ++finite[c];
            if (e > s.maxAbs) {
                s.maxAbs = e;
                s.maxX = int(i % std::size_t(ref.width));
                s.maxY = int(i / std::size_t(ref.width));
            }
            if (e > rep.tolerance) {
                ++over[c];
                overHere = true;
            }
            pixelMax = std::max(pixelMax, float(e));
        }
        if (bad) {
            ++rep.nonFiniteMismatch;
            mismatch[i] = 1;
            absMap[i] = std::numeric_limits<float>::quiet_NaN();
        } else {
            absMap[i] = pixelMax;
        }
        if (bad || overHere) ++overAny;
    }
    double colourMse = 0.0;
    for (std::size_t c = 0; c < nc; ++c) {
        ChannelStats& s = rep.channels[c];
        const double count = double(std::max<std::uint64_t>(finite[c], 1));
        s.meanAbs = sum[c] / count;
        s.mse = sumSq[c] / count;
        s.psnr = s.mse > 0.0 ? 10.0 * std::log10(1.0 / s.mse) : kInf;
        s.overShare = double(over[c]) / double(n);
        s.ssim = std::numeric_limits<double>::quiet_NaN();
        rep.maxAbs = std::max(rep.maxAbs, s.maxAbs);
        sumAll += sum[c];
        finiteAll += finite[c];
        if (std::find(rep.colourChannels.begin(), rep.colourChannels.end(), s.name) != rep.colourChannels.end())
            colourMse += s.mse / double(rep.colourChannels.size());
    }
    rep.meanAbs = sumAll / double(std::max<std::uint64_t>(finiteAll, 1));
    rep.psnr = colourMse > 0.0 ? 10.0 * std::log10(1.0 / colourMse) : kInf;
    rep.overShare = double(overAny) / double(n);
    rep.secondsAbs = secondsSince(start);

    // One channel of both images as planes, a non-finite value in either image zero in both.
    auto planes = [&](std::size_t c, std::vector<float>& x, std::vector<float>& y) {
        x.resize(n);
        y.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const float a = ref.values[i * nc + c], b = test.values[i * test.channels.size() + testIndex[c]];
            const bool ok = std::isfinite(a) && std::isfinite(b);
            x[i] = ok ? a : 0.0f;
            y[i] = ok ? b : 0.0f;
        }
    };

    // --- SSIM -----------------------------------------------------------------------------
    rep.ssim = std::numeric_limits<double>::quiet_NaN();
    if (options.ssim) {
        start = std::chrono::steady_clock::now();
        std::vector<float> x, y;
        double colourSsim = 0.0;
        for (std::size_t c = 0; c < nc; ++c) {
            planes(c, x, y);
            ChannelStats& s = rep.channels[c];
            s.ssim = ssimChannel(x.data(), y.data(), ref.width, ref.height, 1.0);
            if (std::find(rep.colourChannels.begin(), rep.colourChannels.end(), s.name) != rep.colourChannels.end())
                colourSsim += s.ssim / double(rep.colourChannels.size());
        }
        rep.ssim = colourSsim;
        rep.secondsSsim = secondsSince(start);
    }

    // --- FLIP -----------------------------------------------------------------------------
    std::vector<float> flipMap;
    const bool hasRgb = rep.colourChannels.size() == 3 && rep.colourChannels[0] == "R";
    const bool hasY = rep.colourChannels.size() == 1 && rep.colourChannels[0] == "Y";
    if (options.flip != FlipForm::Off && (hasRgb || hasY)) {
        start = std::chrono::steady_clock::now();
        std::vector<float> r(n * 3), t(n * 3), x, y;
        for (int k = 0; k < 3; ++k) {
            const std::size_t c = std::size_t(ref.channelIndex(hasRgb ? rep.colourChannels[std::size_t(k)] : "Y"));
            planes(c, x, y);
            for (std::size_t i = 0; i < n; ++i) {
                r[i * 3 + std::size_t(k)] = x[i];
                t[i * 3 + std::size_t(k)] = y[i];
            }
        }
        FlipStats fs;
        fs.pixelsPerDegree = options.pixelsPerDegree;
        const bool hdr = options.flip == FlipForm::Hdr ||
                         (options.flip == FlipForm::Auto && ref.encoding == PixelEncoding::Linear);
        if (hdr) {
            if (ref.encoding == PixelEncoding::Srgb)
                for (std::vector<float>* v : {&r, &t})
                    for (float& f : *v) {
                        f = std::clamp(f, 0.0f, 1.0f);
                        f = f <= 0.04045f ? f / 12.92f : std::pow((f + 0.055f) / 1.055f, 2.4f);
                    }
            flipMap = flipHdr(r.data(), t.data(), ref.width, ref.height, options.pixelsPerDegree, &fs);
        } else {
            flipMap = flipLdr(r.data(), t.data(), ref.width, ref.height,
                              ref.encoding == PixelEncoding::Srgb, options.pixelsPerDegree);
        }
        double total = 0.0;
        for (float v : flipMap) {
            total += v;
            fs.max = std::max(fs.max, double(v));
        }
        fs.mean = total / double(n);
        std::vector<float> sorted = flipMap;
        std::sort(sorted.begin(), sorted.end());
        auto pct = [&](double q) {
            const double pos = q * double(n - 1);
            const std::size_t lo = std::size_t(pos);
            const double hi = sorted[std::min(lo + 1, n - 1)];
            return sorted[lo] + (hi - sorted[lo]) * (pos - double(lo));
        };
        fs.median = pct(0.5);
        fs.p95 = pct(0.95);
        rep.flip = fs;
        rep.secondsFlip = secondsSince(start);
    }
    if ((th.metric == CompareMetric::Flip || th.metric == CompareMetric::FlipMean) && !rep.flip)
        return makeError(ErrorCode::InvalidInput,
                         std::string("metric ") + toString(th.metric) + " needs R,G,B or Y channels; " +
                             ref.source + " has " + join(ref.channels),
                         {}, ref.source);

    // --- Judgement ------------------------------------------------------------------------
    auto judge = [&](double limit, double percent, double& value) {
        if (perPixel(th.metric)) {
            const std::vector<float>& map = th.metric == CompareMetric::Abs ? absMap : flipMap;
            std::uint64_t failing = 0;
            for (std::size_t i = 0; i < n; ++i) failing += mismatch[i] || map[i] > limit;
            value = double(failing) / double(n);
            return value * 100.0 > percent;
        }
        value = th.metric == CompareMetric::Mae    ? rep.meanAbs
                : th.metric == CompareMetric::Psnr ? rep.psnr
                : th.metric == CompareMetric::Ssim ? rep.ssim
                                                   : rep.flip->mean;
        return exceeds(th.metric, value, limit);
    };
    const bool failed = judge(th.fail, th.failPercent, rep.judged) || rep.nonFiniteMismatch > 0;
    bool warned = false;
    if (th.warn) warned = judge(*th.warn, th.warnPercent, rep.judgedWarn);
    rep.status = failed ? CompareStatus::Fail : warned ? CompareStatus::Warn : CompareStatus::Pass;
    std::ostringstream s;
    s << toString(rep.status) << ": ";
    if (perPixel(th.metric))
        s << number(rep.judged * 100.0) << "% of pixels have " << toString(th.metric) << " > "
          << number(th.fail) << " (allowed " << number(th.failPercent) << "%)";
    else
        s << toString(th.metric) << " " << number(rep.judged)
          << (th.metric == CompareMetric::Psnr || th.metric == CompareMetric::Ssim ? " (must be >= " : " (must be <= ")
          << number(th.fail) << ")";
    if (rep.nonFiniteMismatch > 0)
        s << "; " << rep.nonFiniteMismatch << " pixels hold NaN or Inf in one image only";
    if (warned && !failed) s << "; over the warning threshold " << number(*th.warn);
    rep.summary = s.str();

    if (options.keepMaps) {
        rep.absMap = std::move(absMap);
        rep.flipMap = std::move(flipMap);
    }
    return rep;
}

Result<CompareReport> compareFiles(const std::filesystem::path& reference,
                                   const std::filesystem::path& test, const CompareOptions& options) {
    auto ref = readCompareImage(reference);
    if (!ref) return std::move(ref).error();
    auto tst = readCompareImage(test);
    if (!tst) return std::move(tst).error();
    return compareImages(*ref, *tst, options);
}

Image compareHeatMap(const CompareReport& report) {
    const bool flip = report.thresholds.metric == CompareMetric::Flip ||
                      report.thresholds.metric == CompareMetric::FlipMean;
    const std::vector<float>& map = flip && !report.flipMap.empty() ? report.flipMap : report.absMap;
    const std::size_t n = std::size_t(report.width) * std::size_t(report.height);
    if (map.size() != n || n == 0) return {};
    // Divided by the largest error in float, so that the largest pixel maps to exactly 1.
    const float largest = (&map == &report.flipMap) ? 1.0f : float(report.maxAbs);
    Image out(report.width, report.height);
    for (std::size_t i = 0; i < n; ++i) {
        float* p = out.rgba.data() + i * 4;
        p[3] = 1.0f;
        if (std::isnan(map[i])) {  // a NaN/Inf mismatch
            p[0] = 1.0f;
            p[1] = 0.0f;
            p[2] = 1.0f;
            continue;
        }
        // black -> red -> yellow -> white
        const float t = largest > 0.0f ? std::clamp(map[i] / largest, 0.0f, 1.0f) * 3.0f : 0.0f;
        p[0] = std::min(t, 1.0f);
        p[1] = std::clamp(t - 1.0f, 0.0f, 1.0f);
        p[2] = std::clamp(t - 2.0f, 0.0f, 1.0f);
    }
    return out;
}

std::string compareReportJson(const CompareReport& r) {
    using nlohmann::json;
    auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
    json channels = json::array();
    for (const ChannelStats& c : r.channels)
        channels.push_back({{"name", c.name},
                            {"max_abs", c.maxAbs},
                            {"max_at", c.maxX >= 0 ? json::array({c.maxX, c.maxY}) : json(nullptr)},
                            {"mean_abs", c.meanAbs},
                            {"mse", c.mse},
                            {"psnr", num(c.psnr)},
                            {"ssim", num(c.ssim)},
                            {"over_share", c.overShare},
                            {"non_finite_reference", c.nonFiniteRef},
                            {"non_finite_test", c.nonFiniteTest}});
    json out = {{"reference", r.reference},
                {"test", r.test},
                {"width", r.width},
                {"height", r.height},
                {"encoding", r.encoding == PixelEncoding::Srgb ? "srgb" : "linear"},
                {"channels", channels},
                {"colour_channels", r.colourChannels},
                {"max_abs", r.maxAbs},
                {"mean_abs", r.meanAbs},
                {"psnr", num(r.psnr)},
                {"identical", r.maxAbs == 0.0 && r.nonFiniteMismatch == 0},
                {"ssim", num(r.ssim)},
                {"tolerance", r.tolerance},
                {"over_share", r.overShare},
                {"non_finite_mismatch", r.nonFiniteMismatch},
                {"metric", toString(r.thresholds.metric)},
                {"fail", r.thresholds.fail},
                {"fail_percent", r.thresholds.failPercent},
                {"warn", r.thresholds.warn ? json(*r.thresholds.warn) : json(nullptr)},
                {"warn_percent", r.thresholds.warnPercent},
                {"judged", num(r.judged)},
                {"status", toString(r.status)},
                {"summary", r.summary},
                {"seconds", {{"abs", r.secondsAbs}, {"ssim", r.secondsSsim}, {"flip", r.secondsFlip}}}};
    if (r.flip)
        out["flip"] = {{"form", r.flip->hdr ? "hdr" : "ldr"},
                       {"mean", r.flip->mean},
                       {"max", r.flip->max},
                       {"median", r.flip->median},
                       {"p95", r.flip->p95},
                       {"pixels_per_degree", r.flip->pixelsPerDegree},
                       {"start_exposure", r.flip->hdr ? json(r.flip->startExposure) : json(nullptr)},
                       {"stop_exposure", r.flip->hdr ? json(r.flip->stopExposure) : json(nullptr)},
                       {"exposures", r.flip->exposures}};
    else
        out["flip"] = nullptr;
    return out.dump(2) + "\n";
}

} // namespace lantern
