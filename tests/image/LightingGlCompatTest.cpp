// --gl-compat reproduces OpenGL's fixed-function pipeline: GL_FLAT takes the colour lit at the
// provoking (last) vertex, lit colours are clamped to [0, 1] per vertex before interpolation,
// shininess and spot exponent are limited to [0, 128], and a scene that does not choose a
// shading mode is shaded per vertex (GL_SMOOTH). Each case compares every pixel with the
// reference and checks that the GL rule really changed the picture.
#include "LightingCompare.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

constexpr double kStep = 1.0 / 255.0;

Scene litSphere(double lightStrength, double shininess = 20.0, double spotExponent = 0.0) {
    LitScene s;
    const Material m =
        test::phongMaterial({0.1, 0.1, 0.1}, {0.7, 0.5, 0.3, 1.0}, {0.4, 0.4, 0.4}, shininess);
    s.objects.push_back({makeSphere(1.0, 12, 6), m, glm::dmat4(1.0)});
    Light l = test::makeLight(spotExponent > 0.0 ? LightType::Spot : LightType::Point);
    l.diffuse = l.specular = glm::dvec3(lightStrength);
    l.spotCutoffDeg = spotExponent > 0.0 ? 40.0 : 180.0;
    l.spotExponent = spotExponent;
    s.lights.push_back({l, test::aimed({1.0, 1.5, 3.0}, {-1.0, -1.5, -3.0})});
    return s.build();
}

// Pixels whose colours differ by more than two 8-bit steps in some channel.
std::size_t differing(const Image& a, const Image& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixelCount(); ++i)
        for (int k = 0; k < 3; ++k)
            if (std::abs(a.rgba[i * 4 + k] - b.rgba[i * 4 + k]) > 2.0 * kStep) {
                ++n;
                break;
            }
    return n;
}

class LightingGlCompat : public GpuTest {
protected:
    test::ReferenceComparison compare(const Scene& scene, const RenderOptions& o,
                                      const std::string& name) {
        test::ReferenceComparison c = test::compareWithReference(device(), scene, o);
        EXPECT_EQ(c.frame.readback.nonFinite, 0u) << name;
        EXPECT_GT(c.compared, 500u) << name;
        EXPECT_LE(c.worst, kStep) << name << ": " << c.describe(name);
        return c;
    }
    Image plain(const Scene& scene, const RenderOptions& o) {
        auto img = renderer().render(scene, o, 0.0);
        EXPECT_TRUE(img) << img.error().describe();
        return img ? *img : Image(o.width, o.height);
    }
};

// GL_FLAT: the whole triangle has the (clamped) colour lit at its last vertex.
TEST_F(LightingGlCompat, FlatTakesTheProvokingVertexColor) {
    const Scene scene = litSphere(1.0);
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Flat);
    o.glCompat = true;
    const test::ReferenceComparison c = compare(scene, o, "gl_flat");
    ASSERT_EQ(c.frame.frame.lighting.program, frame::Program::GlFlat);
    // The rule matters: the first vertex's colour, or Lantern's centroid, would differ.
    const frame::Draw& d = c.frame.frame.views[0].draws[0];
    const auto lights =
        frame::placeLights(scene, c.frame.frame.pose, c.frame.frame.views[0].camera.viewFromWorld, true);
    const Primitive& p = scene.meshes[0].primitives[0];
    std::size_t unlikeFirst = 0, lit = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const ProbeReport& r = c.at(x, y);
            if (!r.hit) continue;
            ++lit;
            EXPECT_EQ(r.evaluations.size(), 1u);
            EXPECT_EQ(r.evaluations[0].where, "provoking vertex " + std::to_string(r.vertices[2]));
            const std::uint32_t v0 = r.vertices[0];
            const glm::dvec3 eye(d.viewFromModel * glm::dvec4(glm::dvec3(p.positions[v0]), 1.0));
            const glm::dvec3 n =
                ref::safeNormalize(normalMatrix(d.viewFromModel) * glm::dvec3(p.normals[v0]));
            const glm::dvec3 first = glm::clamp(
                ref::shade(eye, n, scene.materials[0].front, lights, ref::Settings{}), 0.0, 1.0);
            const float* px = c.pixel(x, y);
            for (int k = 0; k < 3; ++k)
                if (std::abs(px[k] - first[k]) > 2.0 * kStep) {
                    ++unlikeFirst;
                    break;
                }
        }
    EXPECT_GT(unlikeFirst, lit / 4) << "the first vertex's colour must differ on many pixels";
    RenderOptions lantern = o;
    lantern.glCompat = false;
    EXPECT_GT(differing(c.frame.readback.image, plain(scene, lantern)), 200u)
        << "Lantern's flat (centroid)";
}

