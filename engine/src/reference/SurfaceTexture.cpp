// Texture coordinates on analytic surfaces and nearest-texel sampling for the reference.
#include "reference/SurfaceTexture.h"

#include <algorithm>
#include <cmath>

namespace lantern::ref {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A texel index along one axis of `size` texels at coordinate u, as `wrap` folds it.
int wrapIndex(double u, int size, TextureWrap wrap) {
    const double x = std::floor(u * size);
    const double n = size;
    double i = x;
    switch (wrap) {
    case TextureWrap::Repeat: i = x - n * std::floor(x / n); break;
    case TextureWrap::MirroredRepeat: {
        const double period = x - 2.0 * n * std::floor(x / (2.0 * n));
        i = period < n ? period : 2.0 * n - 1.0 - period;
        break;
    }
    case TextureWrap::ClampToEdge: i = std::clamp(x, 0.0, n - 1.0); break;
    }
    return std::clamp(int(i), 0, size - 1);
}

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

} // namespace

glm::dvec2 analyticUv(const AnalyticShape& shape, const glm::dvec3& p) {
    if (shape.kind == AnalyticKind::Plane) return {p.x / shape.size + 0.5, 0.5 - p.y / shape.size};
    const glm::dvec3 n = p / shape.radius;
    double theta = std::atan2(n.x, n.z);
    if (theta < 0.0) theta += 2.0 * kPi;
    return {theta / (2.0 * kPi), std::acos(std::clamp(n.y, -1.0, 1.0)) / kPi};
}

glm::dvec4 sampleNearest(const Texture& t, const glm::dvec2& uv) {
    if (t.width <= 0 || t.height <= 0) return glm::dvec4(1.0);
    const int x = wrapIndex(uv.x, t.width, t.wrapS), y = wrapIndex(uv.y, t.height, t.wrapT);
    const std::uint8_t* texel = &t.rgba8[(std::size_t(y) * std::size_t(t.width) + std::size_t(x)) * 4];
    glm::dvec4 c(texel[0] / 255.0, texel[1] / 255.0, texel[2] / 255.0, texel[3] / 255.0);
    if (t.srgb)
        for (int k = 0; k < 3; ++k) c[k] = srgbToLinear(c[k]);
    return c;
}

} // namespace lantern::ref
