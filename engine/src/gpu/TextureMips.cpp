#include "gpu/TextureMips.h"

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

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// sRGB codes to linear light, and back to the nearest code: `threshold[k]` is the linear value
// halfway (in code space) between codes k and k + 1, so a value's code is the number of
// thresholds at or below it; a coarse table gives a start one or two steps from it.
struct SrgbTables {
    std::array<float, 256> toLinear{};
    std::array<float, 255> threshold{};
    std::array<std::uint8_t, 4097> coarse{};

    SrgbTables() {
        for (int k = 0; k < 256; ++k) toLinear[std::size_t(k)] = float(srgbToLinear(k / 255.0));
        for (int k = 0; k < 255; ++k)
            threshold[std::size_t(k)] = float(srgbToLinear((k + 0.5) / 255.0));
        for (int i = 0; i <= 4096; ++i) {
            const float v = float(i) / 4096.0f;
            coarse[std::size_t(i)] = std::uint8_t(
                std::upper_bound(threshold.begin(), threshold.end(), v) - threshold.begin());
        }
    }

    std::uint8_t encode(float linear) const {
        const float v = std::clamp(linear, 0.0f, 1.0f);
        int k = coarse[std::size_t(v * 4096.0f)];
        while (k < 255 && v >= threshold[std::size_t(k)]) ++k;
        while (k > 0 && v < threshold[std::size_t(k - 1)]) --k;
        return std::uint8_t(k);
    }
};

const SrgbTables& srgbTables() {
    static const SrgbTables tables;
    return tables;
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

void downsampleRgba8(const std::uint8_t* src, int srcWidth, int srcHeight, std::uint8_t* dst,
                     int dstWidth, int dstHeight, bool srgb) {
    LANTERN_ASSERT(dstWidth == std::max(srcWidth / 2, 1) &&
                   dstHeight == std::max(srcHeight / 2, 1),
                   "the destination is the next mip level of the source");
    const std::vector<Taps> across = tapsAlong(srcWidth, dstWidth);
    const std::vector<Taps> down = tapsAlong(srcHeight, dstHeight);
    const SrgbTables& tables = srgbTables();
    // Channel values as averaged: linear light in 0..1 for sRGB colour, codes 0..255 otherwise.
    std::array<float, 256> colour{}, plain{};
    for (int k = 0; k < 256; ++k) {
        plain[std::size_t(k)] = float(k);
        colour[std::size_t(k)] = srgb ? tables.toLinear[std::size_t(k)] : float(k);
    }
    const std::size_t srcRow = std::size_t(srcWidth) * 4;
    for (int y = 0; y < dstHeight; ++y) {
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
                    sum[3] += w * plain[p[3]];
                }
            }
            for (int c = 0; c < 3; ++c)
                out[c] = srgb ? tables.encode(sum[c]) : roundUnorm(sum[c]);
            out[3] = roundUnorm(sum[3]);
        }
    }
}

} // namespace lantern::gpu
