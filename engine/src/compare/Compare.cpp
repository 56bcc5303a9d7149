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

namespace {

Result<void> checkOptions(const CompareOptions& options) {
    const CompareThresholds& th = options.thresholds;
    if (!std::isfinite(th.fail) || !std::isfinite(th.failPercent) || th.failPercent < 0 ||
        (th.warn && !std::isfinite(*th.warn)) || !std::isfinite(th.warnPercent) || th.warnPercent < 0)
        return makeError(ErrorCode::Usage, "thresholds must be finite and percentages >= 0");
    if ((th.metric == CompareMetric::Flip || th.metric == CompareMetric::FlipMean) &&
        options.flip == FlipForm::Off)
        return makeError(ErrorCode::Usage, std::string("metric ") + toString(th.metric) + " needs FLIP, which is off");
    if (th.metric == CompareMetric::Ssim && !options.ssim)
        return makeError(ErrorCode::Usage, "metric ssim needs SSIM, which is off");
    return {};
}

// The two images of one comparison, the test's channels looked up in the reference's order.
struct ImagePair {
    const CompareImage& ref;
    const CompareImage& test;
    std::size_t n = 0, nc = 0;
    std::vector<std::size_t> testIndex;

    ImagePair(const CompareImage& r, const CompareImage& t)
        : ref(r), test(t), n(r.pixelCount()), nc(r.channels.size()), testIndex(nc) {
        for (std::size_t c = 0; c < nc; ++c) testIndex[c] = std::size_t(test.channelIndex(ref.channels[c]));
    }
    float refValue(std::size_t i, std::size_t c) const { return ref.values[i * nc + c]; }
    float testValue(std::size_t i, std::size_t c) const {
        return test.values[i * test.channels.size() + testIndex[c]];
    }
    // One channel of both images as planes, a non-finite value in either image zero in both.
    void planes(std::size_t c, std::vector<float>& x, std::vector<float>& y) const {
        x.resize(n);
        y.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const float a = refValue(i, c), b = testValue(i, c);
            const bool ok = std::isfinite(a) && std::isfinite(b);
            x[i] = ok ? a : 0.0f;
            y[i] = ok ? b : 0.0f;
        }
    }
};

bool isColour(const CompareReport& rep, const std::string& name) {
    return std::find(rep.colourChannels.begin(), rep.colourChannels.end(), name) != rep.colourChannels.end();
}

// Per-pixel maps the judgement reads: the largest absolute error over channels (NaN for a
// non-finite mismatch), whether the pixel is such a mismatch, and FLIP when computed.
struct ErrorMaps {
    std::vector<float> abs, flip;
    std::vector<unsigned char> mismatch;
};

// Per-channel sums of one pass over the pixels.
struct ChannelSums {
    double sum = 0.0, sumSq = 0.0;
    std::uint64_t over = 0, finite = 0;
};

// One pixel's channels into the sums; returns whether a non-finite value mismatched, and
// sets `overHere` when a finite error passes the tolerance.
bool accumulatePixel(const ImagePair& p, std::size_t i, CompareReport& rep, std::vector<ChannelSums>& sums,
                     float& pixelMax, bool& overHere) {
    bool bad = false;
    for (std::size_t c = 0; c < p.nc; ++c) {
        const float x = p.refValue(i, c), y = p.testValue(i, c);
        ChannelStats& s = rep.channels[c];
        ChannelSums& sum = sums[c];
        const bool fx = std::isfinite(x), fy = std::isfinite(y);
        if (!fx) ++s.nonFiniteRef;
        if (!fy) ++s.nonFiniteTest;
        if (!fx || !fy) {
            // The same Inf (or NaN in both) matches; anything else is a mismatch.
            if (!((std::isnan(x) && std::isnan(y)) || x == y)) {
                bad = true;
                ++sum.over;
            }
            continue;
        }
        const double e = std::abs(double(y) - double(x));
        sum.sum += e;
        sum.sumSq += e * e;
        ++sum.finite;
        if (e > s.maxAbs) {
            s.maxAbs = e;
            s.maxX = int(i % std::size_t(p.ref.width));
            s.maxY = int(i / std::size_t(p.ref.width));
        }
        if (e > rep.tolerance) {
            ++sum.over;
            overHere = true;
        }
        pixelMax = std::max(pixelMax, float(e));
    }
    return bad;
}

