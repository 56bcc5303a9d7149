// Shadow maps (frame/Shadows.cpp, gpu/Shadows.cpp, shaders/include/shadows.glsl) against the
// reference's exact shadow rays (lantern/Reference.h): a sphere over a plane, lit by each
// light type, seen from above. A pixel is shadowed where its colour falls well below the same
// picture without shadows; the maps may disagree with the exact shadow only along its edge.
// And a frame without a shadow-casting light compiles the variants it had before.
#include "LightingCompare.h"

#include "render/FrameRender.h"

#include <gtest/gtest.h>
#include <lantern/Reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>

namespace {

using namespace lantern;
using lantern::test::LitScene;

const glm::dvec3 kTowardsLight = glm::normalize(glm::dvec3(1.25, 0.0, 1.0));

glm::dmat4 aimed(const glm::dvec3& position, const glm::dvec3& direction) {
    const glm::dvec3 up = std::abs(direction.y) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::inverse(glm::lookAt(position, position + direction, up));
}

Material matte() {
    return test::phongMaterial({0.3, 0.2, 0.1}, {0.6, 0.7, 0.8, 1.0}, {0.3, 0.3, 0.3}, 20.0);
}

// The plane (4 x 4 at z = 0) and the sphere (radius 0.5 at (0, 0, 1)) under an orthographic
// camera looking down -Z over [-2, 2]^2, lit by one light of `type` whose shadow falls around
// (-1.25, 0, 0).
Scene sphereOverPlane(LightType type, bool castShadows) {
    LitScene s;
    s.objects.push_back({tessellate(AnalyticShape::plane(0, 4.0), 8), matte(), glm::dmat4(1.0)});
    s.objects.push_back({tessellate(AnalyticShape::sphere(1, 0.5), 96), matte(),
                         glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 1))});
    Light l = test::makeLight(type);
    l.ambient = {0.1, 0.1, 0.1};
    l.castShadows = castShadows;
    if (type == LightType::Spot) l.spotCutoffDeg = 60.0;
    const glm::dvec3 position = glm::dvec3(-1.25, 0.0, 0.0) + 2.4 * glm::dvec3(1.25, 0.0, 1.0);
    s.lights.push_back({l, aimed(type == LightType::Directional ? glm::dvec3(0.0) : position, -kTowardsLight)});
    s.projection = Projection::makeOrtho(-2, 2, -2, 2, 1.0, 10.0);
    s.lookAt = LookAt{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
    return s.build();
}

class ShadowMaps : public test::RenderTest {};

// Pixels of the plane (outside the sphere's disc) whose shadowed state the maps get wrong,
// and how many the exact shadow covers.
struct ShadowCount {
    int wrong = 0, shadowed = 0, plane = 0;
};

ShadowCount compareShadows(const Image& lit, const Image& shadowed, const ReferenceImage& refLit,
                           const ReferenceImage& refShadowed) {
    ShadowCount c;
    const int n = lit.width;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double px = -2.0 + 4.0 * (x + 0.5) / n, py = 2.0 - 4.0 * (y + 0.5) / n;
            if (px * px + py * py <= 0.3) continue;  // the sphere, seen from above
            ++c.plane;
            const bool exact = refShadowed.centre.pixel(x, y)[1] < 0.8f * refLit.centre.pixel(x, y)[1];
            const bool mapped = shadowed.pixel(x, y)[1] < 0.8f * lit.pixel(x, y)[1];
            c.shadowed += exact;
            c.wrong += exact != mapped;
        }
    return c;
}

TEST_F(ShadowMaps, EveryLightTypeMatchesTheExactShadowOutsideItsEdge) {
    for (LightType type : {LightType::Directional, LightType::Spot, LightType::Point}) {
        for (ShadowFilter filter : {ShadowFilter::Hardware, ShadowFilter::Pcf}) {
            SCOPED_TRACE(std::to_string(int(type)) + (filter == ShadowFilter::Pcf ? " pcf" : " hardware"));
            const Scene scene = sphereOverPlane(type, true);
            RenderOptions o = test::optionsFor(96, 96, ShadingMode::Phong);
            o.shadows.filter = filter;
            o.shadows.resolution = 1024;
            const Image shadowed = render(scene, o);
            const Image lit = render(sphereOverPlane(type, false), o);
            ReferenceOptions r;
            r.shapes = {AnalyticShape::plane(0, 4.0), AnalyticShape::sphere(1, 0.5)};
            r.boxSamples = 1;
            auto refShadowed = raycastReference(scene, o, 0.0, r);
            auto refLit = raycastReference(sphereOverPlane(type, false), o, 0.0, r);
            ASSERT_TRUE(refShadowed && refLit);
            const ShadowCount c = compareShadows(lit, shadowed, *refLit, *refShadowed);
            std::printf("light %d, %s: %d of %d plane pixels wrong, %d in the exact shadow\n", int(type),
                        filter == ShadowFilter::Pcf ? "pcf 3x3" : "hardware", c.wrong, c.plane, c.shadowed);
            EXPECT_GT(c.shadowed, 100) << "the exact shadow covers too little to test";
            // The shadow's edge is about 2 x 60 pixels long; at most one pixel across it may
            // differ (the maps' texels and PCF's blur).
            EXPECT_LT(c.wrong, c.plane / 50) << c.wrong << " of " << c.plane << " plane pixels";
        }
    }
}

