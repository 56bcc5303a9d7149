// Keyframe sampling as glTF 2.0 defines it: STEP, LINEAR (shortest-arc slerp for rotations)
// and CUBICSPLINE (Hermite with in/out tangents), clamped outside the key range.
#include <lantern/Scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern {
namespace {

glm::dvec4 normalizeQuat(const glm::dvec4& q) {
    const double len = glm::length(q);
    return len > 0.0 ? q / len : glm::dvec4(0, 0, 0, 1);
}

// Spherical interpolation along the shorter arc between unit quaternions stored as (x,y,z,w).
glm::dvec4 slerpShortest(glm::dvec4 a, glm::dvec4 b, double s) {
    double d = glm::dot(a, b);
    if (d < 0.0) {
        b = -b;
        d = -d;
    }
    if (d > 0.9995) return normalizeQuat(a + s * (b - a));  // nearly parallel: lerp is exact enough
    const double theta = std::acos(std::min(d, 1.0));
    const double sinTheta = std::sin(theta);
    return (std::sin((1.0 - s) * theta) / sinTheta) * a + (std::sin(s * theta) / sinTheta) * b;
}

} // namespace

glm::dvec4 sampleAnimation(const AnimationSampler& sampler, AnimationPath path, double time) {
    const auto& times = sampler.times;
    const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
    const std::size_t stride = cubic ? 3 : 1;
    auto value = [&](std::size_t k) { return sampler.values[k * stride + (cubic ? 1 : 0)]; };
    const bool rotation = path == AnimationPath::Rotation;
    auto finish = [&](const glm::dvec4& v) { return rotation ? normalizeQuat(v) : v; };

    if (times.empty()) return rotation ? glm::dvec4(0, 0, 0, 1) : glm::dvec4(0);
    if (!(time > times.front())) return finish(value(0));
    if (time >= times.back()) return finish(value(times.size() - 1));

    // The key interval [k, k+1] containing time.
    const std::size_t k1 = std::size_t(std::upper_bound(times.begin(), times.end(), time) -
                                       times.begin());
    const std::size_t k0 = k1 - 1;
    const double t0 = times[k0], t1 = times[k1], dt = t1 - t0;
    const double s = (time - t0) / dt;

    switch (sampler.interpolation) {
    case Interpolation::Step: return finish(value(k0));
    case Interpolation::Linear:
        if (rotation) return slerpShortest(normalizeQuat(value(k0)), normalizeQuat(value(k1)), s);
        return value(k0) + s * (value(k1) - value(k0));
    case Interpolation::CubicSpline: {
        const glm::dvec4 p0 = value(k0), p1 = value(k1);
        const glm::dvec4 m0 = dt * sampler.values[k0 * 3 + 2];  // out-tangent of k0
        const glm::dvec4 m1 = dt * sampler.values[k1 * 3 + 0];  // in-tangent of k1
        const double s2 = s * s, s3 = s2 * s;
        const glm::dvec4 v = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 +
                             (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
        return finish(v);
    }
    }
    return finish(value(k0));
}

std::vector<double> sampleWeights(const AnimationSampler& sampler, double time) {
    const std::size_t n = sampler.weightCount;
    const auto& times = sampler.times;
    const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
    const std::size_t per = cubic ? 3 : 1;
    std::vector<double> out(n, 0.0);
    if (times.empty() || sampler.weights.size() < times.size() * per * n) return out;
    // Group g (0: in-tangents, 1: values, 2: out-tangents for CubicSpline) of key k.
    auto group = [&](std::size_t k, std::size_t g) { return &sampler.weights[(k * per + g) * n]; };
    const std::size_t valueGroup = cubic ? 1 : 0;
    auto copyKey = [&](std::size_t k) {
        const double* v = group(k, valueGroup);
        out.assign(v, v + n);
        return out;
    };
    if (!(time > times.front())) return copyKey(0);
    if (time >= times.back()) return copyKey(times.size() - 1);
    const std::size_t k1 = std::size_t(std::upper_bound(times.begin(), times.end(), time) -
                                       times.begin());
    const std::size_t k0 = k1 - 1;
    const double dt = times[k1] - times[k0];
    const double s = (time - times[k0]) / dt;
    switch (sampler.interpolation) {
    case Interpolation::Step: return copyKey(k0);
    case Interpolation::Linear: {
        const double *a = group(k0, 0), *b = group(k1, 0);
        for (std::size_t i = 0; i < n; ++i) out[i] = a[i] + s * (b[i] - a[i]);
        return out;
    }
    case Interpolation::CubicSpline: {
        const double *p0 = group(k0, 1), *p1 = group(k1, 1);
        const double *b0 = group(k0, 2), *a1 = group(k1, 0);  // out-tangent of k0, in of k1
        const double s2 = s * s, s3 = s2 * s;
        for (std::size_t i = 0; i < n; ++i)
            out[i] = (2 * s3 - 3 * s2 + 1) * p0[i] + (s3 - 2 * s2 + s) * dt * b0[i] +
                     (-2 * s3 + 3 * s2) * p1[i] + (s3 - s2) * dt * a1[i];
        return out;
    }
    }
    return copyKey(k0);
}

} // namespace lantern
