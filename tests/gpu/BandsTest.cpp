// A picture rendered in bands (Renderer::renderBands) and written band by band (PngStream):
// the bands hold the whole frame's rows, in order, with several views, overlays, flat shading
// and multisampling; the PNG written from them is the PNG of the whole frame; and what goes
// wrong (a failing sink, a frame with NaN, a stream used out of turn) writes nothing.
#include "TestSupport.h"

#include "gpu/DrawList.h"
#include "render/FrameRender.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

namespace {

using namespace lantern;
using lantern::test::testOutputDir;

// The shared renderer (validation on: a message fails the test) with builtin:spheres prepared.
class Bands : public lantern::test::GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        auto scene = builtinScene("spheres");
        ASSERT_TRUE(scene);
        auto p = renderer().prepare(std::make_shared<const Scene>(std::move(*scene)));
        ASSERT_TRUE(p) << p.error().describe();
        prepared.emplace(std::move(*p));
    }
    static RenderOptions sized(int w, int h) {
        RenderOptions o;
        o.width = w;
        o.height = h;
        return o;
    }

    // The picture put together from renderBands' bands, checking each band's place and size.
    Result<Image> banded(const RenderOptions& o, int rows) {
        Image out(o.width, o.height);
        int expectedTop = 0;
        auto r = renderer().renderBands(*prepared, o, 0.5, rows, [&](const FrameView& band, int top) {
            EXPECT_EQ(top, expectedTop);
            EXPECT_EQ(band.width(), o.width);
            EXPECT_EQ(band.height(), std::min(rows, o.height - top));
            for (int y = 0; y < band.height(); ++y)
                std::memcpy(out.rgba.data() + std::size_t(top + y) * std::size_t(o.width) * 4,
                            band.row(y), std::size_t(o.width) * 16);
            expectedTop += band.height();
            return Result<void>{};
        });
        if (!r) return std::move(r).error();
        EXPECT_EQ(expectedTop, o.height);
        return out;
    }

    static std::string bytes(const std::filesystem::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    std::optional<PreparedScene> prepared;
};

// The largest difference of any channel between two pictures of one size, relative to the
// value where it exceeds 1.
float largestDifference(const Image& a, const Image& b) {
    float d = 0.0f;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        d = std::max(d, std::abs(a.rgba[i] - b.rgba[i]) / std::max(1.0f, std::abs(b.rgba[i])));
    return d;
}

// Every band holds the whole frame's rows: a band's viewport keeps the view's place in the
// picture and its scissor keeps the band's rows, so the rasteriser covers the same pixels.
// The values may differ in their last bits: the rasteriser interpolates from vertex positions
// whose window coordinates are rounded once more in a band (the translation differs by the
// band's first row). Measured on lavapipe: at most 3.1e-6, and none in flat shading, whose
// colour is constant per triangle; a pixel covered differently would differ by far more.
// Bands of 1 row, of sizes that do not divide the height, and of more rows than the picture;
// one and four samples; two views (one wholly outside some bands) with the wireframe overlay;
// flat shading lit per triangle.
TEST_F(Bands, TheBandsHoldTheRowsOfTheWholeFrame) {
    struct Case {
        const char* what;
        RenderOptions options;
    };
    std::vector<Case> cases;
    cases.push_back({"one view", sized(67, 45)});
    RenderOptions msaa = sized(64, 40);
    msaa.msaa = 4;
    msaa.background = glm::vec4(0.0f);
    cases.push_back({"msaa 4, transparent", msaa});
    RenderOptions views = sized(60, 48);
    views.views = {View{0, 0, 30, 20, {}}, View{30, 8, 30, 40, {}}};
    views.wireframe = true;
    cases.push_back({"two views, wireframe", views});
    RenderOptions flat = sized(50, 38);
    flat.shading = ShadingMode::Flat;
    cases.push_back({"flat", flat});
    for (const Case& c : cases) {
        auto whole = renderer().render(*prepared, c.options, 0.5);
        ASSERT_TRUE(whole) << whole.error().describe();
        for (int rows : {1, 7, 16, c.options.height, 1000}) {
            SCOPED_TRACE(std::string(c.what) + ", bands of " + std::to_string(rows) + " rows");
            auto bands = banded(c.options, rows);
            ASSERT_TRUE(bands) << bands.error().describe();
            EXPECT_LE(largestDifference(*bands, *whole), 1e-5f);
            if (c.options.shading == ShadingMode::Flat) {
                EXPECT_EQ(largestDifference(*bands, *whole), 0.0f);
            }
        }
    }
}

// The rows chosen for a whole picture: one band under 2^20 pixels; about 4 MiB of float colour
// per band above (136 rows of 1920 pixels, 68 of 3840, at least 16); one band again when
// drawing the geometry once more per band would cost more than a quarter of a vertex per pixel.
TEST(BandRows, TheAutomaticHeightWeighsPixelsAgainstVertices) {
    EXPECT_EQ(render::autoBandRows(1024, 1023, 0.0), 1023);  // just under 2^20 pixels
    EXPECT_EQ(render::autoBandRows(1024, 1024, 0.0), 256);
    EXPECT_EQ(render::autoBandRows(1920, 1080, 0.0), 136);
    EXPECT_EQ(render::autoBandRows(3840, 2160, 0.0), 68);
    EXPECT_EQ(render::autoBandRows(100000, 20, 0.0), 16);
    EXPECT_EQ(render::autoBandRows(1920, 100, 0.0), 100);  // one band holds it all
    // 1920x1080 in 8 bands: 7 more draws of the geometry against 518,400 vertices' worth.
    EXPECT_EQ(render::autoBandRows(1920, 1080, 518400.0 / 7.0), 136);
    EXPECT_EQ(render::autoBandRows(1920, 1080, 518400.0 / 7.0 + 1.0), 1080);
}

