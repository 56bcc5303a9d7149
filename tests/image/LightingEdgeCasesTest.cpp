// The lighting equation at its numeric extremes (numerics.md section 3.8, LN-1 to LN-14, and
// the edge cases listed in docs/lighting.md): each case renders on the device, counts NaN/Inf at readback (before any
// scrub or clamp), and compares every pixel with the double-precision reference under the
// same interpolation rule, plus the case's own pass criterion.
#include "LightingCompare.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <limits>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

constexpr double kPi = 3.14159265358979323846;
constexpr double kStep = 1.0 / 255.0; // one 8-bit step

const ShadingMode kModes[] = {ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong};

// The angle between two vectors, accurate for tiny angles too (acos is not near 1).
double angleDegrees(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / kPi;
}

std::string modeName(const ::testing::TestParamInfo<ShadingMode>& p) {
    return toString(p.param);
}

class EdgeCases : public GpuTest, public ::testing::WithParamInterface<ShadingMode> {
protected:
    // Renders, checks there was no NaN/Inf at readback and every covered pixel is within
    // `tolerance` of the reference; returns the comparison for the case's own criterion.
    test::ReferenceComparison check(const Scene& scene, RenderOptions o, const std::string& name,
                                    double tolerance = kStep, bool perLight = true) {
        test::PixelCheck pc;
        pc.perLight = perLight;
        test::ReferenceComparison c = test::compareWithReference(device(), scene, o, pc);
        EXPECT_EQ(c.frame.readback.nonFinite, 0u) << name << ": NaN/Inf counted at readback";
        EXPECT_GT(c.compared, 0u) << name;
        EXPECT_LE(c.worst, tolerance) << name << ": " << c.describe(name);
        return c;
    }
};

// LN-1: shininess 0 and a surface seen from behind while lit from the front: n.l > 0 while
// n.h <= 0 on part of it. x^0 = 1, so the specular term is s_m s_i on every lit pixel
// (lavapipe's pow(0, 0) is 0).
TEST_P(EdgeCases, LN1_ZeroShininessGivesFullSpecularWhereverLit) {
    LitScene s;
    Material m = test::phongMaterial({0.1, 0.1, 0.1}, {0.3, 0.3, 0.3, 1.0}, {0.5, 0.4, 0.3}, 0.0);
    m.doubleSided = true;
    // The plane's normal turned to -Z: away from the camera at +Z, towards the light behind.
    s.objects.push_back(
        {makePlane(3.0, 4), m, glm::rotate(glm::dmat4(1.0), kPi, glm::dvec3(0, 1, 0))});
    s.lights.push_back({test::makeLight(LightType::Point), test::translation({0.2, 0.1, -2.0})});
    s.lighting->localViewer = true;
    s.lighting->twoSided = false; // GL's one-sided lighting of the visible back face
    const test::ReferenceComparison c =
        check(s.build(), test::optionsFor(64, 64, GetParam()), "ln1");
    std::size_t lit = 0, darkHalfway = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const ProbeReport& r = c.at(x, y);
            if (!r.hit) continue;
            for (const ProbeEvaluation& e : r.evaluations) {
                ASSERT_EQ(e.lights.size(), 1u);
                if (e.lights[0].nDotL <= 0.0) continue;
                ++lit;
                EXPECT_EQ(e.lights[0].specularTerm, 1.0);
                const glm::dvec3 l = glm::normalize(glm::dvec3(0.2, 0.1, -2.0 - 4.0) - e.position);
                const glm::dvec3 h = glm::normalize(l + glm::normalize(-e.position));
                darkHalfway += glm::dot(e.normal, h) <= 0.0;
            }
        }
    EXPECT_GT(lit, 100u);
    EXPECT_GT(darkHalfway, 0u) << "the case needs points where n.h <= 0";
}

