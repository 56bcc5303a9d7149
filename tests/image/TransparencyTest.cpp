// Exact and weighted transparency (gpu/Transparency.h, shaders/include/oit.glsl) against the
// reference's exact composite (lantern/Reference.h): crossing blended squares, nested
// blended spheres and a torus overlapping itself, where sorting by object is wrong inside the
// picture. Exact matches the
// reference to the shading's own error; the composite does not depend on the order of the
// draws; where sorting by object is right, exact and sorted agree; a frame whose lists
// overflow is rendered again and comes out the same; a scene without blended draws pays
// nothing.
#include "LightingCompare.h"

#include "render/DrawLists.h"
#include "render/FrameRender.h"
#include "render/Variants.h"

#include <gtest/gtest.h>
#include <lantern/Reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

using namespace lantern;
using lantern::test::LitScene;

Material glass(const glm::dvec4& colour) {
    Material m = test::phongMaterial({0.2, 0.2, 0.2}, colour, {0.5, 0.5, 0.5}, 30.0);
    m.alphaMode = AlphaMode::Blend;
    m.doubleSided = true;
    return m;
}

struct Layered {
    Scene scene;
    std::vector<AnalyticShape> shapes;
};

// Object i is mesh i (LitScene::build); `reversed` lists the same objects in the other order.
Layered build(std::vector<LitScene::Object> objects, std::vector<AnalyticShape> shapes,
              const glm::dvec3& eye, bool reversed) {
    if (reversed) {
        std::reverse(objects.begin(), objects.end());
        std::reverse(shapes.begin(), shapes.end());
    }
    for (std::size_t i = 0; i < shapes.size(); ++i) shapes[i].mesh = int(i);
    LitScene s;
    s.objects = std::move(objects);
    Light l = test::makeLight(LightType::Point);
    l.ambient = {0.1, 0.1, 0.1};
    s.lights.push_back({l, test::translation({2.0, 2.0, 4.0})});
    s.lookAt = LookAt{eye, {0, 0, 0}, {0, 1, 0}};
    return {s.build(), std::move(shapes)};
}

// Two blended 2 x 2 squares turned +-0.6 rad about Y through the origin (the bench's T1).
Layered crossing(bool reversed = false) {
    const glm::dvec3 up(0, 1, 0);
    const AnalyticShape square = AnalyticShape::plane(0, 2.0);
    return build({{tessellate(square, 1), glass({0.9, 0.2, 0.1, 0.5}), glm::rotate(glm::dmat4(1.0), 0.6, up)},
                  {tessellate(square, 1), glass({0.1, 0.3, 0.9, 0.5}), glm::rotate(glm::dmat4(1.0), -0.6, up)}},
                 {square, square}, {0.0, 0.6, 4.0}, reversed);
}

// An opaque sphere inside blended spheres of radius 0.7 and 1 (the bench's T2).
Layered nested(bool reversed = false) {
    const AnalyticShape outer = AnalyticShape::sphere(0, 1.0), middle = AnalyticShape::sphere(0, 0.7),
                        core = AnalyticShape::sphere(0, 0.4);
    Material opaque = test::phongMaterial({0.2, 0.2, 0.2}, {0.8, 0.2, 0.2, 1.0}, {0.5, 0.5, 0.5}, 30.0);
    return build({{tessellate(outer, 64), glass({0.6, 0.8, 0.9, 0.3}), glm::dmat4(1.0)},
                  {tessellate(middle, 64), glass({0.9, 0.7, 0.2, 0.5}), glm::dmat4(1.0)},
                  {tessellate(core, 64), opaque, glm::dmat4(1.0)}},
                 {outer, middle, core}, {0.0, 0.0, 4.0}, reversed);
}

// One blended torus tilted towards the eye, overlapping itself (the bench's T4): its triangles
// are one draw, drawn in index order, which no sort by object can put in depth order.
Layered torus(bool reversed = false) {
    const AnalyticShape ring = AnalyticShape::torus(0, 1.0, 0.35);
    return build({{tessellate(ring, 128), glass({0.3, 0.6, 0.9, 0.5}), glm::rotate(glm::dmat4(1.0), -1.1, glm::dvec3(1, 0, 0))}},
                 {ring}, {0.0, 0.6, 4.0}, reversed);
}

RenderOptions options(TransparencyMethod method, int msaa = 1) {
    RenderOptions o;
    o.width = 96;
    o.height = 96;
    o.msaa = msaa;
    o.shading = ShadingMode::Phong;
    o.transparency = method;
    return o;
}

class Transparency : public test::RenderTest {
protected:
    // Interior RMSE against the exact composite (and the pixels it covers).
    ErrorMetrics error(const Layered& l, const RenderOptions& o) {
        ReferenceOptions r;
        r.shapes = l.shapes;
        r.boxSamples = 2;
        auto ref = raycastReference(l.scene, o, 0.0, r);
        EXPECT_TRUE(ref) << ref.error().describe();
        if (!ref) return {};
        auto m = measureError(render(l.scene, o), *ref);
        EXPECT_TRUE(m) << m.error().describe();
        return m ? *m : ErrorMetrics{};
    }
};

