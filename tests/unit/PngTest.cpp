// PNG output read back with libpng: the colour-space chunks (sRGB, with gAMA and cHRM for
// decoders that do not know sRGB) come before the pixels, and the pixels are the sRGB encoding
// of the un-premultiplied linear colour.
#include "TestSupport.h"

#include "io/image/ImageEncode.h"
#include "math/Srgb.h"

#include <lantern/Io.h>

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>

namespace {

using namespace lantern;

struct PngFacts {
    bool read = false;
    int width = 0, height = 0;
    bool srgb = false;
    int intent = -1;
    bool gamma = false;
    double gammaValue = 0.0;
    bool chrm = false;
    std::vector<unsigned char> rgba;
};

// Reads every fact the test checks; on a libpng error, `read` stays false.
void readPng(const std::filesystem::path& path, PngFacts* facts) {
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    ASSERT_TRUE(file) << path;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return;
    }
    png_init_io(png, file.get());
    png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
    facts->width = int(png_get_image_width(png, info));
    facts->height = int(png_get_image_height(png, info));
    facts->srgb = png_get_sRGB(png, info, &facts->intent) != 0;
    facts->gamma = png_get_gAMA(png, info, &facts->gammaValue) != 0;
    double wx, wy, rx, ry, gx, gy, bx, by;
    facts->chrm = png_get_cHRM(png, info, &wx, &wy, &rx, &ry, &gx, &gy, &bx, &by) != 0;
    if (png_get_color_type(png, info) == PNG_COLOR_TYPE_RGB_ALPHA &&
        png_get_bit_depth(png, info) == 8) {
        png_bytepp rows = png_get_rows(png, info);
        for (int y = 0; y < facts->height; ++y)
            facts->rgba.insert(facts->rgba.end(), rows[y], rows[y] + facts->width * 4);
    }
    png_destroy_read_struct(&png, &info, nullptr);
    facts->read = true;
}

// Writes `image` as NAME in the test's output folder and reads it back into `facts`.
void writeAndRead(const Image& image, const std::string& name, PngFacts* facts) {
    const auto path = test::testOutputDir() / name;
    ASSERT_TRUE(writePng(path, image));
    readPng(path, facts);
    EXPECT_TRUE(facts->read) << "libpng could not read " << path;
}

TEST(Png, CarriesTheSrgbChunkWithGammaAndChromaticities) {
    Image image(3, 2);
    auto set = [&](int x, int y, float r, float g, float b, float a) {
        float* p = image.pixel(x, y);
        p[0] = r, p[1] = g, p[2] = b, p[3] = a;
    };
    set(0, 0, 0.0f, 0.0f, 0.0f, 0.0f);    // transparent background
    set(1, 0, 1.0f, 0.5f, 0.0f, 1.0f);    // opaque
    set(2, 0, 0.25f, 0.25f, 0.25f, 0.5f); // half covered: 0.5 linear once un-premultiplied
    set(0, 1, 4.0f, -1.0f, 0.0031308f, 1.0f);
    PngFacts facts;
    writeAndRead(image, "srgb.png", &facts);
    ASSERT_TRUE(facts.read);
    EXPECT_EQ(facts.width, 3);
    EXPECT_EQ(facts.height, 2);
    EXPECT_TRUE(facts.srgb) << "no sRGB chunk: viewers would guess the colour space";
    EXPECT_EQ(facts.intent, PNG_sRGB_INTENT_PERCEPTUAL);
    EXPECT_TRUE(facts.gamma) << "no gAMA chunk for decoders without sRGB support";
    EXPECT_NEAR(facts.gammaValue, 1.0 / 2.2, 1e-4);
    EXPECT_TRUE(facts.chrm) << "no cHRM chunk";
    ASSERT_EQ(facts.rgba.size(), 3u * 2u * 4u);
    auto at = [&](int x, int y, int c) { return int(facts.rgba[std::size_t((y * 3 + x) * 4 + c)]); };
    EXPECT_EQ(at(0, 0, 3), 0);
    EXPECT_EQ(at(1, 0, 0), 255);
    EXPECT_EQ(at(1, 0, 1), 188) << "sRGB encoding of linear 0.5";
    EXPECT_EQ(at(1, 0, 2), 0);
    EXPECT_EQ(at(1, 0, 3), 255);
    EXPECT_EQ(at(2, 0, 0), 188) << "straight alpha: 0.25 / 0.5 = 0.5 linear";
    EXPECT_EQ(at(2, 0, 3), 128);
    EXPECT_EQ(at(0, 1, 0), 255) << "HDR values clamp to 1";
    EXPECT_EQ(at(0, 1, 1), 0) << "negative values clamp to 0";
    EXPECT_EQ(at(0, 1, 2), 10) << "the linear segment of the sRGB curve: 12.92 * 0.0031308";
}

