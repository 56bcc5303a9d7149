// Cascaded maps for directional lights, soft shadows (PCSS) and per-map culling
// (frame/Shadows.cpp, render/ShadowLists.cpp, shaders/include/shadows.glsl), each against the
// reference's exact shadow rays (lantern/Reference.h): a row of spheres over a long plane seen
// from low down at one end, where one map over the whole plane is too coarse near the eye;
// a sphere over a plane under a light with a size, whose penumbra PCSS must draw; and maps
// that skip the casters outside them without changing a pixel.
#include "LightingCompare.h"

#include "render/FrameRender.h"

#include <gtest/gtest.h>
#include <lantern/Reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace {

using namespace lantern;
using lantern::test::LitScene;

constexpr int kW = 192, kH = 108;

Material matte() {
    return test::phongMaterial({0.3, 0.2, 0.1}, {0.6, 0.7, 0.8, 1.0}, {0.3, 0.3, 0.3}, 20.0);
}

// A 40 x 40 plane (z = 0) with five spheres of radius 0.5 along Y at 0.7 above it, seen from
// (0, 18, 1.5) towards the origin; one light of `type`.
Scene field(LightType type, bool castShadows) {
    LitScene s;
    s.objects.push_back({tessellate(AnalyticShape::plane(0, 40.0), 8), matte(), glm::dmat4(1.0)});
    for (double y : {12.0, 6.0, 0.0, -6.0, -12.0})
        s.objects.push_back({tessellate(AnalyticShape::sphere(0, 0.5), 64), matte(),
                             glm::translate(glm::dmat4(1.0), glm::dvec3(0.8, y, 0.7))});
    Light l = test::makeLight(type);
    l.ambient = {0.1, 0.1, 0.1};
    l.castShadows = castShadows;
    const glm::dvec3 towards = glm::normalize(glm::dvec3(-1.0, 0.4, 1.2));
    s.lights.push_back({l, type == LightType::Directional ? test::aimed(glm::dvec3(0.0), -towards)
                                                          : test::translation({0.0, 3.0, 3.0})});
    s.projection = Projection::makePerspective(glm::radians(40.0), 0.0, 0.1, 100.0);
    s.lookAt = LookAt{{0.0, 18.0, 1.5}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
    return s.build();
}

std::vector<AnalyticShape> fieldShapes() {
    std::vector<AnalyticShape> shapes{AnalyticShape::plane(0, 40.0)};
    for (int i = 1; i <= 5; ++i) shapes.push_back(AnalyticShape::sphere(i, 0.5));
    return shapes;
}

// The references with and without the shadow, at one sample per pixel.
struct References {
    ReferenceImage shadowed, lit;
};

References references(const Scene& shadowed, const Scene& lit, const RenderOptions& o,
                      const std::vector<AnalyticShape>& shapes) {
    ReferenceOptions r;
    r.shapes = shapes;
    r.boxSamples = 1;
    auto a = raycastReference(shadowed, o, 0.0, r);
    auto b = raycastReference(lit, o, 0.0, r);
    EXPECT_TRUE(a && b);
    return {a ? std::move(*a) : ReferenceImage{}, b ? std::move(*b) : ReferenceImage{}};
}

// The covered pixels whose shadowed state the render gets wrong: shadowed where the colour
// falls by more than half the largest fall the exact shadow makes.
struct StateCount {
    int wrong = 0, covered = 0, inShadow = 0;
};

StateCount compareStates(const Image& shadowed, const Image& lit, const References& ref) {
    StateCount c;
    const int w = shadowed.width, h = shadowed.height;
    auto fallOf = [](const float* a, const float* b) { return a[1] - b[1]; };
    float fall = 0.0f;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            fall = std::max(fall, fallOf(ref.lit.centre.pixel(x, y), ref.shadowed.centre.pixel(x, y)));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!ref.lit.interior[std::size_t(y) * w + x]) continue;
            ++c.covered;
            const bool exact = fallOf(ref.lit.centre.pixel(x, y), ref.shadowed.centre.pixel(x, y)) > 0.5f * fall;
            const bool mapped = fallOf(lit.pixel(x, y), shadowed.pixel(x, y)) > 0.5f * fall;
            c.inShadow += exact;
            c.wrong += exact != mapped;
        }
    return c;
}

std::string featureStarting(const FeatureReport& r, const std::string& prefix) {
    for (const std::string& f : r.features)
        if (f.rfind(prefix, 0) == 0) return f;
    return "";
}

class ShadowCascades : public test::RenderTest {};

