// Separable filters with replicated borders, and the row-parallel loop.
#include "compare/Filters.h"

#include <algorithm>
#include <atomic>
#include <thread>

namespace lantern::compare {

void parallelFor(int count, void (*f)(int, void*), void* context) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const int threads = int(std::min<unsigned>(cores, unsigned(std::max(1, count / 16))));
    if (threads <= 1) {
        for (int i = 0; i < count; ++i) f(i, context);
        return;
    }
    std::atomic<int> next{0};
    auto work = [&]() {
        constexpr int kChunk = 8;
        for (int begin = next.fetch_add(kChunk); begin < count; begin = next.fetch_add(kChunk))
            for (int i = begin; i < std::min(count, begin + kChunk); ++i) f(i, context);
    };
    std::vector<std::thread> pool;
    pool.reserve(std::size_t(threads - 1));
    for (int t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
}

Plane filterRows(const Plane& in, const Kernel& k) {
    Plane out(in.width, in.height);
    const int r = int(k.size() / 2), w = in.width;
    forEachRow(in.height, [&](int y) {
        const float* src = in.v.data() + std::size_t(y) * std::size_t(w);
        float* dst = out.v.data() + std::size_t(y) * std::size_t(w);
        for (int x = 0; x < w; ++x) {
            float sum = 0.0f;
            if (x >= r && x + r < w) {
                const float* s = src + (x - r);
                for (std::size_t i = 0; i < k.size(); ++i) sum += k[i] * s[i];
            } else {
                for (int i = -r; i <= r; ++i) sum += k[std::size_t(i + r)] * src[std::clamp(x + i, 0, w - 1)];
            }
            dst[x] = sum;
        }
    });
    return out;
}

Plane filterColumns(const Plane& in, const Kernel& k) {
    Plane out(in.width, in.height);
    const int r = int(k.size() / 2), w = in.width, h = in.height;
    forEachRow(h, [&](int y) {
        float* dst = out.v.data() + std::size_t(y) * std::size_t(w);
        for (int i = -r; i <= r; ++i) {
            const float weight = k[std::size_t(i + r)];
            const float* src = in.v.data() + std::size_t(std::clamp(y + i, 0, h - 1)) * std::size_t(w);
            for (int x = 0; x < w; ++x) dst[x] += weight * src[x];
        }
    });
    return out;
}

Plane filterSeparable(const Plane& in, const Kernel& kx, const Kernel& ky) {
    return filterColumns(filterRows(in, kx), ky);
}

} // namespace lantern::compare
