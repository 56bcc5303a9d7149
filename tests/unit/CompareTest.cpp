// lantern/Compare.h on constructed images whose answers are known: identical images, constant
// offsets, constant colours whose FLIP follows from the paper's formulas alone, HDR exposure
// ranges, NaN, mismatched sizes and channels, idiff's thresholds, the heat map and the JSON.
#include "TestSupport.h"

#include <lantern/Compare.h>
#include <lantern/Io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>

namespace {

using namespace lantern;

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

CompareImage makeImage(int w, int h, std::vector<std::string> channels, PixelEncoding e,
                       const std::string& name) {
    CompareImage i;
    i.width = w;
    i.height = h;
    i.channels = std::move(channels);
    i.values.assign(std::size_t(w) * std::size_t(h) * i.channels.size(), 0.0f);
    i.encoding = e;
    i.source = name;
    return i;
}

// Smooth shapes plus noise, values in [lo, hi].
CompareImage textured(int w, int h, PixelEncoding e, float lo = 0.1f, float hi = 0.9f,
                      std::vector<std::string> channels = {"R", "G", "B", "A"}) {
    CompareImage i = makeImage(w, h, std::move(channels), e, "ref");
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> noise(-0.05f, 0.05f);
    const std::size_t nc = i.channels.size();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (std::size_t c = 0; c < nc; ++c) {
                float v = 0.5f + 0.35f * std::sin(0.2f * float(x) + float(c)) * std::cos(0.13f * float(y));
                v = std::clamp(v + noise(rng), 0.0f, 1.0f);
                i.values[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * nc + c] = lo + (hi - lo) * v;
            }
    return i;
}

CompareImage constant(int w, int h, std::vector<float> rgb, PixelEncoding e, const std::string& name) {
    CompareImage i = makeImage(w, h, {"R", "G", "B"}, e, name);
    for (std::size_t p = 0; p < i.pixelCount(); ++p)
        for (std::size_t c = 0; c < 3; ++c) i.values[p * 3 + c] = rgb[c];
    return i;
}

TEST(Compare, IdenticalImagesHaveNoErrorInEveryMetric) {
    for (PixelEncoding e : {PixelEncoding::Linear, PixelEncoding::Srgb}) {
        const CompareImage a = textured(48, 40, e);
        CompareImage b = a;
        b.source = "test";
        auto r = compareImages(a, b);
        ASSERT_TRUE(r) << r.error().describe();
        EXPECT_EQ(r->maxAbs, 0.0);
        EXPECT_EQ(r->meanAbs, 0.0);
        EXPECT_TRUE(std::isinf(r->psnr) && r->psnr > 0);
        EXPECT_EQ(r->ssim, 1.0);
        for (const ChannelStats& c : r->channels) {
            EXPECT_EQ(c.ssim, 1.0) << c.name;
            EXPECT_TRUE(std::isinf(c.psnr)) << c.name;
            EXPECT_EQ(c.maxX, -1);
        }
        ASSERT_TRUE(r->flip);
        EXPECT_EQ(r->flip->hdr, e == PixelEncoding::Linear);
        EXPECT_EQ(r->flip->max, 0.0);
        EXPECT_EQ(r->status, CompareStatus::Pass);
        EXPECT_EQ(r->colourChannels, (std::vector<std::string>{"R", "G", "B"}));
    }
}

TEST(Compare, AConstantOffsetHasTheKnownErrorAndPsnr) {
    const CompareImage a = textured(40, 30, PixelEncoding::Linear);
    CompareImage b = a;
    for (float& v : b.values) v += 0.01f;
    CompareOptions o;
    o.pixelTolerance = 0.005;
    auto r = compareImages(a, b, o);
    ASSERT_TRUE(r);
    for (const ChannelStats& c : r->channels) {
        EXPECT_NEAR(c.maxAbs, 0.01, 1e-6) << c.name;
        EXPECT_NEAR(c.meanAbs, 0.01, 1e-6) << c.name;
        EXPECT_NEAR(c.psnr, 40.0, 1e-3) << c.name;  // 10 log10(1 / 0.01^2)
        EXPECT_EQ(c.overShare, 1.0);
    }
    EXPECT_NEAR(r->psnr, 40.0, 1e-3);
    EXPECT_EQ(r->overShare, 1.0);
    EXPECT_EQ(r->status, CompareStatus::Fail);  // idiff's default: any pixel over 1e-6
    o.pixelTolerance = 0.02;
    r = compareImages(a, b, o);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->overShare, 0.0);
    // SSIM sees a small luminance shift: below 1, far above 0.9.
    EXPECT_LT(r->ssim, 1.0);
    EXPECT_GT(r->ssim, 0.99);
}