TEST(Png, TheColourSpaceChunkComesBeforeThePixels) {
    const auto path = test::testOutputDir() / "order.png";
    ASSERT_TRUE(writePng(path, Image(4, 4)));
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto srgb = bytes.find("sRGB"), idat = bytes.find("IDAT");
    ASSERT_NE(srgb, std::string::npos) << "no sRGB chunk";
    ASSERT_NE(idat, std::string::npos) << "no IDAT chunk";
    EXPECT_LT(srgb, idat) << "PNG requires sRGB before the first IDAT";
}

// A picture large enough to be converted on a second thread while libpng compresses
// (PngIo.cpp, 2^18 pixels and up) reads back as pngPixels' rows, every pixel different.
TEST(Png, ALargePictureEncodedWhileItIsConvertedReadsBackRowForRow) {
    Image image(640, 480);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            float* p = image.pixel(x, y);
            p[0] = float(x) / 639.0f;
            p[1] = float(y) / 479.0f;
            p[2] = float((x * 7 + y * 13) % 256) / 255.0f;
            p[3] = 1.0f;
        }
    PngFacts facts;
    writeAndRead(image, "large.png", &facts);
    ASSERT_TRUE(facts.read);
    ASSERT_EQ(facts.width, 640);
    ASSERT_EQ(facts.height, 480);
    EXPECT_EQ(facts.rgba, io::pngPixels(image));
}

} // namespace

// The step table PNGs are quantised with (math::srgb8) gives the formula's code for every float
// where they could differ: 4096 floats on each side of each of the 255 steps, every 997th
// float from 0 to 2, and the special values. (An exhaustive pass over the 1.07e9 floats in
// [0, 1] agreed when the table was written: 1,065,353,217 floats, no mismatch, 15 to 23 s,
// too long for the suite.)
TEST(Png, Srgb8MatchesTheFormulaForEveryFloatNearEachStep) {
    const auto bitsOf = [](float v) {
        std::uint32_t b;
        std::memcpy(&b, &v, sizeof b);
        return b;
    };
    const auto floatOf = [](std::uint32_t b) {
        float v;
        std::memcpy(&v, &b, sizeof v);
        return v;
    };
    std::uint64_t checked = 0, mismatches = 0;
    const auto check = [&](float v) {
        ++checked;
        if (math::srgb8(v) != math::srgb8Reference(v) && ++mismatches <= 5)
            ADD_FAILURE() << "v = " << v << ": table " << int(math::srgb8(v)) << ", formula "
                          << int(math::srgb8Reference(v));
    };
    for (int code = 1; code <= 255; ++code) {
        // The first float of `code` by bisection on the formula itself.
        std::uint32_t lo = 0, hi = bitsOf(1.0f);
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            (math::srgb8Reference(floatOf(mid)) >= code ? hi : lo) = mid;
        }
        for (std::int64_t d = -4096; d <= 4096; ++d)
            if (std::int64_t(hi) + d >= 0) check(floatOf(std::uint32_t(std::int64_t(hi) + d)));
    }
    for (std::uint32_t b = 0; b <= bitsOf(2.0f); b += 997) check(floatOf(b));
    for (float v : {-0.0f, -1.0f, 1.0f, 1e30f, std::numeric_limits<float>::infinity(),
                    std::numeric_limits<float>::denorm_min()})
        check(v);
    EXPECT_EQ(mismatches, 0u) << "of " << checked;
    EXPECT_EQ(math::srgb8(std::nanf("")), 0);
}