// The probe names, per light, whether the pixel is shadowed and by which node (the
// reference's exact shadow ray), and its colour then includes the shadow as the render does.
TEST_F(ShadowMaps, TheProbeNamesTheShadowAndWhatCastsIt) {
    const Scene scene = sphereOverPlane(LightType::Point, true);
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    // (-1.25, 0) is pixel (12, 32): inside the shadow; (56, 8) in the light.
    auto inside = renderer().probe(scene, o, 0.0, 12, 32);
    ASSERT_TRUE(inside) << inside.error().describe();
    ASSERT_TRUE(inside->hit);
    ASSERT_EQ(inside->evaluations.size(), 1u);
    ASSERT_EQ(inside->evaluations[0].lights.size(), 1u);
    const ProbeLight& l = inside->evaluations[0].lights[0];
    EXPECT_TRUE(l.castsShadows);
    EXPECT_EQ(l.visibility, 0.0);
    EXPECT_EQ(l.occluderName, "object 1");
    EXPECT_EQ(l.diffuse, glm::dvec3(0.0));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(inside->colour[k], inside->pixel[k], 1e-4) << k;
    auto outside = renderer().probe(scene, o, 0.0, 56, 8);
    ASSERT_TRUE(outside && outside->hit);
    EXPECT_EQ(outside->evaluations[0].lights[0].visibility, 1.0);
    EXPECT_EQ(outside->evaluations[0].lights[0].occluderNode, -1);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(outside->colour[k], outside->pixel[k], 1e-4) << k;
}

// 64 point lights at 16384 texels would be 384 GiB of maps: refused before anything is
// allocated, naming the option, and the renderer goes on rendering.
TEST_F(ShadowMaps, MapsTheDeviceCannotHoldAreRefusedBeforeAllocating) {
    Scene scene = sphereOverPlane(LightType::Point, true);
    for (int i = 0; i < 63; ++i) {
        scene.lights.push_back(scene.lights[0]);
        Node n;
        n.light = int(scene.lights.size()) - 1;
        n.translation = {0.05 * i - 1.5, 0.0, 3.0};
        scene.roots[0].nodes.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(n);
    }
    RenderOptions o = test::optionsFor(32, 32, ShadingMode::Phong);
    o.shadows.resolution = 16384;
    auto refused = renderer().render(scene, o, 0.0);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::OutOfMemory);
    EXPECT_EQ(refused.error().object, "--shadow-resolution") << refused.error().describe();
    EXPECT_NE(refused.error().describe().find("384 shadow maps of 16384x16384"), std::string::npos)
        << refused.error().describe();
    o.shadows.resolution = 64;
    auto image = renderer().render(scene, o, 0.0);
    EXPECT_TRUE(image) << image.error().describe();
}

TEST_F(ShadowMaps, AFrameWithoutThemKeepsItsVariantsAndPicture) {
    const Scene scene = sphereOverPlane(LightType::Point, false);
    const RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    auto plain = render::explain(scene, o, 0.0);
    ASSERT_TRUE(plain);
    for (const std::string& v : plain->variants) EXPECT_EQ(v.find("shadows"), std::string::npos) << v;
    RenderOptions all = o;
    all.shadows.all = true;
    auto shadowed = render::explain(scene, all, 0.0);
    ASSERT_TRUE(shadowed);
    bool any = false;
    for (const std::string& v : shadowed->variants) any |= v.find("shadows=pcf") != std::string::npos;
    EXPECT_TRUE(any);
    // The shadow options alone, with no light casting, change nothing.
    RenderOptions tuned = o;
    tuned.shadows.resolution = 64;
    tuned.shadows.kernel = 9;
    EXPECT_EQ(render(scene, o).rgba, render(scene, tuned).rgba);
}

TEST_F(ShadowMaps, GlCompatibilityCastsOnlyWhenAsked) {
    const Scene scene = sphereOverPlane(LightType::Directional, true);
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Gouraud);
    o.glCompat = true;
    auto report = render::explain(scene, o, 0.0);
    ASSERT_TRUE(report);
    for (const std::string& v : report->variants) EXPECT_EQ(v.find("shadows"), std::string::npos) << v;
    o.shadows.all = true;
    report = render::explain(scene, o, 0.0);
    ASSERT_TRUE(report);
    bool any = false;
    for (const std::string& v : report->variants) any |= v.find("shadows") != std::string::npos;
    EXPECT_TRUE(any);
}

TEST_F(ShadowMaps, GouraudAndFlatShadeWhereTheyLight) {
    // Per vertex and per triangle the shadow is sampled where the equation is evaluated: the
    // plane's pixels in the middle of the exact shadow are darker than without it.
    for (ShadingMode mode : {ShadingMode::Gouraud, ShadingMode::Flat}) {
        const Scene lit = sphereOverPlane(LightType::Directional, false);
        Scene scene = sphereOverPlane(LightType::Directional, true);
        scene.meshes[0].primitives[0] = tessellate(AnalyticShape::plane(0, 4.0), 64);
        scene.meshes[0].primitives[0].material = 0;
        Scene plain = lit;
        plain.meshes[0].primitives[0] = scene.meshes[0].primitives[0];
        RenderOptions o = test::optionsFor(64, 64, mode);
        const Image a = render(plain, o), b = render(scene, o);
        // (-1.25, 0) is pixel (12, 32).
        EXPECT_LT(b.pixel(12, 32)[1], 0.6f * a.pixel(12, 32)[1]) << int(mode);
        EXPECT_NEAR(b.pixel(56, 8)[1], a.pixel(56, 8)[1], 1e-5) << "far from the shadow nothing changes";
    }
}

} // namespace