TEST(Compare, SsimOfConstantImagesIsTheLuminanceTerm) {
    const float a = 0.3f, b = 0.5f;
    std::vector<float> x(32 * 32, a), y(32 * 32, b);
    const double c1 = 0.01 * 0.01;
    const double expected = (2.0 * a * b + c1) / (double(a) * a + double(b) * b + c1);
    EXPECT_NEAR(ssimChannel(x.data(), y.data(), 32, 32), expected, 1e-6);
    // A pattern against its negative: structure anti-correlated, SSIM below 0.
    const CompareImage t = textured(32, 32, PixelEncoding::Linear, 0.0f, 1.0f, {"Y"});
    std::vector<float> inv(t.values.size());
    for (std::size_t i = 0; i < inv.size(); ++i) inv[i] = 1.0f - t.values[i];
    EXPECT_LT(ssimChannel(t.values.data(), inv.data(), 32, 32), 0.0);
}

// CIE L*a*b* relative to the white of linear sRGB, Hunt-adjusted: written here from the
// definitions, independently of the engine's code.
std::array<double, 3> huntLab(double r, double g, double b) {
    const double m[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                            {0.2126729, 0.7151522, 0.0721750},
                            {0.0193339, 0.1191920, 0.9503041}};
    double f[3];
    for (int i = 0; i < 3; ++i) {
        const double t = (m[i][0] * r + m[i][1] * g + m[i][2] * b) / (m[i][0] + m[i][1] + m[i][2]);
        f[i] = t > std::pow(6.0 / 29.0, 3) ? std::cbrt(t) : t / (3.0 * std::pow(6.0 / 29.0, 2)) + 4.0 / 29.0;
    }
    const double L = 116.0 * f[1] - 16.0;
    return {L, L / 100.0 * 500.0 * (f[0] - f[1]), L / 100.0 * 200.0 * (f[1] - f[2])};
}

