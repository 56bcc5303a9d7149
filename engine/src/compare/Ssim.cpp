// SSIM (Wang, Bovik, Sheikh, Simoncelli 2004): local means, variances and covariance under an
// 11x11 Gaussian window (sigma 1.5), K1 = 0.01, K2 = 0.03, for a dynamic range L; borders are
// replicated so that every pixel has a value, and the mean over all pixels is returned.
#include "compare/Filters.h"

#include <lantern/Compare.h>

#include <algorithm>
#include <cmath>

namespace lantern {

double ssimChannel(const float* reference, const float* test, int width, int height,
                   double range) {
    using compare::Plane;
    const std::size_t n = std::size_t(width) * std::size_t(height);
    if (n == 0) return 1.0;
    compare::Kernel k(11);
    double sum = 0.0;
    for (int i = -5; i <= 5; ++i) sum += std::exp(-double(i) * i / (2.0 * 1.5 * 1.5));
    for (int i = -5; i <= 5; ++i)
        k[std::size_t(i + 5)] = float(std::exp(-double(i) * i / (2.0 * 1.5 * 1.5)) / sum);
    // Second moments from values centred on each image's mean: variances are shift-invariant,
    // and float sums of x^2 would otherwise cancel (a constant image gets variance 0 exactly).
    double meanX = 0.0, meanY = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        meanX += reference[i];
        meanY += test[i];
    }
    meanX /= double(n);
    meanY /= double(n);
    Plane x(width, height), y(width, height), xx(width, height), yy(width, height), xy(width, height);
    for (std::size_t i = 0; i < n; ++i) {
        const float a = float(reference[i] - meanX), b = float(test[i] - meanY);
        x.v[i] = a;
        y.v[i] = b;
        xx.v[i] = a * a;
        yy.v[i] = b * b;
        xy.v[i] = a * b;
    }
    const Plane mx = compare::filterSeparable(x, k, k), my = compare::filterSeparable(y, k, k);
    const Plane sxx = compare::filterSeparable(xx, k, k), syy = compare::filterSeparable(yy, k, k);
    const Plane sxy = compare::filterSeparable(xy, k, k);
    const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double cx = mx.v[i], cy = my.v[i];  // centred local means
        const double ux = cx + meanX, uy = cy + meanY;
        // Not clamped at 0: identical inputs then give exactly 1 whatever the rounding.
        const double vx = double(sxx.v[i]) - cx * cx;
        const double vy = double(syy.v[i]) - cy * cy;
        const double cxy = double(sxy.v[i]) - cx * cy;
        const double s = ((2.0 * ux * uy + c1) * (2.0 * cxy + c2)) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
        total += std::clamp(s, -1.0, 1.0);  // float filtering can overshoot the bound by ~1e-6
    }
    return total / double(n);
}

} // namespace lantern