// LN-3: zero-length vertex normals. Phong and gouraud light a zero normal with ambient and
// emission only (no direction, no diffuse or highlight); flat shading never reads vertex
// normals (it uses the face normal). No NaN in any mode.
TEST_P(EdgeCases, LN3_ZeroLengthNormals) {
    for (const bool all : {true, false}) {
        LitScene s;
        Primitive p = makeSphere(1.0, 16, 8);
        for (std::size_t i = 0; i < p.normals.size(); ++i)
            if (all || i % 3 == 0) p.normals[i] = glm::vec3(0.0f);
        Material m;
        m.front.emission = {0.05, 0.0, 0.0};
        m.front.specular = {1, 1, 1};
        m.front.shininess = 10.0;
        s.objects.push_back({p, m, glm::dmat4(1.0)});
        Light l = test::makeLight(LightType::Point);
        l.ambient = {0.1, 0.1, 0.1};
        s.lights.push_back({l, test::translation({1, 1, 3})});
        const std::string name = std::string("ln3_") + (all ? "all" : "some");
        const test::ReferenceComparison c =
            check(s.build(), test::optionsFor(64, 64, GetParam()), name);
        if (!all || GetParam() == ShadingMode::Flat) continue;
        // Ambient and emission only: e + a_m (A + a_i), with a_m = A = 0.2, a_i = 0.1.
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x)
                if (c.at(x, y).hit) {
                    ASSERT_NEAR(c.pixel(x, y)[0], 0.05 + 0.2 * 0.3, 1e-6) << x << "," << y;
                    ASSERT_NEAR(c.pixel(x, y)[1], 0.2 * 0.3, 1e-6) << x << "," << y;
                }
    }
}

// LN-4: zero-area and collinear triangles in front of a quad: no pixels, no NaN.
TEST_P(EdgeCases, LN4_DegenerateTrianglesCoverNoPixel) {
    LitScene s;
    Primitive p = makePlane(2.0, 1);
    const std::uint32_t base = std::uint32_t(p.positions.size());
    const glm::vec3 extra[] = {
        {-1.0f, -0.25f, 0.5f}, {0.0f, 0.125f, 0.5f}, {1.0f, 0.5f, 0.5f}, {0.3f, 0.3f, 0.5f}};
    for (const glm::vec3& v : extra) {
        p.positions.push_back(v);
        p.normals.emplace_back(0.0f, 0.0f, 1.0f);
        p.texcoords.emplace_back(0.0f, 0.0f);
    }
    // Triangle 2: collinear (exactly, in float); triangle 3: two corners the same point.
    p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base + 3, base + 3, base + 1});
    Material m;
    m.doubleSided = true;
    s.objects.push_back({p, m, glm::dmat4(1.0)});
    s.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {0, 0, -1})});
    const test::ReferenceComparison c =
        check(s.build(), test::optionsFor(64, 64, GetParam()), "ln4");
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if (c.at(x, y).hit) {
                EXPECT_LT(c.at(x, y).triangle, 2u) << x << "," << y;
            }
}

// LN-5: distant viewer and a directional light along -Z: l = -v, no halfway vector. The
// sphere faces away from the light (n.l <= 0: no highlight); the double-sided plane shows its
// back (two-sided off: lit with its front normal, n.l = 1 > 0, highlight term 0, not NaN).
TEST_P(EdgeCases, LN5_NoHalfwayVector) {
    for (const bool twoSided : {false, true}) {
        LitScene s;
        Material m;
        m.doubleSided = true;
        m.front.specular = {1, 1, 1};
        m.front.shininess = 10.0;
        s.objects.push_back({makeSphere(0.8, 16, 8), m, test::translation({-1.0, 0, 0})});
        s.objects.push_back({makePlane(1.5, 2), m,
                             test::translation({1.0, 0, 0}) *
                                 glm::rotate(glm::dmat4(1.0), kPi, glm::dvec3(0, 1, 0))});
        // Shines along +Z, towards the camera: the direction towards the light is -Z.
        s.lights.push_back(
            {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {0, 0, 1})});
        // Stated as an option, two-sided lighting decides for the double-sided plane too (off:
        // GL's one-sided lighting of a visible back face).
        RenderOptions o = test::optionsFor(96, 48, GetParam());
        o.twoSided = twoSided;
        const std::string name = std::string("ln5_two_sided_") + (twoSided ? "on" : "off");
        const test::ReferenceComparison c = check(s.build(), o, name);
        std::size_t planeLit = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 96; ++x) {
                const ProbeReport& r = c.at(x, y);
                if (!r.hit) continue;
                for (const ProbeEvaluation& e : r.evaluations) {
                    if (e.lights[0].nDotL <= 0.0) {
                        EXPECT_EQ(e.lights[0].specular, glm::dvec3(0.0));
                    }
                    if (r.mesh == 1 && e.lights[0].nDotL > 0.0) {
                        ++planeLit;
                        EXPECT_EQ(e.lights[0].specularTerm, 0.0);
                    }
                }
            }
        if (!twoSided) {
            EXPECT_GT(planeLit, 50u) << "the plane's back must be lit (n.l > 0, l = -v)";
        }
    }
}