// One map over the 40 x 40 plane spends its 512 texels on the whole plane (a texel 8 cm
// across, wider than a pixel near the eye); four cascades fitted to the view's depth give the
// near shadows finer texels, and so fewer wrong pixels.
TEST_F(ShadowCascades, FittedToTheViewTheyCutTheWrongPixels) {
    const Scene shadowedScene = field(LightType::Directional, true);
    const Scene litScene = field(LightType::Directional, false);
    RenderOptions o = test::optionsFor(kW, kH, ShadingMode::Phong);
    o.shadows.resolution = 512;
    const References ref = references(shadowedScene, litScene, o, fieldShapes());
    const Image lit = render(litScene, o);
    int wrong[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
        o.shadows.cascades = i == 0 ? 1 : 4;
        auto report = render::explain(shadowedScene, o, 0.0);
        ASSERT_TRUE(report);
        EXPECT_EQ(featureStarting(*report, "shadow-maps:").rfind(std::string("shadow-maps:") + (i == 0 ? "1 " : "4 "), 0), 0u)
            << featureStarting(*report, "shadow-maps:");
        const StateCount c = compareStates(render(shadowedScene, o), lit, ref);
        std::printf("%d cascade(s): %d of %d covered pixels wrong, %d in the exact shadow\n",
                    o.shadows.cascades, c.wrong, c.covered, c.inShadow);
        EXPECT_GT(c.inShadow, 100) << "the exact shadows cover too little to test";
        wrong[i] = c.wrong;
    }
    EXPECT_LT(wrong[1], wrong[0] * 6 / 10) << "four cascades should beat one map clearly";
    EXPECT_LT(wrong[1], kW * kH / 100) << "under 1 % of the picture";
}

// A point light's six faces each draw only the casters in front of them; the picture is the
// one every face drawing every caster makes, bit for bit.
TEST_F(ShadowCascades, CullingPerMapChangesNoPixel) {
    for (LightType type : {LightType::Point, LightType::Directional}) {
        SCOPED_TRACE(int(type));
        const Scene scene = field(type, true);
        RenderOptions o = test::optionsFor(kW, kH, ShadingMode::Phong);
        o.shadows.resolution = 256;
        RenderOptions all = o;
        all.culling = false;
        auto culled = render::explain(scene, o, 0.0), unculled = render::explain(scene, all, 0.0);
        ASSERT_TRUE(culled && unculled);
        const std::string a = featureStarting(*culled, "shadow-maps:");
        const std::string b = featureStarting(*unculled, "shadow-maps:");
        std::printf("culled: %s; unculled: %s\n", a.c_str(), b.c_str());
        EXPECT_NE(a, b) << "culling should leave some caster out of some map";
        EXPECT_EQ(render(scene, o).rgba, render(scene, all).rgba);
    }
}

// A sphere 1 above a plane under a light with a size: the exact shadow has a penumbra as wide
// as similar triangles make it. PCSS draws it; PCF's fixed 3 x 3 texels do not. Measured as
// the RMSE over the plane against the area light's reference, and as the share of plane
// pixels inside the penumbra (between a tenth and nine tenths of the full fall).
struct SoftCase {
    const char* name;
    LightType type;
    glm::dvec3 position;
};

Scene softScene(const SoftCase& c, bool castShadows) {
    LitScene s;
    s.objects.push_back({tessellate(AnalyticShape::plane(0, 6.0), 8), matte(), glm::dmat4(1.0)});
    s.objects.push_back({tessellate(AnalyticShape::sphere(1, 0.5), 96), matte(),
                         glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 1))});
    Light l = test::makeLight(c.type);
    l.ambient = {0.1, 0.1, 0.1};
    l.castShadows = castShadows;
    s.lights.push_back({l, c.type == LightType::Directional
                               ? test::aimed(glm::dvec3(0.0), -glm::normalize(glm::dvec3(0.3, 0.0, 1.0)))
                               : test::translation(c.position)});
    s.projection = Projection::makeOrtho(-3, 3, -3, 3, 1.0, 10.0);
    s.lookAt = LookAt{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
    return s.build();
}

struct SoftMeasure {
    double rmse = 0.0;
    int penumbra = 0;
};

