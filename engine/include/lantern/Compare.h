// Compare: how far a test image is from a reference image, per channel (largest and mean
// absolute error, the share of pixels over a per-pixel tolerance, PSNR, SSIM) and as a whole
// (FLIP, NVIDIA's perceptual difference, in its LDR and HDR forms), judged against thresholds
// in the manner of OpenImageIO's idiff. Device-free: no Vulkan, no renderer needed.
// docs/testing-with-lantern.md shows it in CI; `lantern compare` is its command.
#pragma once

#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Result.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern {

/// How a CompareImage's values are encoded.
enum class PixelEncoding {
    Linear,  ///< linear light, any range (EXR); FLIP uses its HDR form
    Srgb,    ///< sRGB-encoded display values in [0, 1] (PNG); FLIP uses its LDR form
};

/// A picture as read for comparison: the channels a file holds, by name, interleaved.
struct CompareImage {
    int width = 0;
    int height = 0;
    /// Channel names as in the file: R, G, B, A first when present (PNG: R,G,B[,A] or Y[,A]),
    /// then any other EXR channels (Z, N.X, ...) in the file's order.
    std::vector<std::string> channels;
    /// width * height * channels.size() floats, top row first, pixel by pixel. May hold NaN
    /// or Inf as read (they are counted, never a crash).
    std::vector<float> values;
    PixelEncoding encoding = PixelEncoding::Linear;
    std::string source;  ///< the file (or "render") named in messages

    std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }
    int channelIndex(std::string_view name) const {  ///< -1 when absent
        for (std::size_t i = 0; i < channels.size(); ++i)
            if (channels[i] == name) return int(i);
        return -1;
    }
};

// Reading images from files for comparison (readCompareImage, toCompareImage, compareFiles)
// is in lantern/Io.h.


/// The value the thresholds judge.
enum class CompareMetric {
    Abs,       ///< per pixel: the largest absolute error over its channels (idiff's)
    Flip,      ///< per pixel: the FLIP value in [0, 1]
    Mae,       ///< whole image: mean absolute error over every channel
    Psnr,      ///< whole image: PSNR of the colour channels, in dB (fails when BELOW --fail)
    Ssim,      ///< whole image: mean SSIM of the colour channels (fails when BELOW --fail)
    FlipMean,  ///< whole image: mean FLIP
};

LANTERN_API const char* toString(CompareMetric metric) noexcept;  ///< "abs", "flip", "flip-mean"...
LANTERN_API std::optional<CompareMetric> parseCompareMetric(std::string_view text) noexcept;

/// idiff's thresholds. For a per-pixel metric (abs, flip) a pixel fails when its value exceeds
/// `fail`, and the comparison fails when more than `failPercent` percent of the pixels fail;
/// warn likewise. For a whole-image metric the value is compared with `fail` / `warn`
/// directly (percentages unused): mae and flip-mean fail above it, psnr and ssim below it.
struct CompareThresholds {
    CompareMetric metric = CompareMetric::Abs;
    double fail = 1e-6;
    double failPercent = 0.0;
    std::optional<double> warn;  ///< no warning unless set
    double warnPercent = 0.0;
};

enum class FlipForm {
    Auto,  ///< LDR for Srgb images, HDR for Linear ones
    Ldr,   ///< LDR-FLIP (a Linear image is clamped to [0, 1] as linear values)
    Hdr,   ///< HDR-FLIP (an Srgb image is decoded to linear first)
    Off,   ///< not computed
};

struct CompareOptions {
    CompareThresholds thresholds;
    /// Per-channel tolerance for the share of pixels over it (overShare). A negative value
    /// means "the fail threshold" when the metric is abs, otherwise 1e-6.
    double pixelTolerance = -1.0;
    bool ssim = true;  ///< compute SSIM (11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03, L 1)
    FlipForm flip = FlipForm::Auto;
    /// Observer's pixels per degree: FLIP's default, a 0.7 m wide 3840-pixel screen at 0.7 m.
    double pixelsPerDegree = 0.7 * 3840.0 / 0.7 * 3.14159265358979323846 / 180.0;
    /// Keep the per-pixel error maps in the report (needed by compareHeatMap).
    bool keepMaps = false;
};