// Absolute errors, MSE and PSNR, shares over the tolerance.
void absolutePass(const ImagePair& p, CompareReport& rep, ErrorMaps& maps) {
    const auto start = std::chrono::steady_clock::now();
    rep.channels.resize(p.nc);
    for (std::size_t c = 0; c < p.nc; ++c) rep.channels[c].name = p.ref.channels[c];
    std::vector<ChannelSums> sums(p.nc);
    maps.abs.assign(p.n, 0.0f);
    maps.mismatch.assign(p.n, 0);
    std::uint64_t overAny = 0;
    for (std::size_t i = 0; i < p.n; ++i) {
        float pixelMax = 0.0f;
        bool overHere = false;
        const bool bad = accumulatePixel(p, i, rep, sums, pixelMax, overHere);
        if (bad) {
            ++rep.nonFiniteMismatch;
            maps.mismatch[i] = 1;
        }
        maps.abs[i] = bad ? std::numeric_limits<float>::quiet_NaN() : pixelMax;
        if (bad || overHere) ++overAny;
    }
    double colourMse = 0.0, sumAll = 0.0;
    std::uint64_t finiteAll = 0;
    for (std::size_t c = 0; c < p.nc; ++c) {
        ChannelStats& s = rep.channels[c];
        const double count = double(std::max<std::uint64_t>(sums[c].finite, 1));
        s.meanAbs = sums[c].sum / count;
        s.mse = sums[c].sumSq / count;
        s.psnr = s.mse > 0.0 ? 10.0 * std::log10(1.0 / s.mse) : kInf;
        s.overShare = double(sums[c].over) / double(p.n);
        s.ssim = std::numeric_limits<double>::quiet_NaN();
        rep.maxAbs = std::max(rep.maxAbs, s.maxAbs);
        sumAll += sums[c].sum;
        finiteAll += sums[c].finite;
        if (isColour(rep, s.name)) colourMse += s.mse / double(rep.colourChannels.size());
    }
    rep.meanAbs = sumAll / double(std::max<std::uint64_t>(finiteAll, 1));
    rep.psnr = colourMse > 0.0 ? 10.0 * std::log10(1.0 / colourMse) : kInf;
    rep.overShare = double(overAny) / double(p.n);
    rep.secondsAbs = secondsSince(start);
}

void ssimPass(const ImagePair& p, CompareReport& rep) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<float> x, y;
    double colourSsim = 0.0;
    for (std::size_t c = 0; c < p.nc; ++c) {
        p.planes(c, x, y);
        ChannelStats& s = rep.channels[c];
        s.ssim = ssimChannel(x.data(), y.data(), p.ref.width, p.ref.height, 1.0);
        if (isColour(rep, s.name)) colourSsim += s.ssim / double(rep.colourChannels.size());
    }
    rep.ssim = colourSsim;
    rep.secondsSsim = secondsSince(start);
}

// Mean, max, median and 95th percentile of a FLIP map.
void flipSummary(const std::vector<float>& map, FlipStats& fs) {
    const std::size_t n = map.size();
    double total = 0.0;
    for (float v : map) {
        total += v;
        fs.max = std::max(fs.max, double(v));
    }
    fs.mean = total / double(n);
    std::vector<float> sorted = map;
    std::sort(sorted.begin(), sorted.end());
    auto pct = [&](double q) {
        const double pos = q * double(n - 1);
        const std::size_t lo = std::size_t(pos);
        const double hi = sorted[std::min(lo + 1, n - 1)];
        return sorted[lo] + (hi - sorted[lo]) * (pos - double(lo));
    };
    fs.median = pct(0.5);
    fs.p95 = pct(0.95);
}

