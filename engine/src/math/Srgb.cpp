#include "math/Srgb.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern::math {
namespace {

float srgbEncode(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float floatOf(std::uint32_t bits) {
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

} // namespace

unsigned char srgb8Reference(float linear) {
    return static_cast<unsigned char>(std::lround(srgbEncode(linear) * 255.0f));
}

Srgb8Encoder::Srgb8Encoder() {
    for (int k = 0; k < 255; ++k) {
        std::uint32_t lo = 0, hi = kOne;  // 0.0f and 1.0f: codes 0 and 255
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            (srgb8Reference(floatOf(mid)) > k ? hi : lo) = mid;
        }
        steps[k] = floatOf(hi);
    }
    for (std::uint32_t i = 0; i <= (kOne >> kShift); ++i) {
        const float first = floatOf(i << kShift);
        int code = 0;
        while (code < 255 && steps[code] <= first) ++code;
        start[i] = static_cast<unsigned char>(code);
    }
}

const Srgb8Encoder& srgb8Encoder() {
    static const Srgb8Encoder encoder;
    return encoder;
}

unsigned char srgb8(float linear) { return srgb8Encoder()(linear); }

const float* srgb8ToLinear() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int k = 0; k < 256; ++k) {
            const double c = k / 255.0;
            t[std::size_t(k)] =
                float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table.data();
}

} // namespace lantern::math
