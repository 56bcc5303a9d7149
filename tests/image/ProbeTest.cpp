// Renderer::probe and `lantern render --probe X,Y`: the colour the reference computes at the
// surface the renderer drew at a pixel equals that pixel (within one 8-bit step), in every
// shading mode, and the report's terms add up to it.
#include "LightingCompare.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

constexpr double kStep = 1.0 / 255.0;

// A sphere with vertex colours in front of a plane, lit by an attenuated point light and a
// GL spot.
Scene probeScene() {
    LitScene s;
    Primitive sphere = makeSphere(1.0, 20, 10);
    for (const glm::vec3& n : sphere.normals)
        sphere.colors.emplace_back(0.6f + 0.3f * n.x, 0.6f + 0.3f * n.y, 0.5f, 1.0f);
    Material shiny;
    shiny.name = "shiny";
    shiny.front.specular = {0.8, 0.8, 0.8};
    shiny.front.shininess = 24.0;
    shiny.front.emission = {0.02, 0.02, 0.05};
    s.objects.push_back({sphere, shiny, test::translation({-0.4, 0.2, 0.5})});
    Material matte;
    matte.name = "matte";
    matte.front.diffuse = {0.5, 0.6, 0.7, 1.0};
    s.objects.push_back(
        {makePlane(5.0, 6), matte, glm::rotate(glm::dmat4(1.0), -0.5, glm::dvec3(1, 0, 0))});
    Light bulb = test::makeLight(LightType::Point);
    bulb.attenuation = {1.0, 0.1, 0.02};
    bulb.ambient = {0.05, 0.05, 0.05};
    s.lights.push_back({bulb, test::translation({1.5, 2.0, 2.5})});
    Light spot = test::makeLight(LightType::Spot);
    spot.spotCutoffDeg = 35.0;
    spot.spotExponent = 6.0;
    spot.diffuse = spot.specular = {0.6, 0.5, 0.4};
    s.lights.push_back({spot, test::aimed({-1.5, 1.0, 3.0}, {0.5, -0.5, -1.0})});
    return s.build();
}

struct ModeRow {
    const char* name;
    ShadingMode mode;
    bool glCompat;
};

void PrintTo(const ModeRow& r, std::ostream* os) {
    *os << r.name;
}

class ProbeModes : public GpuTest, public ::testing::WithParamInterface<ModeRow> {};

TEST_P(ProbeModes, ProbeColourEqualsThePixel) {
    const ModeRow& row = GetParam();
    const Scene scene = probeScene();
    RenderOptions o = test::optionsFor(64, 64, row.mode);
    o.glCompat = row.glCompat;
    auto img = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    int hits = 0;
    for (const auto& [x, y] : {std::pair{20, 24},
                               {26, 30},
                               {33, 18},
                               {12, 40},
                               {40, 44},
                               {50, 12},
                               {30, 58},
                               {5, 5},
                               {60, 33},
                               {36, 36}}) {
        auto r = renderer().probe(scene, o, 0.0, x, y);
        ASSERT_TRUE(r) << r.error().describe();
        EXPECT_EQ(r->x, x);
        EXPECT_EQ(r->y, y);
        const float* px = img->pixel(x, y);
        for (int k = 0; k < 4; ++k)
            EXPECT_NEAR(r->pixel[k], px[k], 1e-6 * std::max(1.0f, std::abs(px[k])));
        if (!r->hit) continue;
        ++hits;
        for (int k = 0; k < 4; ++k)
            EXPECT_NEAR(r->colour[k], px[k], kStep * std::max(1.0f, std::abs(px[k])))
                << row.name << " pixel " << x << "," << y << " channel " << k;
        EXPECT_NEAR(glm::length(r->normal), 1.0, 1e-9);
        // The terms add up to the colour (unclamped modes): e + a_m A + sum of the lights.
        if (!row.glCompat) {
            glm::dvec3 sum(0.0);
            for (const ProbeEvaluation& e : r->evaluations) {
                ASSERT_EQ(e.lights.size(), 2u);
                glm::dvec3 c = e.emission + e.globalAmbient;
                for (const ProbeLight& l : e.lights)
                    c += l.ambient + l.diffuse + l.specular;
                EXPECT_NEAR(glm::length(c - e.colour), 0.0, 1e-12);
                sum += e.weight * c;
            }
            EXPECT_NEAR(glm::length(sum - glm::dvec3(r->colour)), 0.0, 1e-12);
        }
    }
    EXPECT_GE(hits, 9);
}

INSTANTIATE_TEST_SUITE_P(Modes, ProbeModes,
                         ::testing::Values(ModeRow{"flat", ShadingMode::Flat, false},
                                           ModeRow{"gouraud", ShadingMode::Gouraud, false},
                                           ModeRow{"phong", ShadingMode::Phong, false},
                                           ModeRow{"gl_flat", ShadingMode::Flat, true},
                                           ModeRow{"gl_gouraud", ShadingMode::Gouraud, true}),
                         [](const auto& p) { return std::string(p.param.name); });

class Probe : public GpuTest {};