// LN-6: a point light exactly on a vertex with (kc, kl, kq) = (0, 0, 1), spot factor 0 on the
// rest of the surface and a zero diffuse colour: the attenuation is 1/max(0, 1e-30) = 1e30,
// finite (gouraud spreads the huge vertex colour, phong and flat never evaluate at d = 0).
// The camera is the identity, so the vertex and the light coincide exactly in float too.
TEST_P(EdgeCases, LN6_LightExactlyOnAVertex) {
    LitScene s;
    Material m;
    m.front.diffuse = {0, 0, 0, 1};
    m.front.ambient = {0.2, 0.2, 0.2};
    s.objects.push_back({makePlane(2.0, 2), m, test::translation({0, 0, -3})});
    Light l = test::makeLight(LightType::Spot);
    l.attenuation = {0.0, 0.0, 1.0};
    l.ambient = {0.1, 0.1, 0.1};
    l.spotCutoffDeg = 60.0; // from the surface, every other point is 90 degrees off the axis
    s.lights.push_back({l, test::aimed({0, 0, -3}, {0, 0, -1})});
    s.lookAt = {{0, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    const test::ReferenceComparison c =
        check(s.build(), test::optionsFor(64, 64, GetParam()), "ln6");
    ASSERT_EQ(c.frame.frame.views[0].camera.viewFromWorld, glm::dmat4(1.0));
    const float brightest = test::brightestColour(c.frame.readback.image);
    if (GetParam() == ShadingMode::Gouraud)
        EXPECT_GT(brightest, 1e20f) << "the vertex on the light is lit with att = 1e30";
    else
        EXPECT_LT(brightest, 1.0f) << "no pixel centre is on the light";
}

// LN-6 (second half): huge coefficients make a light vanish: kq = 1e30 at d = 1e5 gives
// (kq d) d = inf in float, attenuation 0, never NaN.
TEST_P(EdgeCases, LN6_HugeAttenuationCoefficients) {
    LitScene s;
    const Material m = test::phongMaterial({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8, 1}, {1, 1, 1}, 5.0);
    s.objects.push_back({makeSphere(1.0, 16, 8), m, glm::dmat4(1.0)});
    Light l = test::makeLight(LightType::Point);
    l.attenuation = {0.0, 0.0, 1e30};
    l.ambient = {1, 1, 1};
    s.lights.push_back({l, test::translation({0, 0, 1e5})});
    const test::ReferenceComparison c =
        check(s.build(), test::optionsFor(64, 64, GetParam()), "ln6_huge");
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if (c.at(x, y).hit) {
                ASSERT_NEAR(c.pixel(x, y)[0], 0.2 * 0.2, 1e-6) << "global ambient only";
            }
}

// Spot cutoff 180 is no cone at all: the same picture as a point light.
TEST_P(EdgeCases, SpotCutoff180IsAPointLight) {
    auto build = [](LightType type) {
        LitScene s;
        Material m;
        m.front.specular = {0.5, 0.5, 0.5};
        m.front.shininess = 16.0;
        s.objects.push_back({makeSphere(1.0, 16, 8), m, glm::dmat4(1.0)});
        Light l = test::makeLight(type);
        l.spotCutoffDeg = 180.0;
        l.spotExponent = 50.0; // ignored without a cone, as in GL
        l.attenuation = {1.0, 0.1, 0.0};
        s.lights.push_back({l, test::aimed({1, 1, 3}, {0, 0, -1})});
        return s.build();
    };
    const RenderOptions o = test::optionsFor(64, 64, GetParam());
    check(build(LightType::Spot), o, "cutoff180");
    auto spot = renderer().render(build(LightType::Spot), o, 0.0);
    auto point = renderer().render(build(LightType::Point), o, 0.0);
    ASSERT_TRUE(spot && point);
    EXPECT_EQ(spot->rgba, point->rgba);
}

INSTANTIATE_TEST_SUITE_P(Modes, EdgeCases, ::testing::ValuesIn(kModes), modeName);

class EdgeCasesPhong : public EdgeCases {};

// A plane (side `size`, facing +Z at the origin) under a GL spot, with no ambient light: the
// picture is the spot's diffuse term alone.
LitScene spotOnPlane(double size, double cutoffDeg, double exponent, const glm::dmat4& spotAt) {
    LitScene s;
    Material m;
    m.front.ambient = {0, 0, 0};
    s.objects.push_back({makePlane(size, 2), m, glm::dmat4(1.0)});
    Light l = test::makeLight(LightType::Spot);
    l.spotCutoffDeg = cutoffDeg;
    l.spotExponent = exponent;
    s.lights.push_back({l, spotAt});
    s.lighting->globalAmbient = {0, 0, 0};
    return s;
}

// LN-2: spot exponent 0 (x^0 = 1), cutoff 90: receivers where -l.s = +1e-6 are inside the cone
// (spot = 1), where it is -1e-6 outside (0). An orthographic camera puts pixel-centre rows at
// y = +-0.001 exactly; the spot, 1000 away, points along +Y.
TEST_F(EdgeCasesPhong, LN2_SpotExponentZeroAtTheNinetyDegreeCone) {
    LitScene s = spotOnPlane(4.0, 90.0, 0.0, test::aimed({0, 0, 1000}, {0, 1, 0}));
    s.projection = Projection::makeOrtho(-0.064, 0.064, -0.064, 0.064, 1.0, 20.0);
    s.lookAt = {{0, 0, 10}, {0, 0, 0}, {0, 1, 0}};
    const test::ReferenceComparison c =
        check(s.build(), test::optionsFor(64, 64, ShadingMode::Phong), "ln2");
    for (int x = 0; x < 64; ++x) {
        const ProbeReport& above = c.at(x, 31);
        const ProbeReport& below = c.at(x, 32);
        ASSERT_TRUE(above.hit && below.hit);
        EXPECT_NEAR(above.position.y, 0.001, 1e-12);
        EXPECT_EQ(above.evaluations[0].lights[0].spot, 1.0);
        EXPECT_EQ(below.evaluations[0].lights[0].spot, 0.0);
        EXPECT_NEAR(c.pixel(x, 31)[0], 0.8, 1e-5) << "inside the cone: diffuse 0.8";
        EXPECT_EQ(c.pixel(x, 32)[0], 0.0f) << "outside the cone: black";
    }
}

// Spot cutoff 0: only the axis itself is inside the cone; no pixel centre of an even-sized
// image lies on it, so nothing is lit, and nothing is NaN.
TEST_F(EdgeCasesPhong, SpotCutoffZeroLightsOnlyTheAxis) {
    const LitScene s = spotOnPlane(4.0, 0.0, 0.0, test::aimed({0, 0, 4}, {0, 0, -1}));
    const test::ReferenceComparison c =
        check(s.build(), test::optionsFor(64, 64, ShadingMode::Phong), "cutoff0");
    for (float v : c.frame.readback.image.rgba)
        EXPECT_TRUE(v == 0.0f || v == 1.0f);
}

// A cone of 0.05 degrees with exponent 1e5: 1 - cos(cutoff) = 3.8e-7 is 6 float steps below 1,
// so comparing cosines in float would move the edge by about 8%; lighting.glsl compares
// 1 - cos computed without cancellation. Every pixel farther than 1% from the edge matches.
TEST_F(EdgeCasesPhong, NarrowSpotConeKeepsItsEdge) {
    const double cutoffDeg = 0.05;
    LitScene s = spotOnPlane(1.0, cutoffDeg, 1e5, test::aimed({0, 0, 4}, {0, 0, -1}));
    // The cone's radius is about 20 pixels.
    s.projection =
        Projection::makePerspective(cutoffDeg * kPi / 180.0 * 64.0 / 20.0, 0.0, 0.1, kInfinity);
    test::PixelCheck pc;
    pc.perLight = true;
    const test::ReferenceComparison c = test::compareWithReference(
        device(), s.build(), test::optionsFor(64, 64, ShadingMode::Phong), pc);
    EXPECT_EQ(c.frame.readback.nonFinite, 0u);
    std::size_t inside = 0, compared = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const ProbeReport& r = c.at(x, y);
            ASSERT_TRUE(r.hit);
            const double angle = angleDegrees(r.position, {0, 0, -1});
            if (std::abs(angle / cutoffDeg - 1.0) < 0.01) continue;
            ++compared;
            inside += angle < cutoffDeg;
            EXPECT_NEAR(c.pixel(x, y)[0], r.colour.r, kStep)
                << x << "," << y << " at " << angle << " degrees";
        }
    EXPECT_GT(inside, 500u);
    EXPECT_GT(compared, 3500u);
}

// LN-9: shininess from 0 to 1e6. A plane faces the camera, the light sits at the eye and the
// viewer is local, so n.h = cos(angle off the axis) and the field of view is scaled to keep
// the lobe about ten pixels wide. Specular only: RMSE <= 1e-3, the peak within 0.1% and
// every pixel within 1e-3 of the reference (pow(dot(n, h), s) loses 3% at s = 1e6).
TEST_F(EdgeCasesPhong, LN9_ShininessSweep) {
    for (const double shininess : {0.0, 1.0, 8.0, 128.0, 1e3, 1e4, 1e5, 1e6}) {
        LitScene s;
        const Material m = test::phongMaterial({0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}, shininess);
        s.objects.push_back({makePlane(4.0, 4), m, glm::dmat4(1.0)});
        s.lights.push_back({test::makeLight(LightType::Point), test::translation({0, 0, 4})});
        s.lighting->localViewer = true;
        s.lighting->globalAmbient = {0, 0, 0};
        const double pixelAngle =
            shininess > 0.0 ? std::min(0.2 / std::sqrt(shininess), 0.6 * kPi / 180.0) : 0.01;
        s.projection = Projection::makePerspective(65.0 * pixelAngle, 0.0, 0.1, kInfinity);
        const std::string name = "ln9_s" + std::to_string(shininess);
        test::PixelCheck pc;
        const test::ReferenceComparison c = test::compareWithReference(
            device(), s.build(), test::optionsFor(65, 65, ShadingMode::Phong), pc);
        EXPECT_EQ(c.frame.readback.nonFinite, 0u) << name;
        double sum = 0.0, peakGot = 0.0, peakWant = 0.0;
        for (int y = 0; y < 65; ++y)
            for (int x = 0; x < 65; ++x) {
                const double got = c.pixel(x, y)[0], want = c.at(x, y).colour.r;
                sum += (got - want) * (got - want);
                peakGot = std::max(peakGot, got);
                peakWant = std::max(peakWant, want);
            }
        const double rmse = std::sqrt(sum / (65.0 * 65.0));
        EXPECT_LE(rmse, 1e-3) << name;
        EXPECT_NEAR(peakGot / peakWant, 1.0, 1e-3) << name;
        EXPECT_LE(c.worst, 1e-3) << name << ": " << c.describe(name);
        if (shininess >= 1e3) {
            // The case must test the lobe's shape: pixels between 10% and 90% of the peak.
            std::size_t shoulder = 0;
            for (int x = 0; x < 65; ++x)
                shoulder += c.at(x, 32).colour.r > 0.1 && c.at(x, 32).colour.r < 0.9;
            EXPECT_GE(shoulder, 4u) << name;
        }
    }
}

// LN-11: Phong-n and Blinn-4n highlights on a plane lit by a directional light at incidence
// theta, seen by a local viewer from the mirror direction with a 60 degree field of view, so
// that each pixel is a view direction (image y is across the plane of incidence). At theta = 0
// the two match within 2% of the peak everywhere; at 75 degrees the Blinn lobe is much
// narrower across the plane (about cos 75 times: width ratio < 0.3), which proves the two
// options run different code.
TEST_F(EdgeCasesPhong, LN11_PhongAgainstBlinnTimesFour) {
    const int size = 192;
    auto render = [&](SpecularModel model, double shininess, double incidenceDeg) {
        LitScene s;
        const Material m = test::phongMaterial({0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}, shininess);
        s.objects.push_back({makePlane(40.0, 8), m, glm::dmat4(1.0)});
        const double a = incidenceDeg * kPi / 180.0;
        const glm::dvec3 toLight(std::sin(a), 0, std::cos(a)), mirror(-std::sin(a), 0, std::cos(a));
        s.lights.push_back(
            {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, -toLight)});
        s.lighting->globalAmbient = {0, 0, 0};
        s.lighting->specular = model;
        s.lighting->localViewer = true;
        s.lookAt = {3.0 * mirror, {0, 0, 0}, {0, 1, 0}};
        s.projection = Projection::makePerspective(kPi / 3.0, 0.0, 0.01, kInfinity);
        auto img =
            renderer().render(s.build(), test::optionsFor(size, size, ShadingMode::Phong), 0.0);
        EXPECT_TRUE(img) << img.error().describe();
        EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u);
        return img ? *img : Image(size, size);
    };
    // Head-on: the images agree within 2% of the peak.
    const Image phong0 = render(SpecularModel::Phong, 32.0, 0.0);
    const Image blinn0 = render(SpecularModel::Blinn, 128.0, 0.0);
    float peak = 0.0f, worst = 0.0f;
    for (std::size_t i = 0; i < phong0.rgba.size(); i += 4) {
        peak = std::max(peak, phong0.rgba[i]);
        worst = std::max(worst, std::abs(phong0.rgba[i] - blinn0.rgba[i]));
    }
    EXPECT_GT(peak, 0.99f);
    EXPECT_LE(worst, 0.02f * peak) << test::saveComparison(blinn0, phong0, "ln11_head_on");
    // At 75 degrees: the width across the plane of incidence (image y) at half the maximum,
    // in the column of the brightest pixel.
    auto width = [&](const Image& img) {
        int bx = 0;
        float best = -1.0f;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                if (img.pixel(x, y)[0] > best) {
                    best = img.pixel(x, y)[0];
                    bx = x;
                }
        int w = 0;
        for (int y = 0; y < size; ++y)
            w += img.pixel(bx, y)[0] >= 0.5f * best;
        return w;
    };
    const Image phong75 = render(SpecularModel::Phong, 32.0, 75.0);
    const Image blinn75 = render(SpecularModel::Blinn, 128.0, 75.0);
    const int phongWidth = width(phong75), blinnWidth = width(blinn75);
    EXPECT_GT(phongWidth, 40);
    EXPECT_LT(double(blinnWidth) / phongWidth, 0.3)
        << blinnWidth << " vs " << phongWidth << " pixels\n"
        << test::saveComparison(blinn75, phong75, "ln11_75_degrees");
}