// FLIP over R,G,B (or Y in all three), LDR or HDR as asked; nothing without colour channels.
void flipPass(const ImagePair& p, const CompareOptions& options, CompareReport& rep, ErrorMaps& maps) {
    const bool hasRgb = rep.colourChannels.size() == 3 && rep.colourChannels[0] == "R";
    const bool hasY = rep.colourChannels.size() == 1 && rep.colourChannels[0] == "Y";
    if (options.flip == FlipForm::Off || !(hasRgb || hasY)) return;
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = p.n;
    std::vector<float> r(n * 3), t(n * 3), x, y;
    for (int k = 0; k < 3; ++k) {
        const std::size_t c = std::size_t(p.ref.channelIndex(hasRgb ? rep.colourChannels[std::size_t(k)] : "Y"));
        p.planes(c, x, y);
        for (std::size_t i = 0; i < n; ++i) {
            r[i * 3 + std::size_t(k)] = x[i];
            t[i * 3 + std::size_t(k)] = y[i];
        }
    }
    FlipStats fs;
    fs.pixelsPerDegree = options.pixelsPerDegree;
    const bool srgb = p.ref.encoding == PixelEncoding::Srgb;
    const bool hdr = options.flip == FlipForm::Hdr || (options.flip == FlipForm::Auto && !srgb);
    if (hdr) {
        if (srgb)
            for (std::vector<float>* v : {&r, &t})
                for (float& f : *v) {
                    f = std::clamp(f, 0.0f, 1.0f);
                    f = f <= 0.04045f ? f / 12.92f : std::pow((f + 0.055f) / 1.055f, 2.4f);
                }
        maps.flip = flipHdr(r.data(), t.data(), p.ref.width, p.ref.height, options.pixelsPerDegree, &fs);
    } else {
        maps.flip = flipLdr(r.data(), t.data(), p.ref.width, p.ref.height, srgb, options.pixelsPerDegree);
    }
    flipSummary(maps.flip, fs);
    rep.flip = fs;
    rep.secondsFlip = secondsSince(start);
}

// Whether the judged metric passes `limit` (per-pixel metrics: the share of pixels over
// it against `percent`); the judged value goes to `value`.
bool judge(const CompareReport& rep, const ErrorMaps& maps, double limit, double percent, double& value) {
    const CompareMetric m = rep.thresholds.metric;
    if (perPixel(m)) {
        const std::vector<float>& map = m == CompareMetric::Abs ? maps.abs : maps.flip;
        std::uint64_t failing = 0;
        for (std::size_t i = 0; i < map.size(); ++i) failing += maps.mismatch[i] || map[i] > limit;
        value = double(failing) / double(map.size());
        return value * 100.0 > percent;
    }
    value = m == CompareMetric::Mae    ? rep.meanAbs
            : m == CompareMetric::Psnr ? rep.psnr
            : m == CompareMetric::Ssim ? rep.ssim
                                       : rep.flip->mean;
    return exceeds(m, value, limit);
}

void judgeAndSummarise(CompareReport& rep, const ErrorMaps& maps) {
    const CompareThresholds& th = rep.thresholds;
    const bool failed = judge(rep, maps, th.fail, th.failPercent, rep.judged) || rep.nonFiniteMismatch > 0;
    const bool warned = th.warn && judge(rep, maps, *th.warn, th.warnPercent, rep.judgedWarn);
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
}

} // namespace

Result<CompareReport> compareImages(const CompareImage& ref, const CompareImage& test,
                                    const CompareOptions& options) {
    LANTERN_TRY(checkComparable(ref, test));
    LANTERN_TRY(checkOptions(options));
    const CompareThresholds& th = options.thresholds;
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
    const ImagePair pair(ref, test);
    ErrorMaps maps;
    absolutePass(pair, rep, maps);
    rep.ssim = std::numeric_limits<double>::quiet_NaN();
    if (options.ssim) ssimPass(pair, rep);
    flipPass(pair, options, rep, maps);
    if ((th.metric == CompareMetric::Flip || th.metric == CompareMetric::FlipMean) && !rep.flip)
        return makeError(ErrorCode::InvalidInput,
                         std::string("metric ") + toString(th.metric) + " needs R,G,B or Y channels; " +
                             ref.source + " has " + join(ref.channels),
                         {}, ref.source);
    judgeAndSummarise(rep, maps);
    if (options.keepMaps) {
        rep.absMap = std::move(maps.abs);
        rep.flipMap = std::move(maps.flip);
    }
    return rep;
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
