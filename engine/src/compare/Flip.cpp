// FLIP, from the papers: "FLIP: A Difference Evaluator for Alternating Images" (Andersson,
// Nilsson, Akenine-Moller, Oskarsson, Astrom, Fairchild; HPG 2020) for LDR-FLIP, and
// "Visualizing Errors in Rendered High Dynamic Range Images" (Andersson, Nilsson, Shirley,
// Akenine-Moller; Eurographics 2021) for HDR-FLIP.
//
// LDR-FLIP, per pixel:
//   colour: both images to YCxCz (opponent space, D65 white), each channel filtered by its
//     contrast sensitivity function (a sum of Gaussians, in degrees of visual angle), back to
//     linear RGB clamped to [0,1], to L*a*b*, Hunt-adjusted (a, b scaled by L/100); the HyAB
//     distance raised to qc = 0.7 and remapped to [0,1] by the largest such distance (green to
//     blue) with pc = 0.4, pt = 0.95.
//   features: on the luminance Y/Yn, edges (first derivative of a Gaussian) and points (second
//     derivative) whose standard deviation is half of w = 0.082 degrees; the feature difference
//     is (max(|edge difference|, |point difference|) / sqrt 2)^qf with qf = 0.5.
//   FLIP = colour ^ (1 - features).
// HDR-FLIP: the largest LDR-FLIP over exposures from the reference's start exposure (its
// brightest luminance tone-maps to 0.85) to its stop exposure (its median does), the ACES
// fit as tone mapper, max(2, ceil(stop - start)) exposures.
// Every kernel here is separable, so the 2D filters run as row and column passes.
#include "compare/Filters.h"

#include <lantern/Compare.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern {
namespace {

using compare::Kernel;
using compare::Plane;

constexpr double kPi = 3.14159265358979323846;

// Linear sRGB (D65) to CIE XYZ, IEC 61966-2-1.
constexpr double kRgbToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                    {0.2126729, 0.7151522, 0.0721750},
                                    {0.0193339, 0.1191920, 0.9503041}};

struct Colour {
    std::array<std::array<float, 3>, 3> toXyz{}, toRgb{};
    std::array<float, 3> white{};  // XYZ of linear RGB (1, 1, 1)