// LN-7: node scale 1e-20 and 1e20 with the camera and the light scaled alike: the image equals
// the unit-scale render (a naive inverse-transpose normal loses the normal at 1e20 on lavapipe).
TEST_F(EdgeCasesPhong, LN7_TinyAndHugeUniformScale) {
    auto render = [&](double k) {
        LitScene s;
        const Material m =
            test::phongMaterial({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8, 1}, {1, 1, 1}, 32.0);
        s.objects.push_back(
            {makeSphere(1.0, 64, 32), m, glm::scale(glm::dmat4(1.0), glm::dvec3(k))});
        s.lights.push_back(
            {test::makeLight(LightType::Point), test::translation(k * glm::dvec3(2, 2, 4))});
        s.lookAt = {{0, 0, 4 * k}, {0, 0, 0}, {0, 1, 0}};
        s.projection = Projection::makePerspective(40.0 * kPi / 180.0, 0.0, 0.1 * k, kInfinity);
        auto img = renderer().render(s.build(), test::optionsFor(96, 96, ShadingMode::Phong), 0.0);
        EXPECT_TRUE(img) << img.error().describe();
        EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u) << k;
        return img ? *img : Image(96, 96);
    };
    const Image unit = render(1.0);
    for (const double k : {1e-20, 1e20}) {
        const Image scaled = render(k);
        double sum = 0.0;
        for (std::size_t i = 0; i < unit.rgba.size(); ++i)
            sum += double(unit.rgba[i] - scaled.rgba[i]) * double(unit.rgba[i] - scaled.rgba[i]);
        const double rmse = std::sqrt(sum / double(unit.rgba.size()));
        EXPECT_LE(rmse, 1e-4) << "scale " << k << "\n"
                              << test::saveComparison(scaled, unit, "ln7_" + std::to_string(k));
    }
}

