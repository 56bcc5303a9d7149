// Separable filtering of float planes with replicated borders, and a parallel loop over rows:
// what SSIM and FLIP are made of. Device-free.
#pragma once

#include <cstddef>
#include <vector>

namespace lantern::compare {

/// A plane of width x height floats, row after row.
struct Plane {
    int width = 0, height = 0;
    std::vector<float> v;
    Plane() = default;
    Plane(int w, int h) : width(w), height(h), v(std::size_t(w) * std::size_t(h), 0.0f) {}
    float& at(int x, int y) { return v[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    float at(int x, int y) const { return v[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

/// A 1D kernel of odd size 2r + 1, index i for offset i - r.
using Kernel = std::vector<float>;

/// out(x, y) = sum_j ky[j] * sum_i kx[i] * in(x + i - rx, y + j - ry), borders replicated
/// (correlation, as OpenCV's filter2D computes it).
Plane filterSeparable(const Plane& in, const Kernel& kx, const Kernel& ky);

/// Rows only / columns only.
Plane filterRows(const Plane& in, const Kernel& k);
Plane filterColumns(const Plane& in, const Kernel& k);

/// Runs f(i) for i in [0, count) over the available cores.
void parallelFor(int count, void (*f)(int, void*), void* context);

template <class F>
void forEachRow(int count, F&& f) {
    parallelFor(
        count, [](int i, void* c) { (*static_cast<F*>(c))(i); }, &f);
}

} // namespace lantern::compare