double hyab(const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// The paper's colour remapping for a uniform pair (no features: the feature term is 0).
double expectedFlip(const std::array<double, 3>& p, const std::array<double, 3>& q) {
    const double cmax = std::pow(hyab(huntLab(0, 1, 0), huntLab(0, 0, 1)), 0.7);
    const double d = std::pow(hyab(p, q), 0.7);
    return d < 0.4 * cmax ? 0.95 / (0.4 * cmax) * d : 0.95 + (d - 0.4 * cmax) / (0.6 * cmax) * 0.05;
}

TEST(Compare, FlipOfUniformColoursFollowsThePaperFormulas) {
    const double ppd = CompareOptions{}.pixelsPerDegree;
    EXPECT_NEAR(ppd, 67.0206, 1e-3);  // the paper's default observer
    struct Case {
        std::vector<float> a, b;
    };
    // Green against blue is the largest colour difference: FLIP 1 by construction.
    const CompareImage g = constant(24, 24, {0, 1, 0}, PixelEncoding::Srgb, "g");
    const CompareImage bl = constant(24, 24, {0, 0, 1}, PixelEncoding::Srgb, "b");
    for (float v : flipLdr(g.values.data(), bl.values.data(), 24, 24, true, ppd)) ASSERT_NEAR(v, 1.0f, 1e-4f);
    // Black against white: HyAB = 100 (L 0 to 100).
    const CompareImage k = constant(24, 24, {0, 0, 0}, PixelEncoding::Srgb, "k");
    const CompareImage w = constant(24, 24, {1, 1, 1}, PixelEncoding::Srgb, "w");
    const double bw = expectedFlip(huntLab(0, 0, 0), huntLab(1, 1, 1));
    EXPECT_GT(bw, 0.95);
    EXPECT_LT(bw, 1.0);
    for (float v : flipLdr(k.values.data(), w.values.data(), 24, 24, true, ppd)) ASSERT_NEAR(v, bw, 1e-4);
    // Two greys, sRGB 0.5 and 0.6 (decoded to linear first), below p_c * c_max.
    const CompareImage g5 = constant(24, 24, {0.5f, 0.5f, 0.5f}, PixelEncoding::Srgb, "g5");
    const CompareImage g6 = constant(24, 24, {0.6f, 0.6f, 0.6f}, PixelEncoding::Srgb, "g6");
    auto lin = [](double s) { return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4); };
    const double gg = expectedFlip(huntLab(lin(0.5), lin(0.5), lin(0.5)), huntLab(lin(0.6), lin(0.6), lin(0.6)));
    EXPECT_LT(gg, 0.95);
    for (float v : flipLdr(g5.values.data(), g6.values.data(), 24, 24, true, ppd)) ASSERT_NEAR(v, gg, 1e-4);
    // Linear input (srgb false) skips the decoding.
    const double gl = expectedFlip(huntLab(0.5, 0.5, 0.5), huntLab(0.6, 0.6, 0.6));
    for (float v : flipLdr(g5.values.data(), g6.values.data(), 24, 24, false, ppd)) ASSERT_NEAR(v, gl, 1e-4);
    EXPECT_NE(gg, gl);
}

TEST(Compare, FlipSeesAnEdgeOnlyWhereItDiffers) {
    // A thin bright line in the test only: FLIP is high on the line, 0 far from it (beyond
    // the filters' reach), and the feature term raises it above the colour term alone.
    const int w = 64, h = 32;
    CompareImage a = constant(w, h, {0.2f, 0.2f, 0.2f}, PixelEncoding::Srgb, "a");
    CompareImage b = a;
    for (int y = 0; y < h; ++y)
        for (int c = 0; c < 3; ++c) b.values[(std::size_t(y) * w + 10) * 3 + std::size_t(c)] = 0.9f;
    const auto f = flipLdr(a.values.data(), b.values.data(), w, h, true, CompareOptions{}.pixelsPerDegree);
    EXPECT_GT(f[std::size_t(16) * w + 10], 0.3f);
    EXPECT_EQ(f[std::size_t(16) * w + 50], 0.0f);
    EXPECT_GT(f[std::size_t(16) * w + 12], 0.0f);  // the filters spread the line
}