TEST_F(Probe, ReportsTheSurfaceMaterialAndEachLight) {
    const Scene scene = probeScene();
    const RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    auto r = renderer().probe(scene, o, 0.0, 26, 30);
    ASSERT_TRUE(r) << r.error().describe();
    ASSERT_TRUE(r->hit);
    EXPECT_EQ(r->materialName, "shiny");
    EXPECT_EQ(r->nodeName, "object");
    EXPECT_FALSE(r->backFacing);
    ASSERT_EQ(r->evaluations.size(), 1u);
    const ProbeEvaluation& e = r->evaluations[0];
    EXPECT_EQ(e.where, "surface point");
    EXPECT_EQ(e.position, r->position);
    ASSERT_EQ(e.lights.size(), 2u);
    EXPECT_EQ(e.lights[0].name, "bulb");
    EXPECT_EQ(e.lights[0].type, LightType::Point);
    EXPECT_GT(e.lights[0].attenuation, 0.0);
    EXPECT_LT(e.lights[0].attenuation, 1.0);
    EXPECT_EQ(e.lights[0].spot, 1.0);
    EXPECT_EQ(e.lights[1].name, "spot");
    EXPECT_EQ(e.lights[1].type, LightType::Spot);
    EXPECT_EQ(e.lights[1].attenuation, 1.0);
    EXPECT_GE(e.lights[1].spot, 0.0);
    EXPECT_LE(e.lights[1].spot, 1.0);
    // The surface point lies on the sphere (radius 1 at world (-0.4, 0.2, 0.5), eye = world - 4 z)
    // up to the sag of its 20 x 10 tessellation (1 - cos(9 degrees)^2 = 0.024).
    EXPECT_NEAR(glm::length(r->position - glm::dvec3(-0.4, 0.2, -3.5)), 1.0, 0.025);
    // COLOR_0 replaced ambient and diffuse.
    EXPECT_NE(e.diffuseM, glm::dvec3(r->materialSide.diffuse));
}

// Several viewports: the probe finds the view a pixel belongs to (GL's bottom-left viewport
// origin) and its ray goes through that view's camera.
TEST_F(Probe, FindsTheViewOfAPixel) {
    const Scene scene = probeScene();
    RenderOptions o = test::optionsFor(96, 64, ShadingMode::Phong);
    CameraSpec framing;
    framing.source = CameraSpec::Source::Framing;
    o.views = {View{0, 0, 48, 64, CameraSpec{}}, View{48, 16, 48, 48, framing}};
    auto img = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    int hits[2] = {0, 0};
    for (const auto& [x, y] :
         {std::pair{20, 30}, {30, 20}, {60, 30}, {70, 20}, {80, 40}, {72, 28}}) {
        auto r = renderer().probe(scene, o, 0.0, x, y);
        ASSERT_TRUE(r) << r.error().describe();
        if (!r->hit) continue;
        EXPECT_EQ(r->view, x < 48 ? 0 : 1) << x << "," << y;
        ++hits[r->view];
        const float* px = img->pixel(x, y);
        for (int k = 0; k < 4; ++k)
            EXPECT_NEAR(r->colour[k], px[k], kStep) << x << "," << y << " channel " << k;
    }
    EXPECT_GE(hits[0], 1);
    EXPECT_GE(hits[1], 2);
}

TEST_F(Probe, BackgroundAndOutsideTheImage) {
    const Scene scene = probeScene();
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    o.background = {0.1f, 0.2f, 0.3f, 0.0f};
    LitScene small;
    small.objects.push_back({makeSphere(0.2, 8, 4), Material{}, glm::dmat4(1.0)});
    auto r = renderer().probe(small.build(), o, 0.0, 0, 0);
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_FALSE(r->hit);
    EXPECT_TRUE(r->evaluations.empty());
    EXPECT_NEAR(r->pixel.g, 0.2, 1e-7);
    for (const auto& [x, y] : {std::pair{64, 0}, {0, 64}, {-1, 3}}) {
        auto bad = renderer().probe(scene, o, 0.0, x, y);
        ASSERT_FALSE(bad);
        EXPECT_EQ(bad.error().code, ErrorCode::InvalidInput);
        EXPECT_EQ(bad.error().object, "--probe");
        EXPECT_NE(bad.error().message.find("64x64"), std::string::npos) << bad.error().message;
    }
}

// `lantern render --probe`: prints the equation term by term; bad pixels are refused (exit 1).
class ProbeCli : public GpuTest {}; // skips without a device, like the renders it runs

TEST_F(ProbeCli, PrintsTheEquationAtAPixel) {
    const auto dir = test::testOutputDir();
    const std::string out = (dir / "probe.png").string();
    std::vector<std::string> command = {"render", "builtin:spheres", "--width", "64",
                                        "--height", "48", "--probe", "32,24", "-o", out};
    for (const std::string& flag : test::validationFlag()) command.push_back(flag);
    const auto r = test::runLantern(command);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << "validation messages: " << r.err;
    for (const char* text :
         {"probe pixel 32,24", "surface point (eye space)", "normal (eye space", "material ",
          "evaluated at the surface point", "light 0 \"sun\" directional",
          "light 1 \"lamp\" point: attenuation", "colour (reference)", "pixel (renderer)"})
        EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
    EXPECT_TRUE(std::filesystem::exists(out));
    for (const std::vector<std::string>& bad : {std::vector<std::string>{"--probe", "64,0"},
                                                {"--probe", "1,2,3"},
                                                {"--probe", "1.5,2"},
                                                {"--probe", "x,y"}}) {
        std::vector<std::string> args{
            "render", "builtin:spheres",         "--width", "64", "--height", "48",
            "-o",     (dir / "bad.png").string()};
        args.insert(args.end(), bad.begin(), bad.end());
        const auto b = test::runLantern(args);
        EXPECT_EQ(b.exitCode, 1) << bad[1] << "\n" << b.err;
        EXPECT_NE(b.err.find("--probe"), std::string::npos) << b.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.png")) << "nothing written for refused input";
}

} // namespace
