// Alpha: blended draws come after the opaque ones and are sorted back to front whatever the
// scene order; alpha-mask discards below the cutoff per fragment (per triangle with flat
// shading, whose alpha is the triangle's), and what it keeps is opaque.
#include "LightingCompare.h"

#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

Material unlit(glm::dvec4 colour, AlphaMode mode) {
    Material m;
    m.unlit = true;
    m.front.diffuse = colour;
    m.alphaMode = mode;
    return m;
}

class LightingAlpha : public GpuTest {};

// Three half-transparent quads listed near to far, and an opaque quad behind them listed last:
// "over" in the wrong order, or the opaque quad drawn after them, gives other colours.
TEST_F(LightingAlpha, BlendedDrawsAreSortedBackToFrontAfterTheOpaqueOnes) {
    LitScene s;
    s.objects.push_back({makePlane(2.0, 1), unlit({1, 0, 0, 0.5}, AlphaMode::Blend),
                         test::translation({0, 0, 0.5})});
    s.objects.push_back({makePlane(2.2, 1), unlit({0, 1, 0, 0.5}, AlphaMode::Blend),
                         test::translation({0, 0, 0.0})});
    s.objects.push_back({makePlane(2.4, 1), unlit({0, 0, 1, 0.5}, AlphaMode::Blend),
                         test::translation({0, 0, -0.5})});
    s.objects.push_back({makePlane(1.0, 1), unlit({1, 1, 1, 1}, AlphaMode::Opaque),
                         test::translation({0, 0, -1.0})});
    const Scene scene = s.build();
    const RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    auto plan = frame::buildFrame(scene, o, 0.0);
    ASSERT_TRUE(plan);
    const auto& draws = plan->views[0].draws;
    ASSERT_EQ(draws.size(), 4u);
    EXPECT_EQ(draws[0].node, 3u) << "the opaque quad first";
    EXPECT_EQ(draws[1].node, 2u) << "then the farthest blended quad";
    EXPECT_EQ(draws[3].node, 0u) << "the nearest last";

    auto img = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u);
    struct Row {
        int x, y;
        float r, g, b, a;
        const char* why;
    };
    // Straight alpha "over" into a premultiplied target: rgb = a src + (1 - a) dst.
    for (const Row& row :
         {Row{32, 32, 0.625f, 0.375f, 0.25f, 1.0f, "blue, green, red over white"},
          Row{48, 32, 0.5f, 0.25f, 0.125f, 0.875f, "blue, green, red over nothing"}}) {
        const float* px = img->pixel(row.x, row.y);
        EXPECT_NEAR(px[0], row.r, 1e-6) << row.why;
        EXPECT_NEAR(px[1], row.g, 1e-6) << row.why;
        EXPECT_NEAR(px[2], row.b, 1e-6) << row.why;
        EXPECT_NEAR(px[3], row.a, 1e-6) << row.why;
    }
}

class LightingAlphaMask : public GpuTest, public ::testing::WithParamInterface<ShadingMode> {};

// A quad filling an orthographic view, its COLOR_0 alpha rising from 0 (left) to 1 (right),
// masked at 0.5: per fragment, the left half is discarded; with flat shading each triangle
// has its corners' mean alpha, so the lower-right triangle (2/3) stays and the other (1/3) goes.
TEST_P(LightingAlphaMask, DiscardsBelowTheCutoffAndKeepsTheRestOpaque) {
    LitScene s;
    Primitive p = makePlane(2.0, 1);
    for (const glm::vec3& v : p.positions)
        p.colors.emplace_back(1.0f, 1.0f, 1.0f, (v.x + 1.0f) / 2.0f);
    Material m = unlit({1, 1, 1, 1}, AlphaMode::Mask);
    m.alphaCutoff = 0.5;
    s.objects.push_back({p, m, glm::dmat4(1.0)});
    s.projection = Projection::makeOrtho(-1, 1, -1, 1, 1, 10);
    const int n = 64;
    auto img = renderer().render(s.build(), test::optionsFor(n, n, GetParam()), 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    std::size_t kept = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double wx = -1.0 + (x + 0.5) * 2.0 / n, wy = 1.0 - (y + 0.5) * 2.0 / n;
            bool keep;
            if (GetParam() == ShadingMode::Flat) {
                if (std::abs(wx - wy) < 2.0 / n) continue; // the diagonal between the triangles
                keep = wy < wx;
            } else {
                keep = (wx + 1.0) / 2.0 >= 0.5;
            }
            const float* px = img->pixel(x, y);
            kept += keep;
            EXPECT_EQ(px[3], keep ? 1.0f : 0.0f) << x << "," << y;
            EXPECT_EQ(px[0], keep ? 1.0f : 0.0f) << x << "," << y;
        }
    EXPECT_GT(kept, 1000u);
}

INSTANTIATE_TEST_SUITE_P(Modes, LightingAlphaMask,
                         ::testing::Values(ShadingMode::Flat, ShadingMode::Gouraud,
                                           ShadingMode::Phong),
                         [](const auto& p) { return std::string(toString(p.param)); });

} // namespace
