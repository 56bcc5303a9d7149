#include "gpu/TextureMips.h"

#include "core/Bands.h"
#include "math/Srgb.h"

#include <lantern/Assert.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <vector>

namespace lantern::gpu {
namespace {

// The source texels one destination texel covers along an axis, with the share of each:
// destination x covers [x * src, (x + 1) * src) in units of 1/dst of a source texel, so the
// shares are exact ratios of integers and sum to one. A side halves to at most 3 texels.
struct Taps {
    int first = 0;
    int count = 0;
    std::array<float, 3> weight{};
};

std::vector<Taps> tapsAlong(int src, int dst) {
    std::vector<Taps> taps(static_cast<std::size_t>(dst));
    for (int x = 0; x < dst; ++x) {
        const long long lo = (long long)x * src, hi = (long long)(x + 1) * src;
        Taps& t = taps[std::size_t(x)];
        t.first = int(lo / dst);
        const int last = int((hi - 1) / dst);
        t.count = last - t.first + 1;
        LANTERN_ASSERT(t.count >= 1 && t.count <= 3, "a halved side covers 1 to 3 texels");
        for (int i = 0; i < t.count; ++i) {
            const long long cell = (long long)(t.first + i) * dst;
            const long long covered = std::min(hi, cell + dst) - std::max(lo, cell);
            t.weight[std::size_t(i)] = float(double(covered) / double(src));
        }
    }
    return taps;
}

std::uint8_t roundUnorm(float v) { return std::uint8_t(std::clamp(v + 0.5f, 0.0f, 255.0f)); }

} // namespace

std::uint32_t mipLevelCount(int width, int height) {
    LANTERN_ASSERT(width >= 1 && height >= 1, "an image has at least one texel");
    return std::uint32_t(std::bit_width(std::uint32_t(std::max(width, height))));
}

int mipExtent(int extent, std::uint32_t level) {
    return level >= 31 ? 1 : std::max(extent >> level, 1);
}

namespace {

// Destination rows [y0, y1) of downsampleRgba8. `colour` maps a colour channel's code to the
// value averaged (linear light for sRGB, the code otherwise); alpha averages its codes.
struct Downsample {
    const std::uint8_t* src;
    int srcWidth, srcHeight;
    std::uint8_t* dst;
    int dstWidth, dstHeight;
    bool srgb;
    std::vector<Taps> across, down;
    std::array<float, 256> colour{};

    const math::Srgb8Encoder& srgb8 = math::srgb8Encoder();

    std::uint8_t store(float v) const { return srgb ? srgb8(v) : roundUnorm(v); }

    // Both sides even: every texel the plain mean of a 2 x 2 block.
    void evenRows(int y0, int y1) const {
        const std::size_t srcRow = std::size_t(srcWidth) * 4;
        for (int y = y0; y < y1; ++y) {
            const std::uint8_t* a = src + std::size_t(2 * y) * srcRow;
            const std::uint8_t* b = a + srcRow;
            std::uint8_t* out = dst + std::size_t(y) * std::size_t(dstWidth) * 4;
            for (int x = 0; x < dstWidth; ++x, a += 8, b += 8, out += 4) {
                for (int c = 0; c < 3; ++c)
                    out[c] = store(0.25f * (colour[a[c]] + colour[a[4 + c]] + colour[b[c]] +
                                            colour[b[4 + c]]));
                out[3] = roundUnorm(0.25f * float(a[3] + a[7] + b[3] + b[7]));
            }
        }
    }

    void weightedRows(int y0, int y1) const {
        const std::size_t srcRow = std::size_t(srcWidth) * 4;
        for (int y = y0; y < y1; ++y) {
            const Taps& ty = down[std::size_t(y)];
            std::uint8_t* out = dst + std::size_t(y) * std::size_t(dstWidth) * 4;
            for (int x = 0; x < dstWidth; ++x, out += 4) {
                const Taps& tx = across[std::size_t(x)];
                float sum[4] = {0, 0, 0, 0};
                for (int j = 0; j < ty.count; ++j) {
                    const std::uint8_t* row = src + std::size_t(ty.first + j) * srcRow;
                    const float wy = ty.weight[std::size_t(j)];
                    for (int i = 0; i < tx.count; ++i) {
                        const std::uint8_t* p = row + std::size_t(tx.first + i) * 4;
                        const float w = wy * tx.weight[std::size_t(i)];
                        sum[0] += w * colour[p[0]];
                        sum[1] += w * colour[p[1]];
                        sum[2] += w * colour[p[2]];
                        sum[3] += w * float(p[3]);
                    }
                }
                for (int c = 0; c < 3; ++c) out[c] = store(sum[c]);
                out[3] = roundUnorm(sum[3]);
            }
        }
    }

    void rows(int y0, int y1) const {
        if (srcWidth % 2 == 0 && srcHeight % 2 == 0)
            evenRows(y0, y1);
        else
            weightedRows(y0, y1);
    }
};

// Levels with at least this many texels are split between two threads.
constexpr std::size_t kThreadedTexels = std::size_t(1) << 16;

} // namespace

void downsampleRgba8(const std::uint8_t* src, int srcWidth, int srcHeight, std::uint8_t* dst,
                     int dstWidth, int dstHeight, bool srgb) {
    LANTERN_ASSERT(dstWidth == std::max(srcWidth / 2, 1) &&
                       dstHeight == std::max(srcHeight / 2, 1),
                   "the destination is the next mip level of the source");
    Downsample d{src, srcWidth, srcHeight, dst, dstWidth, dstHeight, srgb,
                 tapsAlong(srcWidth, dstWidth), tapsAlong(srcHeight, dstHeight), {}};
    const float* toLinear = math::srgb8ToLinear();
    for (int k = 0; k < 256; ++k) d.colour[std::size_t(k)] = srgb ? toLinear[k] : float(k);
    // The bottom half of the rows on a second thread where the level is large enough to pay
    // for it; the results do not depend on the split.
    inTwoBands(dstHeight, std::size_t(dstWidth) * std::size_t(dstHeight) >= kThreadedTexels,
               [&d](int y0, int y1) { d.rows(y0, y1); });
}

} // namespace lantern::gpu