SoftMeasure measureSoft(const Image& shadowed, const Image& lit, const References& ref) {
    SoftMeasure m;
    const int n = shadowed.width;
    float fall = 0.0f;
    for (int i = 0; i < n * n; ++i)
        fall = std::max(fall, ref.lit.centre.rgba[4 * i + 1] - ref.shadowed.centre.rgba[4 * i + 1]);
    double sum = 0.0;
    int count = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double px = -3.0 + 6.0 * (x + 0.5) / n, py = 3.0 - 6.0 * (y + 0.5) / n;
            if (px * px + py * py <= 0.3 || !ref.lit.interior[std::size_t(y) * n + x]) continue;
            const double d = double(shadowed.pixel(x, y)[1]) - ref.shadowed.centre.pixel(x, y)[1];
            sum += d * d;
            ++count;
            const float f = (lit.pixel(x, y)[1] - shadowed.pixel(x, y)[1]) / fall;
            m.penumbra += f > 0.1f && f < 0.9f;
        }
    m.rmse = std::sqrt(sum / std::max(count, 1));
    return m;
}

TEST_F(ShadowCascades, PcssDrawsTheAreaLightsPenumbra) {
    const SoftCase cases[] = {{"point light, radius 0.3", LightType::Point, {0.5, 0.0, 3.5}},
                              {"spot light, radius 0.3", LightType::Spot, {0.5, 0.0, 3.5}},
                              {"directional light, angular radius 8 degrees", LightType::Directional, {}}};
    for (const SoftCase& c : cases) {
        SCOPED_TRACE(c.name);
        RenderOptions o = test::optionsFor(96, 96, ShadingMode::Phong);
        o.shadows.resolution = 1024;
        o.shadows.lightRadius = 0.3;
        o.shadows.sunRadius = 8.0;
        Scene shadowedScene = softScene(c, true), litScene = softScene(c, false);
        if (c.type == LightType::Spot)
            for (Scene* s : {&shadowedScene, &litScene}) s->lights[0].spotCutoffDeg = 50.0;
        RenderOptions soft = o;
        soft.shadows.filter = ShadowFilter::Pcss;
        soft.shadows.kernel = 7;
        const References ref = references(shadowedScene, litScene, soft, {AnalyticShape::plane(0, 6.0), AnalyticShape::sphere(1, 0.5)});
        const Image lit = render(litScene, o);
        const SoftMeasure exact = measureSoft(ref.shadowed.centre, ref.lit.centre, ref);
        const SoftMeasure pcf = measureSoft(render(shadowedScene, o), lit, ref);
        const Image pcssImage = render(shadowedScene, soft);
        const SoftMeasure pcss = measureSoft(pcssImage, lit, ref);

        std::printf("%s: penumbra pixels exact %d, pcf %d, pcss %d; RMSE pcf %.4f, pcss %.4f\n",
                    c.name, exact.penumbra, pcf.penumbra, pcss.penumbra, pcf.rmse, pcss.rmse);
        EXPECT_GT(exact.penumbra, 80) << "the light's size should make a wide penumbra";
        EXPECT_LT(pcss.rmse, 0.85 * pcf.rmse) << "PCSS should follow the area light's shadow";
        EXPECT_GT(pcss.penumbra, 3 * pcf.penumbra) << "PCSS's penumbra should be far wider than PCF's";
        EXPECT_GT(pcss.penumbra, exact.penumbra / 2);
        EXPECT_LT(pcss.penumbra, exact.penumbra * 2);
    }
}

// A sphere whose mask removes it everywhere (alpha 0.2 under a cutoff of 0.5, no texture) is
// not drawn, so it casts no shadow either: the plane is as bright as without shadows, as the
// reference's shadow rays pass through it.
TEST_F(ShadowCascades, AMaskedAwayCasterCastsNothing) {
    const SoftCase c{"point light", LightType::Point, {0.5, 0.0, 3.5}};
    Scene shadowed = softScene(c, true), lit = softScene(c, false);
    for (Scene* s : {&shadowed, &lit}) {
        Material& m = s->materials.back();
        m.alphaMode = AlphaMode::Mask;
        m.alphaCutoff = 0.5;
        m.front.diffuse.a = 0.2;
    }
    const RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    const Image a = render(shadowed, o), b = render(lit, o);
    double largest = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) largest = std::max(largest, double(std::abs(a.rgba[i] - b.rgba[i])));
    EXPECT_LT(largest, 1e-6);
    // The same sphere opaque does shadow the plane.
    for (Scene* s : {&shadowed, &lit}) s->materials.back().alphaMode = AlphaMode::Opaque;
    const Image c2 = render(shadowed, o), d2 = render(lit, o);
    int darker = 0;
    for (std::size_t i = 1; i < c2.rgba.size(); i += 4) darker += c2.rgba[i] < d2.rgba[i] - 0.05f;
    EXPECT_GT(darker, 50);
}

} // namespace
