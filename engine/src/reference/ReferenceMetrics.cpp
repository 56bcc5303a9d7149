// Error metrics of a render against its ray-cast reference: whole image against the box
// image, interior pixels against the centre image (shading alone), silhouette pixels against
// the box image (geometry and aliasing), PSNR, highlight peak ratio and non-finite values.
#include <algorithm>
#include <cmath>
#include <lantern/Reference.h>
#include <limits>
#include <string>

namespace lantern {
namespace {

// Accumulates squared channel errors and per-pixel worst-channel errors of one population.
class Population {
public:
    void add(const float* got, const float* want) {
        double worst = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double e = std::abs(double(got[k]) - double(want[k]));
            m_squares += e * e;
            worst = std::max(worst, e);
        }
        m_worst.push_back(worst);
    }

    ErrorStats stats() {
        ErrorStats s;
        s.pixels = m_worst.size();
        if (s.pixels == 0) return s;
        s.rmse = std::sqrt(m_squares / (3.0 * double(s.pixels)));
        // The 99th percentile by rank (nearest rank, ceil(0.99 n)).
        const std::size_t rank =
            std::min(s.pixels - 1, std::size_t(std::ceil(0.99 * double(s.pixels))) - 1);
        std::nth_element(m_worst.begin(), m_worst.begin() + std::ptrdiff_t(rank), m_worst.end());
        s.p99 = m_worst[rank];
        s.max = *std::max_element(m_worst.begin(), m_worst.end());
        return s;
    }

private:
    double m_squares = 0.0;
    std::vector<double> m_worst;
};

bool sameSize(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgba.size() == b.rgba.size();
}

} // namespace

Result<ErrorMetrics> measureError(const Image& rendered, const ReferenceImage& reference) {
    const Image& box = reference.box;
    const Image& centre = reference.centre;
    if (!sameSize(rendered, box) || !sameSize(rendered, centre) ||
        reference.interior.size() != rendered.pixelCount())
        return makeError(ErrorCode::InvalidInput,
                         "the render is " + std::to_string(rendered.width) + "x" +
                             std::to_string(rendered.height) + " and its reference " +
                             std::to_string(box.width) + "x" + std::to_string(box.height),
                         "measureError");
    ErrorMetrics m;
    for (float v : rendered.rgba)
        if (!std::isfinite(v)) ++m.nonFinite;
    Population whole, interior, silhouette;
    double referencePeak = 0.0, interiorPeakRendered = 0.0, interiorPeakReference = 0.0;
    for (int y = 0; y < rendered.height; ++y)
        for (int x = 0; x < rendered.width; ++x) {
            const float* got = rendered.pixel(x, y);
            const float* wantBox = box.pixel(x, y);
            const float* wantCentre = centre.pixel(x, y);
            whole.add(got, wantBox);
            for (int k = 0; k < 3; ++k)
                referencePeak = std::max(referencePeak, double(wantBox[k]));
            const bool inside = reference.interior[std::size_t(y) * rendered.width + x] != 0;
            if (inside) {
                for (int k = 0; k < 3; ++k) {
                    if (std::isfinite(got[k]))
                        interiorPeakRendered = std::max(interiorPeakRendered, double(got[k]));
                    interiorPeakReference = std::max(interiorPeakReference, double(wantCentre[k]));
                }
            }
            // A render that covers the pixel only partly (MSAA) or not at all (a coarse
            // tessellation inside the exact outline) has a geometry error there, not a
            // shading error.
            if (inside && got[3] >= 1.0f)
                interior.add(got, wantCentre);
            else if (inside || got[3] > 0.0f || wantBox[3] > 0.0f)
                silhouette.add(got, wantBox);
        }
    m.whole = whole.stats();
    m.interior = interior.stats();
    m.silhouette = silhouette.stats();
    m.psnr = m.whole.rmse > 0.0 ? 20.0 * std::log10(referencePeak / m.whole.rmse)
                                : std::numeric_limits<double>::infinity();
    m.peakRatio = interiorPeakReference > 0.0 ? interiorPeakRendered / interiorPeakReference : 0.0;
    return m;
}

} // namespace lantern