// LN-8: a sphere scaled (1, 1, s_z): the normals the renderer writes (normal AOV) are within
// 0.01 degrees of the reference's (the cofactor normal matrix in double), down to s_z = 1e-30;
// s_z = 0 is a lit disc. No NaN.
TEST_F(EdgeCasesPhong, LN8_NonUniformAndSingularScale) {
    for (const double sz : {1e-3, 1e-6, 1e-30, 0.0}) {
        LitScene s;
        Material m;
        s.objects.push_back(
            {makeSphere(1.0, 32, 16), m, glm::scale(glm::dmat4(1.0), glm::dvec3(1, 1, sz))});
        s.lights.push_back(
            {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {0.3, -0.2, -1})});
        const std::string name = "ln8_sz" + std::to_string(sz);
        const test::ReferenceComparison c = test::compareWithReference(
            device(), s.build(), test::optionsFor(64, 64, ShadingMode::Phong), {});
        EXPECT_EQ(c.frame.readback.nonFinite, 0u) << name;
        EXPECT_LE(c.worst, kStep) << name << ": " << c.describe(name);
        const std::vector<float>& normals = c.frame.readback.image.normal;
        ASSERT_EQ(normals.size(), 64u * 64u * 3u);
        double worstDeg = 0.0;
        std::size_t covered = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const ProbeReport& r = c.at(x, y);
                if (!r.hit) continue;
                ++covered;
                const std::size_t i = (std::size_t(y) * 64 + x) * 3;
                const glm::dvec3 got(normals[i], normals[i + 1], normals[i + 2]);
                const double deg = angleDegrees(got, r.normal);
                worstDeg = std::max(worstDeg, deg);
            }
        EXPECT_GT(covered, 1000u) << name;
        EXPECT_LE(worstDeg, 0.01) << name;
        if (sz == 0.0) {
            const float* centre = c.pixel(32, 32);
            EXPECT_GT(centre[0], 0.5f) << "the disc faces the camera and the light";
        }
    }
}