// The x that ACES (with FLIP's 0.6 pre-exposure) maps to t, found by bisection.
double acesInverse(double t) {
    auto aces = [](double x) {
        x *= 0.6;
        return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    };
    double lo = 0.0, hi = 100.0;
    for (int i = 0; i < 200; ++i) (aces(0.5 * (lo + hi)) < t ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
}

TEST(Compare, HdrFlipExposureRangeFollowsTheReference) {
    const double xMax = acesInverse(0.85);
    // Uniform luminance 2: start = stop = log2(xMax / 2), two exposures.
    const CompareImage a = constant(16, 16, {2, 2, 2}, PixelEncoding::Linear, "a");
    FlipStats s;
    const auto same = flipHdr(a.values.data(), a.values.data(), 16, 16, 67.0, &s);
    EXPECT_NEAR(s.startExposure, std::log2(xMax / 2.0), 1e-6);
    EXPECT_NEAR(s.stopExposure, s.startExposure, 1e-9);
    EXPECT_EQ(s.exposures, 2);
    for (float v : same) ASSERT_EQ(v, 0.0f);
    // Half the pixels at 8, half at 0.5: median 4.25 (numpy's interpolation), max 8.
    CompareImage b = a;
    for (std::size_t p = 0; p < b.pixelCount(); ++p)
        for (std::size_t c = 0; c < 3; ++c) b.values[p * 3 + c] = p % 2 ? 8.0f : 0.5f;
    flipHdr(b.values.data(), b.values.data(), 16, 16, 67.0, &s);
    EXPECT_NEAR(s.startExposure, std::log2(xMax / 8.0), 1e-6);
    EXPECT_NEAR(s.stopExposure, std::log2(xMax / 4.25), 1e-6);
    EXPECT_EQ(s.exposures, 2);
    // Mostly black (a transparent background): the median of the lit pixels stands in.
    CompareImage c = constant(16, 16, {0, 0, 0}, PixelEncoding::Linear, "c");
    for (std::size_t p = 0; p < 10; ++p)
        for (std::size_t k = 0; k < 3; ++k) c.values[p * 3 + k] = p < 5 ? 1.0f : 64.0f;
    flipHdr(c.values.data(), c.values.data(), 16, 16, 67.0, &s);
    EXPECT_NEAR(s.startExposure, std::log2(xMax / 64.0), 1e-6);
    EXPECT_NEAR(s.stopExposure, std::log2(xMax / 32.5), 1e-6);
    EXPECT_TRUE(std::isfinite(s.stopExposure));
    // An HDR difference shows: 2 against 3.
    const CompareImage d = constant(16, 16, {3, 3, 3}, PixelEncoding::Linear, "d");
    const auto diff = flipHdr(a.values.data(), d.values.data(), 16, 16, 67.0, &s);
    EXPECT_GT(diff[0], 0.05f);
}

TEST(Compare, DifferentSizesChannelsOrEncodingsAreClearErrors) {
    const CompareImage a = textured(16, 16, PixelEncoding::Linear);
    CompareImage b = textured(16, 12, PixelEncoding::Linear);
    b.source = "small.exr";
    auto r = compareImages(a, b);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::InvalidInput);
    EXPECT_NE(r.error().message.find("16x16"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("16x12"), std::string::npos);
    EXPECT_NE(r.error().message.find("small.exr"), std::string::npos);
    const CompareImage c = textured(16, 16, PixelEncoding::Linear, 0.1f, 0.9f, {"R", "G", "B"});
    r = compareImages(a, c);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("R,G,B,A"), std::string::npos) << r.error().message;
    const CompareImage d = textured(16, 16, PixelEncoding::Srgb);
    r = compareImages(a, d);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("encodings differ"), std::string::npos) << r.error().message;
    // Channel order does not matter: they are matched by name.
    CompareImage e = makeImage(16, 16, {"A", "B", "G", "R"}, PixelEncoding::Linear, "e");
    for (std::size_t p = 0; p < e.pixelCount(); ++p)
        for (std::size_t k = 0; k < 4; ++k) e.values[p * 4 + k] = a.values[p * 4 + 3 - k];
    r = compareImages(a, e);
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_EQ(r->maxAbs, 0.0);
}

TEST(Compare, NanAndInfAreCountedNeverACrash) {
    CompareImage a = textured(20, 20, PixelEncoding::Linear, 0.1f, 0.9f, {"R", "G", "B", "Z"});
    for (std::size_t p = 0; p < 20; ++p) a.values[p * 4 + 3] = kInf;  // depth: nothing there
    CompareImage b = a;
    // The same Inf and NaN in both images match.
    a.values[100 * 4] = kNan;
    b.values[100 * 4] = kNan;
    auto r = compareImages(a, b);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, CompareStatus::Pass) << r->summary;
    EXPECT_EQ(r->nonFiniteMismatch, 0u);
    EXPECT_EQ(r->channels[3].nonFiniteRef, 20u);
    // NaN in the test only, at three pixels: counted, failing, left out of the statistics.
    for (std::size_t p : {5, 77, 300}) b.values[p * 4 + 1] = kNan;
    b.values[200 * 4 + 2] = kInf;
    r = compareImages(a, b);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->nonFiniteMismatch, 4u);
    EXPECT_EQ(r->channels[1].nonFiniteTest, 3u);
    EXPECT_EQ(r->status, CompareStatus::Fail);
    EXPECT_NE(r->summary.find("NaN or Inf"), std::string::npos);
    EXPECT_EQ(r->maxAbs, 0.0);  // every finite pair is equal
    EXPECT_TRUE(std::isfinite(r->ssim));
    ASSERT_TRUE(!r->flip || std::isfinite(r->flip->mean));
    EXPECT_NEAR(r->overShare, 4.0 / 400.0, 1e-12);
}