// Lit colours clamp to [0, 1] at each vertex, before interpolation: a bright light gives a
// different picture from clamping the interpolated colour (--clamp).
TEST_F(LightingGlCompat, GouraudClampsEachVertexColor) {
    const Scene scene = litSphere(3.0);
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Gouraud);
    o.glCompat = true;
    const test::ReferenceComparison c = compare(scene, o, "gl_gouraud");
    EXPECT_LE(test::brightestColour(c.frame.readback.image), 1.0f);
    RenderOptions clampAfter = o;
    clampAfter.glCompat = false;
    clampAfter.clamp = true;
    EXPECT_GT(differing(c.frame.readback.image, plain(scene, clampAfter)), 100u);
}

// Shininess 1000 and spot exponent 500 are limited to GL's 128.
TEST_F(LightingGlCompat, ShininessAndSpotExponentLimitedTo128) {
    const Scene scene = litSphere(0.5, 1000.0, 500.0);
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    o.glCompat = true;
    const test::ReferenceComparison c = compare(scene, o, "gl_limits");
    bool sawLimit = false;
    for (const ProbeReport& r : c.reports)
        if (r.hit) {
            EXPECT_EQ(r.materialSide.shininess, 128.0);
            sawLimit = true;
        }
    EXPECT_TRUE(sawLimit);
    const auto lights =
        frame::placeLights(scene, c.frame.frame.pose, c.frame.frame.views[0].camera.viewFromWorld, true);
    EXPECT_EQ(lights[0].exponent, 128.0);
    EXPECT_EQ(c.frame.frame.views[0].lights[0].exponent, 128.0);
    EXPECT_EQ(c.frame.frame.materials[0].front.shininess, 128.0);
    // And as packed for the GPU.
    auto plan = render::planFrame(scene, o, 0.0);
    ASSERT_TRUE(plan);
    EXPECT_EQ(plan->list.views[0].lights[0].spot.x, 128.0f);
    EXPECT_EQ(plan->list.materials[0].front.specular.w, 128.0f);
    RenderOptions unlimited = o;
    unlimited.glCompat = false;
    EXPECT_GT(differing(c.frame.readback.image, plain(scene, unlimited)), 50u);
}

// GL's default is GL_SMOOTH: with --gl-compat a scene that chooses no shading is gouraud; an
// explicit choice (option or LANTERN_lighting) is kept.
TEST(LightingGlCompatPlan, DefaultShadingIsGouraudUnlessChosen) {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 8, 4), Material{}, glm::dmat4(1.0)});
    s.lighting.reset();
    const Scene unchosen = s.build();
    s.lighting = LightingModel{};
    const Scene chosen = s.build();
    RenderOptions o;
    o.glCompat = true;
    EXPECT_EQ(frame::resolveLighting(unchosen, -1, o).program, frame::Program::Gouraud);
    EXPECT_EQ(frame::resolveLighting(chosen, -1, o).program, frame::Program::Phong);
    o.shading = ShadingMode::Flat;
    EXPECT_EQ(frame::resolveLighting(unchosen, -1, o).program, frame::Program::GlFlat);
    o.glCompat = false;
    o.shading.reset();
    EXPECT_EQ(frame::resolveLighting(unchosen, -1, o).program, frame::Program::Phong);
}

} // namespace