bool identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgba.size() == b.rgba.size() &&
           std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

TEST_F(Transparency, ExactMatchesTheExactCompositeWhereSortingByObjectCannot) {
    for (const auto& [name, scene] :
         {std::pair{"crossing", crossing()}, std::pair{"nested", nested()}, std::pair{"torus", torus()}}) {
        SCOPED_TRACE(name);
        const ErrorMetrics exact = error(scene, options(TransparencyMethod::Exact));
        const ErrorMetrics sorted = error(scene, options(TransparencyMethod::Sorted));
        const ErrorMetrics weighted = error(scene, options(TransparencyMethod::Weighted));
        std::printf("%s interior RMSE (pixels %zu): exact %.3g, sorted %.3g, weighted %.3g\n", name,
                    exact.interior.pixels, exact.interior.rmse, sorted.interior.rmse,
                    weighted.interior.rmse);
        ASSERT_GT(exact.interior.pixels, 1000u);
        // The shading's own error (phong on a tessellated sphere), not the order's.
        EXPECT_LT(exact.interior.rmse, 2e-3);
        EXPECT_GT(sorted.interior.rmse, 10.0 * exact.interior.rmse);
        EXPECT_EQ(exact.nonFinite + weighted.nonFinite, 0u);
        // Weighted is an approximation: bounded, never exact here.
        EXPECT_LT(weighted.interior.rmse, 0.25);
        EXPECT_GT(weighted.interior.rmse, 2.0 * exact.interior.rmse);
    }
}

TEST_F(Transparency, ExactWithMultisamplingMatchesInsideSurfaces) {
    for (const auto& [name, scene] : {std::pair{"crossing", crossing()}, std::pair{"nested", nested()}}) {
        SCOPED_TRACE(name);
        const ErrorMetrics m = error(scene, options(TransparencyMethod::Exact, 4));
        std::printf("%s, 4x MSAA: exact interior RMSE %.3g (pixels %zu)\n", name, m.interior.rmse,
                    m.interior.pixels);
        ASSERT_GT(m.interior.pixels, 1000u);
        // The flat squares: the order alone (2.97e-5 measured). The spheres add MSAA's own
        // shading error: a fragment that covers part of a pixel is lit at its samples'
        // centroid, not the centre the reference samples (2.5e-3 measured at 64 segments).
        EXPECT_LT(m.interior.rmse, std::string(name) == "crossing" ? 2e-4 : 5e-3);
    }
}

// The lists are sorted per pixel with ties broken by content: the picture does not depend on
// the order the scene lists its objects in, nor on the order the GPU stored the fragments.
TEST_F(Transparency, ExactDoesNotDependOnTheOrderOfTheDraws) {
    for (int msaa : {1, 4}) {
        SCOPED_TRACE(msaa);
        const Image a = render(nested().scene, options(TransparencyMethod::Exact, msaa));
        const Image b = render(nested(true).scene, options(TransparencyMethod::Exact, msaa));
        const Image c = render(nested().scene, options(TransparencyMethod::Exact, msaa));
        EXPECT_TRUE(identical(a, c)) << "two renders of one scene differ";
        EXPECT_TRUE(identical(a, b)) << "the scene's order changed the picture";
    }
}

// One blended square in front of an opaque sphere: far to near by object is right here, so
// exact and sorted composite the same thing (colour and alpha, over a transparent background).
TEST_F(Transparency, ExactAgreesWithSortingWhereSortingIsRight) {
    const AnalyticShape square = AnalyticShape::plane(0, 1.5), ball = AnalyticShape::sphere(0, 0.6);
    Material opaque = test::phongMaterial({0.2, 0.2, 0.2}, {0.2, 0.8, 0.3, 1.0}, {0.5, 0.5, 0.5}, 30.0);
    const Layered l = build({{tessellate(square, 1), glass({0.9, 0.6, 0.1, 0.4}), test::translation({0, 0, 1.2})},
                             {tessellate(ball, 48), opaque, glm::dmat4(1.0)}},
                            {square, ball}, {0.0, 0.0, 4.0}, false);
    const Image exact = render(l.scene, options(TransparencyMethod::Exact));
    const Image sorted = render(l.scene, options(TransparencyMethod::Sorted));
    ASSERT_EQ(exact.rgba.size(), sorted.rgba.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < exact.rgba.size(); ++i)
        worst = std::max(worst, double(std::abs(exact.rgba[i] - sorted.rgba[i])));
    EXPECT_LT(worst, 1e-6);
}

// A renderer whose first lists hold 64 nodes: the frame overflows, is rendered again with
// room for every fragment, and equals a render that never overflowed.
TEST_F(Transparency, AFrameThatOverflowsItsListsIsRenderedAgainWhole) {
    const Image expected = render(nested().scene, options(TransparencyMethod::Exact));
    ASSERT_EQ(setenv("LANTERN_TEST_FRAGMENT_LIST_NODES", "64", 1), 0);
    RendererDesc desc;
    desc.validation = true;
    auto small = Renderer::create(desc);
    unsetenv("LANTERN_TEST_FRAGMENT_LIST_NODES");
    ASSERT_TRUE(small) << small.error().describe();
    auto image = small->render(nested().scene, options(TransparencyMethod::Exact), 0.0);
    ASSERT_TRUE(image) << image.error().describe();
    EXPECT_TRUE(identical(*image, expected));
}