// A PNG written band by band is the PNG of the whole frame, byte for byte, and the file appears
// only at finish().
TEST_F(Bands, APngWrittenBandByBandIsThePngOfTheWholeFrame) {
    RenderOptions o = sized(67, 45);
    o.msaa = 4;
    o.background = glm::vec4(0.0f);  // transparent edges: un-premultiplied on the way
    auto whole = renderer().render(*prepared, o, 0.5);
    ASSERT_TRUE(whole);
    const auto dir = testOutputDir();
    ASSERT_TRUE(writePng(dir / "whole.png", *whole));
    auto stream = PngStream::create(dir / "bands.png", o.width, o.height);
    ASSERT_TRUE(stream) << stream.error().describe();
    auto r = renderer().renderBands(*prepared, o, 0.5, 10, [&](const FrameView& band, int) {
        EXPECT_FALSE(std::filesystem::exists(dir / "bands.png"));
        return stream->write(band);
    });
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_FALSE(std::filesystem::exists(dir / "bands.png"));
    ASSERT_TRUE(stream->finish());
    EXPECT_GT(bytes(dir / "bands.png").size(), 100u);
    EXPECT_EQ(bytes(dir / "bands.png"), bytes(dir / "whole.png"));
}

// A stream refuses a band of another width or more rows than are left and an unfinished
// picture, and leaves nothing when dropped; a sink's error stops the render and is returned;
// AOVs and negative rows are refused before anything renders.
TEST_F(Bands, WhatGoesWrongWritesNothing) {
    const auto dir = testOutputDir() / "bands-wrong";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    RenderOptions o = sized(32, 24);
    int calls = 0;
    auto stopped = renderer().renderBands(*prepared, o, 0.0, 8, [&](const FrameView&, int) {
        ++calls;
        return Result<void>(makeError(ErrorCode::IoError, "disk on fire"));
    });
    ASSERT_FALSE(stopped);
    EXPECT_EQ(stopped.error().message, "disk on fire");
    EXPECT_EQ(calls, 1);
    // The renderer is left ready for the next frame.
    ASSERT_TRUE(renderer().render(*prepared, o, 0.0));

    {
        auto stream = PngStream::create(dir / "wide.png", 31, 24);
        ASSERT_TRUE(stream);
        auto r = renderer().renderBands(*prepared, o, 0.0, 8,
                                       [&](const FrameView& band, int) { return stream->write(band); });
        ASSERT_FALSE(r);
        EXPECT_EQ(r.error().code, ErrorCode::Usage);
        EXPECT_EQ(r.error().file, (dir / "wide.png").string());
    }
    {
        auto stream = PngStream::create(dir / "short.png", 32, 20);
        ASSERT_TRUE(stream);
        auto r = renderer().renderBands(*prepared, o, 0.0, 8,
                                       [&](const FrameView& band, int) { return stream->write(band); });
        ASSERT_FALSE(r);
        EXPECT_NE(r.error().message.find("rows"), std::string::npos) << r.error().message;
    }
    {
        auto stream = PngStream::create(dir / "unfinished.png", 32, 24);
        ASSERT_TRUE(stream);
        auto r = renderer().renderBands(*prepared, o, 0.0, 8, [&](const FrameView& band, int top) {
            return top < 16 ? stream->write(band) : Result<void>{};
        });
        ASSERT_TRUE(r);
        auto finished = stream->finish();
        ASSERT_FALSE(finished);
        EXPECT_EQ(finished.error().code, ErrorCode::Usage);
        EXPECT_NE(finished.error().message.find("16 of 24 rows"), std::string::npos)
            << finished.error().message;
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir));  // not even a temporary file is left

    auto nowhere = PngStream::create(dir / "missing" / "x.png", 32, 24);
    ASSERT_FALSE(nowhere);
    EXPECT_EQ(nowhere.error().code, ErrorCode::IoError);
    EXPECT_FALSE(PngStream::create(dir / "empty.png", 0, 24));
    EXPECT_FALSE(PngStream{}.write(FrameView{}));

    RenderOptions aov = o;
    aov.aovs.depth = true;
    auto refused = renderer().renderBands(*prepared, aov, 0.0, 8, [&](const FrameView&, int) {
        ADD_FAILURE() << "a band was rendered";
        return Result<void>{};
    });
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::Usage);
    EXPECT_EQ(renderer().renderBands(*prepared, o, 0.0, -1, {}).error().code, ErrorCode::Usage);
}

// A band holding NaN is refused as render() refuses the frame, naming the pixel; no band after
// it reaches the sink.
TEST_F(Bands, ABandWithNaNIsRefused) {
    RenderOptions o = sized(48, 32);
    ::setenv("LANTERN_TEST_NONFINITE_PIXEL", "5,3", 1);
    int calls = 0;
    auto r = renderer().renderBands(*prepared, o, 0.0, 8, [&](const FrameView&, int) {
        ++calls;
        return Result<void>{};
    });
    auto image = renderer().render(*prepared, o, 0.0);
    ::unsetenv("LANTERN_TEST_NONFINITE_PIXEL");
    ASSERT_FALSE(r);
    ASSERT_FALSE(image);
    EXPECT_EQ(calls, 0);
    EXPECT_EQ(r.error().message, image.error().message);
    EXPECT_NE(r.error().message.find("the first at pixel (5, 3)"), std::string::npos)
        << r.error().message;
}

} // namespace