// LN-13: a NaN reaching the shader (injected into the material buffer after validation) is
// counted at readback in every clamp mode: the clamps let it through (lavapipe's clamp and
// max turn NaN into 0) and the readback tests isnan/isinf before it replaces the value.
TEST_F(EdgeCasesPhong, LN13_NaNStaysVisibleThroughEveryClamp) {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 16, 8), Material{}, glm::dmat4(1.0)});
    const Scene scene = s.build();
    struct Row {
        const char* name;
        ShadingMode mode;
        bool clamp, glCompat;
    };
    for (const Row& row : {Row{"none", ShadingMode::Phong, false, false},
                           Row{"clamp", ShadingMode::Phong, true, false},
                           Row{"gl_compat_phong", ShadingMode::Phong, false, true},
                           Row{"gl_compat_gouraud", ShadingMode::Gouraud, false, true},
                           Row{"gl_compat_flat", ShadingMode::Flat, false, true}}) {
        RenderOptions o = test::optionsFor(32, 32, row.mode);
        o.clamp = row.clamp;
        o.glCompat = row.glCompat;
        auto clean = test::renderWithIds(device(), scene, o);
        ASSERT_TRUE(clean) << clean.error().describe();
        EXPECT_EQ(clean->readback.nonFinite, 0u) << row.name << ": the control has no NaN";
        render::FrameEdits poison;
        poison.list = [](gpu::DrawList& list) {
            list.materials[0].front.emission.x = std::numeric_limits<float>::quiet_NaN();
        };
        auto poisoned = test::renderWithIds(device(), scene, o, poison);
        ASSERT_TRUE(poisoned) << poisoned.error().describe();
        EXPECT_GT(poisoned->readback.nonFinite, 100u) << row.name;
        EXPECT_EQ(test::countNonFinite(poisoned->readback.image), 0u) << row.name << ": scrubbed";
    }
}