// 40 blended squares one behind the other: each pixel composites its nearest
// LANTERN_OIT_MAX_LAYERS, and the frame counts the pixels that had more.
TEST_F(Transparency, APixelWithMoreLayersThanTheLimitKeepsItsNearest) {
    std::vector<LitScene::Object> objects;
    std::vector<AnalyticShape> shapes;
    for (int i = 0; i < 40; ++i) {
        Material m;
        m.unlit = true;
        m.front.diffuse = {0.5, 0.25, 1.0, 0.2};
        m.alphaMode = AlphaMode::Blend;
        objects.push_back({tessellate(AnalyticShape::plane(0, 3.0), 1), m, test::translation({0, 0, -0.02 * i})});
        shapes.push_back(AnalyticShape::plane(0, 3.0));
    }
    const Layered l = build(objects, shapes, {0.0, 0.0, 4.0}, false);
    auto f = test::renderWithIds(device(), l.scene, options(TransparencyMethod::Exact));
    ASSERT_TRUE(f) << f.error().describe();
    EXPECT_GT(f->readback.listTruncatedPixels, 1000u);
    EXPECT_GE(f->readback.listFragments, 40u * f->readback.listTruncatedPixels);
    const float* centre = f->readback.image.pixel(48, 48);
    const double covered = 1.0 - std::pow(0.8, LANTERN_OIT_MAX_LAYERS);
    EXPECT_NEAR(centre[0], 0.5 * covered, 1e-5);
    EXPECT_NEAR(centre[2], 1.0 * covered, 1e-5);
    EXPECT_NEAR(centre[3], 1.0, 1e-6);  // over the default background, opaque black
}

// Without blended draws the frame is the same whatever the method: same variants, no pass.
TEST_F(Transparency, ASceneWithoutBlendedDrawsPaysNothing) {
    LitScene s;
    s.objects.push_back({tessellate(AnalyticShape::sphere(0, 0.8), 32),
                         test::phongMaterial({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8, 1.0}, {0.5, 0.5, 0.5}, 30.0),
                         glm::dmat4(1.0)});
    const Scene scene = s.build();
    std::vector<gpu::PipelineKey> keys[3];
    int i = 0;
    for (TransparencyMethod m : {TransparencyMethod::Sorted, TransparencyMethod::Exact, TransparencyMethod::Weighted}) {
        auto planned = render::planFrame(scene, options(m), 0.0);
        ASSERT_TRUE(planned) << planned.error().describe();
        EXPECT_EQ(planned->list.target.transparency, TransparencyMethod::Sorted);
        for (const auto& d : planned->list.views[0].draws) keys[i].push_back(d.pipeline);
        ++i;
    }
    EXPECT_EQ(keys[0], keys[1]);
    EXPECT_EQ(keys[0], keys[2]);
    const Image a = render(scene, options(TransparencyMethod::Sorted));
    EXPECT_TRUE(identical(a, render(scene, options(TransparencyMethod::Exact))));
    EXPECT_TRUE(identical(a, render(scene, options(TransparencyMethod::Weighted))));
}

// The default: exact, except under GL compatibility, where blended objects are sorted as GL
// programs sort them.
TEST_F(Transparency, TheDefaultIsExactAndSortedUnderGlCompatibility) {
    RenderOptions o;
    EXPECT_EQ(render::effectiveTransparency(o), TransparencyMethod::Exact);
    o.glCompat = true;
    EXPECT_EQ(render::effectiveTransparency(o), TransparencyMethod::Sorted);
    o.transparency = TransparencyMethod::Weighted;
    EXPECT_EQ(render::effectiveTransparency(o), TransparencyMethod::Weighted);
}

// The blended surfaces keep writing the AOV planes under every method, as sorted ones do
// (with MSAA from the AOV pass, without in the scene pass itself).
TEST_F(Transparency, AovPlanesAreTheSameUnderEveryMethod) {
    for (int msaa : {1, 4}) {
        SCOPED_TRACE(msaa);
        std::vector<Image> images;
        for (TransparencyMethod m : {TransparencyMethod::Sorted, TransparencyMethod::Exact, TransparencyMethod::Weighted}) {
            RenderOptions o = options(m, msaa);
            o.aovs.depth = true;
            o.aovs.primitive = true;
            images.push_back(render(crossing().scene, o));
        }
        for (std::size_t k = 1; k < images.size(); ++k) {
            EXPECT_EQ(images[0].depth, images[k].depth) << k;
            EXPECT_EQ(images[0].mesh, images[k].mesh) << k;
        }
        std::size_t drawn = 0;
        for (std::uint32_t id : images[0].mesh) drawn += id != kNoId;
        EXPECT_GT(drawn, 1000u);
    }
}

} // namespace