struct ChannelStats {
    std::string name;
    double maxAbs = 0.0;   ///< largest |test - ref| over finite pairs
    int maxX = -1, maxY = -1;  ///< where it is (-1: nowhere, identical)
    double meanAbs = 0.0;  ///< mean |test - ref| over finite pairs
    double mse = 0.0;
    double psnr = 0.0;     ///< 10 log10(1 / mse), +inf when identical (peak value 1)
    double ssim = 1.0;     ///< NaN when not computed
    double overShare = 0.0;      ///< share (0..1) of pixels whose |error| > tolerance
    std::uint64_t nonFiniteRef = 0, nonFiniteTest = 0;  ///< NaN/Inf values in each image
};

struct FlipStats {
    bool hdr = false;
    double mean = 0.0, max = 0.0;
    double median = 0.0, p95 = 0.0;  ///< weighted percentiles of the per-pixel map
    double startExposure = 0.0, stopExposure = 0.0;  ///< HDR only (stops)
    int exposures = 0;                                 ///< HDR only
    double pixelsPerDegree = 0.0;
};

enum class CompareStatus { Pass, Warn, Fail };
LANTERN_API const char* toString(CompareStatus status) noexcept;  ///< "pass", "warn", "fail"

struct CompareReport {
    std::string reference, test;  ///< sources
    int width = 0, height = 0;
    PixelEncoding encoding = PixelEncoding::Linear;
    std::vector<ChannelStats> channels;
    std::vector<std::string> colourChannels;  ///< those PSNR and SSIM summarise (R,G,B or Y)
    // Whole-image values.
    double maxAbs = 0.0, meanAbs = 0.0;
    double psnr = 0.0;  ///< over the colour channels; +inf when identical
    double ssim = 1.0;  ///< mean over the colour channels; NaN when not computed
    double overShare = 0.0;  ///< share of pixels with any channel over the tolerance
    double tolerance = 0.0;  ///< the per-pixel tolerance used for overShare
    /// Pixels where one image holds NaN/Inf and the other a different value: they count as
    /// failing pixels, are left out of every statistic, and fail the comparison.
    std::uint64_t nonFiniteMismatch = 0;
    std::optional<FlipStats> flip;  ///< absent when off or without colour channels

    CompareThresholds thresholds;
    double judged = 0.0;       ///< the value judged: a share of pixels (0..1) or the metric
    double judgedWarn = 0.0;   ///< the same for the warn threshold
    CompareStatus status = CompareStatus::Pass;
    std::string summary;  ///< one line: what was judged against what, and the outcome

    /// Seconds spent: reading is the caller's; "abs" (max, mean, PSNR, share), "ssim", "flip".
    double secondsAbs = 0.0, secondsSsim = 0.0, secondsFlip = 0.0;

    /// With keepMaps: per pixel, the largest absolute error over channels (NaN: non-finite
    /// mismatch), and the FLIP value (when computed).
    std::vector<float> absMap, flipMap;
};

/// Compares two images. Different sizes, channel sets or encodings are an InvalidInput error
/// naming both files and what differs; NaN and Inf are counted, never a crash.
LANTERN_API Result<CompareReport> compareImages(const CompareImage& reference,
                                                const CompareImage& test,
                                                const CompareOptions& options = {});


/// A heat map of the judged metric (needs keepMaps): FLIP values, or for the other metrics
/// the per-pixel absolute error divided by the largest one, through a black-red-yellow-white
/// ramp (magenta: a NaN/Inf mismatch). Linear RGBA, ready for writeImage. Empty image when the
/// report holds no map.
LANTERN_API Image compareHeatMap(const CompareReport& report);

/// The report as JSON (infinite PSNR is written as null with "identical": true).
LANTERN_API std::string compareReportJson(const CompareReport& report);

// --- The metrics alone, for one channel or one RGB image (also used by the tests) ----------

/// Mean SSIM of two single-channel width x height images (values per pixel), Gaussian window
/// 11x11 sigma 1.5, replicated borders, dynamic range `range`.
LANTERN_API double ssimChannel(const float* reference, const float* test, int width, int height,
                               double range = 1.0);

/// Per-pixel LDR-FLIP of two RGB images (3 floats per pixel). `srgb`: the values are sRGB
/// encoded (the paper's input); otherwise they are linear and clamped to [0, 1].
LANTERN_API std::vector<float> flipLdr(const float* reference, const float* test, int width,
                                       int height, bool srgb, double pixelsPerDegree);

/// Per-pixel HDR-FLIP of two linear RGB images: LDR-FLIP over the exposure range the reference
/// gives (ACES tone mapper), the largest value per pixel. Fills the exposures used.
LANTERN_API std::vector<float> flipHdr(const float* reference, const float* test, int width,
                                       int height, double pixelsPerDegree,
                                       FlipStats* exposures = nullptr);

} // namespace lantern