// HDR: values far above half's 65504 come out as float, unclamped and finite.
TEST_F(EdgeCasesPhong, HdrValuesAboveTheHalfRange) {
    LitScene s;
    Material m;
    s.objects.push_back({makeSphere(1.0, 32, 16), m, glm::dmat4(1.0)});
    Light l = test::makeLight(LightType::Directional);
    l.diffuse = {1e5, 1e5, 1e5};
    s.lights.push_back({l, test::aimed({0, 0, 0}, {0, 0, -1})});
    const test::ReferenceComparison c =
        check(s.build(), test::optionsFor(64, 64, ShadingMode::Phong), "hdr");
    EXPECT_GT(test::brightestColour(c.frame.readback.image), 65504.0f);
}

// LN-14: 4x MSAA with gouraud shading: no resolved pixel is below 0 or above the largest
// vertex colour (centroid interpolation keeps colours inside their triangles; without it a
// silhouette sample extrapolates, measured at -55.6 on lavapipe). A grazing point light makes
// the colours change fastest at the silhouette.
TEST_F(EdgeCasesPhong, LN14_MsaaGouraudNeverExtrapolates) {
    LitScene s;
    const Material m = test::phongMaterial({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8, 1}, {1, 1, 1}, 64.0);
    s.objects.push_back({makeSphere(1.0, 64, 32), m, glm::dmat4(1.0)});
    Light l = test::makeLight(LightType::Point);
    l.attenuation = {0.0, 0.0, 1.0};
    s.lights.push_back({l, test::translation({1.3, 0.2, -0.2})});
    const Scene scene = s.build();
    RenderOptions o = test::optionsFor(256, 256, ShadingMode::Gouraud);
    o.msaa = 4;
    const auto& counts = renderer().device().msaaSampleCounts;
    if (std::find(counts.begin(), counts.end(), 4) == counts.end())
        GTEST_SKIP() << "the device has no 4x multisampling for float colour and depth";
    auto img = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u);
    // The largest colour lit at any vertex, by the reference.
    auto plan = frame::buildFrame(scene, o, 0.0);
    ASSERT_TRUE(plan);
    const frame::Draw& d = plan->views[0].draws[0];
    const auto lights =
        frame::placeLights(scene, plan->pose, plan->views[0].camera.viewFromWorld, false);
    const glm::dmat3 normals = normalMatrix(d.viewFromModel);
    glm::dvec3 largest(0.0);
    const Primitive& p = scene.meshes[0].primitives[0];
    for (std::size_t v = 0; v < p.positions.size(); ++v) {
        const glm::dvec3 eye(d.viewFromModel * glm::dvec4(glm::dvec3(p.positions[v]), 1.0));
        const glm::dvec3 n = ref::safeNormalize(normals * glm::dvec3(p.normals[v]));
        largest = glm::max(largest, ref::shade(eye, n, m.front, lights, ref::Settings{}));
    }
    std::size_t partial = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            const float* px = img->pixel(x, y);
            partial += px[3] > 0.0f && px[3] < 1.0f;
            for (int k = 0; k < 3; ++k) {
                ASSERT_GE(px[k], -1e-6f) << x << "," << y;
                ASSERT_LE(px[k], largest[k] * (1.0 + 1e-5) + 1e-6) << x << "," << y;
            }
        }
    EXPECT_GT(partial, 100u) << "the silhouette must have partly covered pixels";
}