    Colour() {
        double m[3][3], inv[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m[i][j] = kRgbToXyz[i][j];
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                // inverse = adjugate / det: cofactor of (j, i)
                const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
                inv[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
            }
        for (int i = 0; i < 3; ++i) {
            white[std::size_t(i)] = float(m[i][0] + m[i][1] + m[i][2]);
            for (int j = 0; j < 3; ++j) {
                toXyz[std::size_t(i)][std::size_t(j)] = float(m[i][j]);
                toRgb[std::size_t(i)][std::size_t(j)] = float(inv[i][j]);
            }
        }
    }

    std::array<float, 3> xyz(const float* rgb) const {
        std::array<float, 3> o{};
        for (std::size_t i = 0; i < 3; ++i)
            o[i] = toXyz[i][0] * rgb[0] + toXyz[i][1] * rgb[1] + toXyz[i][2] * rgb[2];
        return o;
    }
    std::array<float, 3> rgb(const std::array<float, 3>& x) const {
        std::array<float, 3> o{};
        for (std::size_t i = 0; i < 3; ++i)
            o[i] = toRgb[i][0] * x[0] + toRgb[i][1] * x[1] + toRgb[i][2] * x[2];
        return o;
    }
    // CIE L*a*b* of linear RGB, relative to `white`; then Hunt-adjusted.
    std::array<float, 3> huntLab(const std::array<float, 3>& linear) const {
        const auto x = xyz(linear.data());
        constexpr float d = 6.0f / 29.0f;
        auto f = [&](float t) {
            return t > d * d * d ? std::cbrt(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
        };
        const float fx = f(x[0] / white[0]), fy = f(x[1] / white[1]), fz = f(x[2] / white[2]);
        const float L = 116.0f * fy - 16.0f;
        return {L, 0.01f * L * 500.0f * (fx - fy), 0.01f * L * 200.0f * (fy - fz)};
    }
};

const Colour& colour() {
    static const Colour c;
    return c;
}

float hyab(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    const float da = a[1] - b[1], db = a[2] - b[2];
    return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

float srgbDecode(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

// The contrast sensitivity filters: per channel, weights and Gaussian kernels (normalised).
struct CsfFilter {
    std::vector<std::pair<float, Kernel>> terms;  // weight, 1D kernel summing to 1
};

std::array<CsfFilter, 3> csfFilters(double ppd) {
    // a1, b1, a2, b2 for the achromatic, red-green and blue-yellow channels.
    const double p[3][4] = {{1.0, 0.0047, 0.0, 1e-5}, {1.0, 0.0053, 0.0, 1e-5},
                            {34.1, 0.04, 13.5, 0.025}};
    double bMax = 0.0;
    for (const auto& c : p) bMax = std::max({bMax, c[1], c[3]});
    const int r = int(std::ceil(3.0 * std::sqrt(bMax / (2.0 * kPi * kPi)) * ppd));
    std::array<CsfFilter, 3> out;
    for (int c = 0; c < 3; ++c) {
        double total = 0.0;
        std::vector<std::pair<double, Kernel>> terms;
        for (int t = 0; t < 2; ++t) {
            const double a = p[c][2 * t], b = p[c][2 * t + 1];
            if (a == 0.0) continue;
            Kernel k(std::size_t(2 * r + 1));
            double sum = 0.0;
            for (int i = -r; i <= r; ++i) {
                const double x = i / ppd;
                const double g = std::exp(-kPi * kPi * x * x / b);
                k[std::size_t(i + r)] = float(g);
                sum += g;
            }
            for (float& v : k) v = float(v / sum);
            // The 2D term a sqrt(pi/b) g(x) g(y) sums to a sqrt(pi/b) sum^2.
            const double mass = a * std::sqrt(kPi / b) * sum * sum;
            total += mass;
            terms.emplace_back(mass, std::move(k));
        }
        for (auto& [mass, k] : terms) out[std::size_t(c)].terms.emplace_back(float(mass / total), std::move(k));
    }
    return out;
}

Plane applyCsf(const Plane& in, const CsfFilter& f) {
    Plane out(in.width, in.height);
    for (const auto& [weight, k] : f.terms) {
        const Plane t = compare::filterSeparable(in, k, k);
        for (std::size_t i = 0; i < out.v.size(); ++i) out.v[i] += weight * t.v[i];
    }
    return out;
}

// The feature kernels: Gaussian g, its first derivative (edges) and second (points), each
// normalised so that its positive weights sum to 1 and its negative ones to -1 in 2D (the
// other axis being g normalised to sum 1).
struct FeatureKernels {
    Kernel gauss, edge, point;
};

FeatureKernels featureKernels(double ppd) {
    const double sd = 0.5 * 0.082 * ppd;
    const int r = int(std::ceil(3.0 * sd));
    FeatureKernels k;
    k.gauss.resize(std::size_t(2 * r + 1));
    k.edge.resize(k.gauss.size());
    k.point.resize(k.gauss.size());
    std::vector<double> g(k.gauss.size()), e(g.size()), p(g.size());
    double gs = 0.0, ePos = 0.0, pPos = 0.0, pNeg = 0.0;
    for (int i = -r; i <= r; ++i) {
        const std::size_t j = std::size_t(i + r);
        g[j] = std::exp(-double(i) * i / (2.0 * sd * sd));
        e[j] = -double(i) * g[j];
        p[j] = (double(i) * i / (sd * sd) - 1.0) * g[j];
        gs += g[j];
        if (e[j] > 0) ePos += e[j];
        (p[j] > 0 ? pPos : pNeg) += std::abs(p[j]);
    }
    for (std::size_t j = 0; j < g.size(); ++j) {
        k.gauss[j] = float(g[j] / gs);
        k.edge[j] = float(e[j] / ePos);  // antisymmetric: the negative sum is the same
        k.point[j] = float(p[j] / (p[j] > 0 ? pPos : pNeg));
    }
    return k;
}

// Edge and point magnitudes of a luminance plane.
std::pair<Plane, Plane> features(const Plane& y, const FeatureKernels& k) {
    const Plane rowsGauss = compare::filterRows(y, k.gauss);
    const Plane ex = compare::filterColumns(compare::filterRows(y, k.edge), k.gauss);
    const Plane ey = compare::filterColumns(rowsGauss, k.edge);
    const Plane px = compare::filterColumns(compare::filterRows(y, k.point), k.gauss);
    const Plane py = compare::filterColumns(rowsGauss, k.point);
    Plane edges(y.width, y.height), points(y.width, y.height);
    for (std::size_t i = 0; i < y.v.size(); ++i) {
        edges.v[i] = std::hypot(ex.v[i], ey.v[i]);
        points.v[i] = std::hypot(px.v[i], py.v[i]);
    }
    return {std::move(edges), std::move(points)};
}

struct Opponent {
    std::array<Plane, 3> ycc;  // Y, Cx, Cz
    Plane luminance;            // Y / Yn
};

Opponent toOpponent(const float* rgb, int w, int h, bool srgb) {
    const Colour& c = colour();
    Opponent o{{Plane(w, h), Plane(w, h), Plane(w, h)}, Plane(w, h)};
    const std::size_t n = std::size_t(w) * std::size_t(h);
    for (std::size_t i = 0; i < n; ++i) {
        float lin[3];
        for (int k = 0; k < 3; ++k) {
            const float v = std::clamp(rgb[i * 3 + std::size_t(k)], 0.0f, 1.0f);
            lin[k] = srgb ? srgbDecode(v) : v;
        }
        const auto x = c.xyz(lin);
        const float xn = x[0] / c.white[0], yn = x[1] / c.white[1], zn = x[2] / c.white[2];
        o.ycc[0].v[i] = 116.0f * yn - 16.0f;
        o.ycc[1].v[i] = 500.0f * (xn - yn);
        o.ycc[2].v[i] = 200.0f * (yn - zn);
        o.luminance.v[i] = yn;
    }
    return o;
}

// Filtered opponent planes -> Hunt-adjusted Lab per pixel.
std::vector<std::array<float, 3>> filteredLab(const Opponent& o,
                                              const std::array<CsfFilter, 3>& csf) {
    const Colour& c = colour();
    std::array<Plane, 3> f;
    for (std::size_t k = 0; k < 3; ++k) f[k] = applyCsf(o.ycc[k], csf[k]);
    std::vector<std::array<float, 3>> lab(f[0].v.size());
    compare::forEachRow(f[0].height, [&](int row) {
        const std::size_t begin = std::size_t(row) * std::size_t(f[0].width);
        for (std::size_t i = begin; i < begin + std::size_t(f[0].width); ++i) {
            const float yn = (f[0].v[i] + 16.0f) / 116.0f;
            const std::array<float, 3> xyz = {(yn + f[1].v[i] / 500.0f) * c.white[0],
                                              yn * c.white[1],
                                              (yn - f[2].v[i] / 200.0f) * c.white[2]};
            std::array<float, 3> rgb = c.rgb(xyz);
            for (float& v : rgb) v = std::clamp(v, 0.0f, 1.0f);
            lab[i] = c.huntLab(rgb);
        }
    });
    return lab;
}

} // namespace

std::vector<float> flipLdr(const float* reference, const float* test, int width, int height,
                           bool srgb, double pixelsPerDegree) {
    constexpr float qc = 0.7f, qf = 0.5f, pc = 0.4f, pt = 0.95f;
    const std::size_t n = std::size_t(width) * std::size_t(height);
    if (n == 0) return {};
    const auto csf = csfFilters(pixelsPerDegree);
    const FeatureKernels fk = featureKernels(pixelsPerDegree);
    const Opponent ro = toOpponent(reference, width, height, srgb);
    const Opponent to = toOpponent(test, width, height, srgb);
    const auto rl = filteredLab(ro, csf), tl = filteredLab(to, csf);
    const auto [re, rp] = features(ro.luminance, fk);
    const auto [te, tp] = features(to.luminance, fk);

    const Colour& c = colour();
    const float green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    const float cmax = std::pow(hyab(c.huntLab({green[0], green[1], green[2]}),
                                     c.huntLab({blue[0], blue[1], blue[2]})),
                                qc);
    const float pccmax = pc * cmax;
    std::vector<float> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float d = std::pow(hyab(rl[i], tl[i]), qc);
        const float colourError =
            d < pccmax ? pt / pccmax * d : pt + (d - pccmax) / (cmax - pccmax) * (1.0f - pt);
        const float fd = std::max(std::abs(re.v[i] - te.v[i]), std::abs(rp.v[i] - tp.v[i]));
        const float featureError = std::pow(fd / std::sqrt(2.0f), qf);
        out[i] = std::pow(std::min(colourError, 1.0f), 1.0f - featureError);
    }
    return out;
}

namespace {

// The ACES fit (Narkowicz) with its 0.6 pre-exposure folded in: (k0 x^2 + k1 x + k2) /
// (k3 x^2 + k4 x + k5).
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

float toneMap(float x) {
    const double n = (kAces[0] * x + kAces[1]) * x + kAces[2];
    const double d = (kAces[3] * x + kAces[4]) * x + kAces[5];
    if (!std::isfinite(d)) return 1.0f;
    return float(std::clamp(n / d, 0.0, 1.0));
}

// The x with toneMap(x) = t.
double inverseToneMap(double t) {
    const double a = kAces[0] - t * kAces[3], b = kAces[1] - t * kAces[4], c = kAces[2] - t * kAces[5];
    return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

// numpy's percentile with linear interpolation.
double percentile(std::vector<float> v, double q) {
    if (v.empty()) return 0.0;
    const double pos = q * double(v.size() - 1);
    const std::size_t lo = std::size_t(std::floor(pos));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(lo), v.end());
    const double a = v[lo];
    if (lo + 1 >= v.size()) return a;
    const double b = *std::min_element(v.begin() + std::ptrdiff_t(lo) + 1, v.end());
    return a + (b - a) * (pos - double(lo));
}

} // namespace

std::vector<float> flipHdr(const float* reference, const float* test, int width, int height,
                           double pixelsPerDegree, FlipStats* stats) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    if (n == 0) return {};
    std::vector<float> lum(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = reference + i * 3;
        lum[i] = std::max(0.0f, 0.2126f * std::max(p[0], 0.0f) + 0.7152f * std::max(p[1], 0.0f) +
                                    0.0722f * std::max(p[2], 0.0f));
    }
    const double xMax = inverseToneMap(0.85);
    const double yMax = *std::max_element(lum.begin(), lum.end());
    double start = 0.0, stop = 0.0;
    if (yMax > 0.0) {
        start = std::log2(xMax / yMax);
        double median = percentile(lum, 0.5);
        if (median <= 0.0) {
            // Mostly black (a render over a transparent background): the paper's stop exposure
            // would be infinite; Lantern takes the median of the lit pixels instead.
            std::vector<float> lit;
            for (float v : lum)
                if (v > 0.0f) lit.push_back(v);
            median = percentile(std::move(lit), 0.5);
        }
        stop = std::log2(xMax / median);
    }
    const int count = std::max(2, int(std::ceil(stop - start)));
    const double step = (stop - start) / double(count - 1);
    std::vector<float> best(n, 0.0f), r(n * 3), t(n * 3);
    for (int e = 0; e < count; ++e) {
        const float scale = float(std::exp2(start + e * step));
        for (std::size_t i = 0; i < n * 3; ++i) {
            r[i] = toneMap(std::max(reference[i], 0.0f) * scale);
            t[i] = toneMap(std::max(test[i], 0.0f) * scale);
        }
        const std::vector<float> ldr = flipLdr(r.data(), t.data(), width, height, false, pixelsPerDegree);
        for (std::size_t i = 0; i < n; ++i) best[i] = std::max(best[i], ldr[i]);
    }
    if (stats) {
        stats->hdr = true;
        stats->startExposure = start;
        stats->stopExposure = stop;
        stats->exposures = count;
    }
    return best;
}

} // namespace lantern
