// The host-made mip chain (gpu/TextureMips.h): level counts and sizes by Vulkan's rule, the
// area weights of even, odd and unit sides, sRGB averaged in linear light and rounded to the
// nearest code (checked against a double-precision formula for every pair of codes), and a
// constant image kept exactly through every level.
#include "gpu/TextureMips.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using namespace lantern::gpu;

double decode(int code) {
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The sRGB code of a linear value, unrounded (0 to 255).
double encoded(double linear) {
    const double c = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return c * 255.0;
}

// A width x height image whose every texel is (r, g, b, a) = value(x, y) in all four channels.
template <typename F>
std::vector<std::uint8_t> imageOf(int width, int height, F value) {
    std::vector<std::uint8_t> px;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::uint8_t v = value(x, y);
            px.insert(px.end(), {v, v, v, v});
        }
    return px;
}

std::vector<std::uint8_t> halved(const std::vector<std::uint8_t>& src, int w, int h, bool srgb) {
    const int nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
    std::vector<std::uint8_t> dst(std::size_t(nw) * std::size_t(nh) * 4);
    downsampleRgba8(src.data(), w, h, dst.data(), nw, nh, srgb);
    return dst;
}

TEST(TextureMips, LevelCountsAndSizesFollowVulkansRule) {
    EXPECT_EQ(mipLevelCount(1, 1), 1u);
    EXPECT_EQ(mipLevelCount(2, 1), 2u);
    EXPECT_EQ(mipLevelCount(1, 3), 2u);
    EXPECT_EQ(mipLevelCount(1024, 1024), 11u);
    EXPECT_EQ(mipLevelCount(1000, 600), 10u);
    EXPECT_EQ(mipLevelCount(128, 32), 8u);
    EXPECT_EQ(mipExtent(1000, 0), 1000);
    EXPECT_EQ(mipExtent(1000, 3), 125);
    EXPECT_EQ(mipExtent(1000, 4), 62);
    EXPECT_EQ(mipExtent(600, 9), 1);
    EXPECT_EQ(mipExtent(5, 40), 1);
}

TEST(TextureMips, EvenSidesAverageTwoByTwo) {
    // Linear data: the four values' mean, rounded to nearest.
    const std::vector<std::uint8_t> src = imageOf(4, 2, [](int x, int y) {
        static const int v[2][4] = {{0, 255, 10, 11}, {255, 255, 20, 20}};
        return std::uint8_t(v[y][x]);
    });
    const std::vector<std::uint8_t> dst = halved(src, 4, 2, false);
    ASSERT_EQ(dst.size(), 8u);
    EXPECT_EQ(dst[0], 191);  // 765 / 4 = 191.25
    EXPECT_EQ(dst[4], 15);   // 61 / 4 = 15.25
}

TEST(TextureMips, OddSidesWeighTheTexelsByHowMuchEachIsCovered) {
    // 5 -> 2: each destination texel covers 2.5 source texels (0.4, 0.4, 0.2 of its area).
    const std::vector<std::uint8_t> five =
        imageOf(5, 1, [](int x, int) { return std::uint8_t(10 * (x + 1)); });
    const std::vector<std::uint8_t> two = halved(five, 5, 1, false);
    ASSERT_EQ(two.size(), 8u);
    EXPECT_EQ(two[0], 18);  // 0.4*10 + 0.4*20 + 0.2*30
    EXPECT_EQ(two[4], 42);  // 0.2*30 + 0.4*40 + 0.4*50
    // 3 x 3 -> 1 x 1: the mean of nine; a side of 1 stays 1.
    const std::vector<std::uint8_t> nine =
        imageOf(3, 3, [](int x, int y) { return std::uint8_t(9 * (x + 3 * y)); });
    EXPECT_EQ(halved(nine, 3, 3, false)[0], 36);
    const std::vector<std::uint8_t> column =
        imageOf(1, 4, [](int, int y) { return std::uint8_t(y == 0 ? 100 : 0); });
    const std::vector<std::uint8_t> half = halved(column, 1, 4, false);
    ASSERT_EQ(half.size(), 8u);
    EXPECT_EQ(half[0], 50);
    EXPECT_EQ(half[4], 0);
}

TEST(TextureMips, SrgbColourIsAveragedInLinearLightAndAlphaIsNot) {
    // Black and white: half the light, sRGB code 188 (not 128); alpha averages as data.
    std::vector<std::uint8_t> src = {0, 0, 0, 0, 255, 255, 255, 255};
    const std::vector<std::uint8_t> dst = halved(src, 2, 1, true);
    EXPECT_EQ(dst[0], 188);
    EXPECT_EQ(dst[1], 188);
    EXPECT_EQ(dst[2], 188);
    EXPECT_EQ(dst[3], 128);
    // Every pair of codes, against the formula in double: the nearest code, or either of two
    // where the mean lies within float's precision of halfway between them (ties included).
    int wrong = 0;
    for (int a = 0; a < 256; ++a)
        for (int b = 0; b < 256; ++b) {
            const std::vector<std::uint8_t> pair = {std::uint8_t(a), 0, 0, 255,
                                                    std::uint8_t(b), 0, 0, 255};
            const double exact = encoded((decode(a) + decode(b)) / 2.0);
            const int got = halved(pair, 2, 1, true)[0];
            const bool nearTie = std::abs(exact - std::floor(exact) - 0.5) < 1e-4;
            wrong += nearTie ? std::abs(got - exact) > 0.5 + 1e-4 : got != std::lround(exact);
        }
    EXPECT_EQ(wrong, 0);
}

TEST(TextureMips, AConstantImageKeepsItsValueAtEveryLevel) {
    for (bool srgb : {false, true})
        for (int code = 0; code < 256; ++code) {
            int w = 37, h = 20;
            std::vector<std::uint8_t> level = imageOf(w, h, [&](int, int) { return std::uint8_t(code); });
            while (w > 1 || h > 1) {
                level = halved(level, w, h, srgb);
                w = std::max(w / 2, 1);
                h = std::max(h / 2, 1);
            }
            ASSERT_EQ(level.size(), 4u);
            EXPECT_EQ(level[0], code) << (srgb ? "srgb" : "linear");
            EXPECT_EQ(level[3], code);
        }
}

} // namespace