// LN-10: parameters the contract refuses, with the object path in the message.
TEST(LightingValidation, LN10_RefusesWhatTheContractRefuses) {
    struct Row {
        const char* name;
        std::function<void(Scene&)> edit;
        bool accepted;
        const char* object; // expected in the message
    };
    const Row rows[] = {
        {"cutoff 90.0001", [](Scene& s) { s.lights[0].spotCutoffDeg = 90.0001; }, false,
         "lights[0].spotCutoffDeg"},
        {"cutoff -0.1", [](Scene& s) { s.lights[0].spotCutoffDeg = -0.1; }, false,
         "lights[0].spotCutoffDeg"},
        {"cutoff 180", [](Scene& s) { s.lights[0].spotCutoffDeg = 180.0; }, true, ""},
        {"cutoff 0", [](Scene& s) { s.lights[0].spotCutoffDeg = 0.0; }, true, ""},
        {"shininess NaN",
         [](Scene& s) {
             s.materials[0].front.shininess = std::numeric_limits<double>::quiet_NaN();
         },
         false, "materials[0].shininess"},
        {"shininess inf", [](Scene& s) { s.materials[0].front.shininess = kInfinity; }, false,
         "materials[0].shininess"},
        {"shininess -1", [](Scene& s) { s.materials[0].front.shininess = -1.0; }, false,
         "materials[0].shininess"},
        {"shininess 1e6", [](Scene& s) { s.materials[0].front.shininess = 1e6; }, true, ""},
        {"negative attenuation",
         [](Scene& s) {
             s.lights[0].attenuation = {1.0, -0.1, 0.0};
         },
         false, "lights[0].attenuation"},
        {"zero attenuation", [](Scene& s) { s.lights[0].attenuation = glm::dvec3(0.0); }, false,
         "lights[0].attenuation"},
    };
    for (const Row& row : rows) {
        LitScene ls;
        ls.objects.push_back({makePlane(1.0, 1), Material{}, glm::dmat4(1.0)});
        ls.lights.push_back({test::makeLight(LightType::Spot), glm::dmat4(1.0)});
        Scene s = ls.build();
        row.edit(s);
        const Result<void> r = s.validate();
        EXPECT_EQ(bool(r), row.accepted) << row.name;
        if (!r) {
            EXPECT_NE(r.error().describe().find(row.object), std::string::npos)
                << row.name << ": " << r.error().describe();
        }
    }
}

} // namespace