TEST(Compare, ThresholdsFollowIdiff) {
    const CompareImage a = textured(50, 40, PixelEncoding::Linear);
    CompareImage b = a;
    // 20 of 2000 pixels (1%) off by 0.1 in R.
    for (std::size_t p = 0; p < 20; ++p) b.values[p * 97 * 4] += 0.1f;
    CompareOptions o;
    o.flip = FlipForm::Off;
    o.thresholds.fail = 0.05;
    o.thresholds.failPercent = 0.5;
    auto r = compareImages(a, b, o);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, CompareStatus::Fail);
    EXPECT_NEAR(r->judged, 0.01, 1e-12);
    o.thresholds.failPercent = 2.0;
    r = compareImages(a, b, o);
    EXPECT_EQ(r->status, CompareStatus::Pass) << r->summary;
    o.thresholds.warn = 0.05;
    o.thresholds.warnPercent = 0.5;
    r = compareImages(a, b, o);
    EXPECT_EQ(r->status, CompareStatus::Warn) << r->summary;
    o.thresholds.fail = 0.2;  // nothing exceeds 0.2
    o.thresholds.failPercent = 0.0;
    o.thresholds.warn.reset();
    r = compareImages(a, b, o);
    EXPECT_EQ(r->status, CompareStatus::Pass);
    // Whole-image metrics: PSNR must reach --fail, MAE must stay under it.
    o.thresholds.metric = CompareMetric::Psnr;
    o.thresholds.fail = r->psnr - 1.0;
    EXPECT_EQ(compareImages(a, b, o)->status, CompareStatus::Pass);
    o.thresholds.fail = r->psnr + 1.0;
    EXPECT_EQ(compareImages(a, b, o)->status, CompareStatus::Fail);
    o.thresholds.metric = CompareMetric::Mae;
    o.thresholds.fail = r->meanAbs * 1.01;
    EXPECT_EQ(compareImages(a, b, o)->status, CompareStatus::Pass);
    o.thresholds.fail = r->meanAbs * 0.99;
    EXPECT_EQ(compareImages(a, b, o)->status, CompareStatus::Fail);
    o.thresholds.metric = CompareMetric::Ssim;
    o.thresholds.fail = 1.0;
    EXPECT_EQ(compareImages(a, b, o)->status, CompareStatus::Fail);
    // FLIP needs FLIP.
    o.thresholds.metric = CompareMetric::FlipMean;
    auto off = compareImages(a, b, o);
    ASSERT_FALSE(off);
    EXPECT_EQ(off.error().code, ErrorCode::Usage);
    o.flip = FlipForm::Auto;
    o.thresholds.fail = 0.5;
    EXPECT_EQ(compareImages(a, b, o)->status, CompareStatus::Pass);
    EXPECT_EQ(parseCompareMetric("flip-mean"), CompareMetric::FlipMean);
    EXPECT_FALSE(parseCompareMetric("rmse"));
}

