// Srgb.h: 8-bit sRGB codes to and from linear light, exactly: the code of a float is the one
// the sRGB formula rounds it to (found in a table of the 255 floats where the code steps, no
// pow per value), and a code's linear value is the formula's. PNG output (io/PngIo.cpp) and
// the host's texture mip levels (gpu/TextureMips.cpp) quantise with it.
#pragma once

#include <cstdint>
#include <cstring>

namespace lantern::math {

/// The 8-bit sRGB code of a linear value, round(255 * srgbEncode(clamp(v, 0, 1))) computed with
/// the sRGB formula (std::pow); NaN reads as 0. The definition Srgb8Encoder must match.
unsigned char srgb8Reference(float linear);

/// The same code from a table: steps[k] is the smallest float whose code is k + 1 (k = 0..254),
/// found by bisection over the floats' bit patterns (non-negative floats order as their bits).
/// The code of v is the number of steps at or below it: start[] holds that count at the first
/// float of each run of 2^15 floats below 1.0, and at most a step or two lies inside a run.
/// Equal to srgb8Reference for every float (Png.Srgb8MatchesTheFormulaForEveryFloatNearEachStep).
struct Srgb8Encoder {
    static constexpr int kShift = 15;
    static constexpr std::uint32_t kOne = 0x3F800000u;  // 1.0f
    float steps[255];
    unsigned char start[(kOne >> kShift) + 1];

    Srgb8Encoder();

    unsigned char operator()(float linear) const {
        if (!(linear > 0.0f)) return 0;  // also NaN
        if (linear >= 1.0f) return 255;
        std::uint32_t bits;
        std::memcpy(&bits, &linear, sizeof bits);
        int code = start[bits >> kShift];
        while (code < 255 && steps[code] <= linear) ++code;
        return static_cast<unsigned char>(code);
    }
};

/// The process's encoder (built on first use, about 255 x 30 evaluations of the formula).
const Srgb8Encoder& srgb8Encoder();

/// srgb8Encoder()(linear).
unsigned char srgb8(float linear);

/// The linear value of each 8-bit sRGB code, from the formula in double, rounded to float.
const float* srgb8ToLinear();

} // namespace lantern::math