TEST(Compare, HeatMapAndJsonDescribeTheDifference) {
    const CompareImage a = textured(30, 20, PixelEncoding::Linear);
    CompareImage b = a;
    b.values[(5 * 30 + 7) * 4 + 2] += 0.5f;  // the largest error, at (7, 5)
    b.values[(10 * 30 + 20) * 4 + 0] += 0.25f;
    b.values[(15 * 30 + 3) * 4 + 1] = kNan;
    CompareOptions o;
    o.keepMaps = true;
    auto r = compareImages(a, b, o);
    ASSERT_TRUE(r);
    const Image heat = compareHeatMap(*r);
    ASSERT_EQ(heat.width, 30);
    ASSERT_EQ(heat.height, 20);
    EXPECT_EQ(heat.pixel(7, 5)[0], 1.0f);  // largest: white
    EXPECT_EQ(heat.pixel(7, 5)[2], 1.0f);
    EXPECT_EQ(heat.pixel(0, 0)[0], 0.0f);  // no error: black
    EXPECT_GT(heat.pixel(20, 10)[0], 0.5f);  // half the largest: red-yellow
    EXPECT_LT(heat.pixel(20, 10)[2], 0.1f);
    EXPECT_EQ(heat.pixel(3, 15)[1], 0.0f);  // NaN mismatch: magenta
    EXPECT_EQ(heat.pixel(3, 15)[2], 1.0f);
    const auto j = nlohmann::json::parse(compareReportJson(*r));
    EXPECT_EQ(j["status"], "fail");
    EXPECT_NEAR(j["max_abs"].get<double>(), r->maxAbs, 1e-12);
    EXPECT_EQ(j["channels"][2]["name"], "B");
    EXPECT_EQ(j["channels"][2]["max_at"][0], 7);
    EXPECT_EQ(j["channels"][2]["max_at"][1], 5);
    EXPECT_EQ(j["non_finite_mismatch"], 1);
    EXPECT_EQ(j["flip"]["form"], "hdr");
    // Identical: PSNR infinite is null, with identical true.
    const auto same = nlohmann::json::parse(compareReportJson(*compareImages(a, a)));
    EXPECT_TRUE(same["psnr"].is_null());
    EXPECT_EQ(same["identical"], true);
    EXPECT_EQ(same["status"], "pass");
}

TEST(Compare, ReadsWhatTheWritersWroteAndQuantisesRendersLikeThePngWriter) {
    Image img(12, 8);
    for (std::size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = float(i % 17) / 16.0f * 0.7f;
    for (std::size_t p = 0; p < img.pixelCount(); ++p) img.rgba[p * 4 + 3] = p % 3 ? 1.0f : 0.5f;
    img.depth.assign(img.pixelCount(), 3.0f);
    const auto dir = test::testOutputDir();
    ASSERT_TRUE(writeExr(dir / "cmp.exr", img));
    ASSERT_TRUE(writePng(dir / "cmp.png", img));
    auto exr = readCompareImage(dir / "cmp.exr");
    ASSERT_TRUE(exr) << exr.error().describe();
    EXPECT_EQ(exr->channels, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
    EXPECT_EQ(exr->encoding, PixelEncoding::Linear);
    auto r = compareImages(*exr, toCompareImage(img, PixelEncoding::Linear));
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_EQ(r->maxAbs, 0.0);
    auto png = readCompareImage(dir / "cmp.png");
    ASSERT_TRUE(png) << png.error().describe();
    EXPECT_EQ(png->encoding, PixelEncoding::Srgb);
    EXPECT_EQ(png->channels, (std::vector<std::string>{"R", "G", "B", "A"}));
    r = compareImages(*png, toCompareImage(img, PixelEncoding::Srgb));
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_EQ(r->maxAbs, 0.0);
    // Not an image, and a missing file: InvalidInput naming the file.
    std::ofstream(dir / "junk.png") << "not a png";
    auto junk = readCompareImage(dir / "junk.png");
    ASSERT_FALSE(junk);
    EXPECT_EQ(junk.error().code, ErrorCode::InvalidInput);
    EXPECT_NE(junk.error().file.find("junk.png"), std::string::npos);
    auto missing = readCompareImage(dir / "missing.exr");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidInput);
    auto tiff = readCompareImage(dir / "cmp.exr.tif");
    ASSERT_FALSE(tiff);
}

} // namespace
