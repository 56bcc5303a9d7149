// Only what the scene requires: the features a scene uses select the pipeline variant
// (specialisation constants), --explain reports both, and variants are cached.
#include "LightingCompare.h"

#include <algorithm>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

bool anyContains(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

std::string joined(const FeatureReport& r) {
    std::string s = "features:";
    for (const auto& f : r.features)
        s += "\n  " + f;
    s += "\nvariants:";
    for (const auto& v : r.variants)
        s += "\n  " + v;
    return s;
}

Scene oneDirectionalNoSpecular() {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 16, 8), Material{}, glm::dmat4(1.0)}); // GL: specular 0
    s.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -1})});
    return s.build();
}

Scene everyCostlyFeature() {
    LitScene s;
    const Material m = test::phongMaterial({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8, 1}, {1, 1, 1}, 30.0);
    s.objects.push_back({makeSphere(1.0, 16, 8), m, glm::dmat4(1.0)});
    Light spot = test::makeLight(LightType::Spot);
    spot.spotCutoffDeg = 30.0;
    spot.attenuation = {1.0, 0.1, 0.0};
    s.lights.push_back({spot, test::aimed({0, 0, 3}, {0, 0, -1})});
    Light gltf = test::makeLight(LightType::Point);
    gltf.falloff = LightFalloff::Gltf;
    s.lights.push_back({gltf, test::translation({2, 2, 2})});
    return s.build();
}

class LightingVariants : public GpuTest {};

// One directional light and no specular: no spot, attenuation, falloff or specular code.
TEST_F(LightingVariants, OneDirectionalLightWithoutSpecularCompilesNothingElse) {
    const Scene scene = oneDirectionalNoSpecular();
    const RenderOptions o = test::optionsFor(48, 48, ShadingMode::Phong);
    auto r = renderer().explain(scene, o);
    ASSERT_TRUE(r) << r.error().describe();
    const std::string all = joined(*r);
    EXPECT_TRUE(anyContains(r->features, "light:directional x1")) << all;
    EXPECT_TRUE(anyContains(r->features, "specular:none")) << all;
    for (const char* absent :
         {"point", "spot", "attenuation", "falloff", "specular:blinn", "specular:phong"})
        EXPECT_FALSE(anyContains(r->features, absent)) << absent << "\n" << all;
    ASSERT_EQ(r->variants.size(), 1u) << all;
    EXPECT_NE(r->variants[0].find("phong: lights=directional specular=none"), std::string::npos)
        << all;
    for (const char* absent :
         {"attenuation", "gl-spot", "gltf-falloff", "point", "spot ", "vertex-color", "texture",
          "alpha-mask", "two-sided", "local-viewer"})
        EXPECT_EQ(r->variants[0].find(absent), std::string::npos) << absent << "\n" << all;
    // The constants themselves, as the pipeline receives them.
    auto plan = render::planFrame(scene, o, 0.0);
    ASSERT_TRUE(plan);
    const auto& sc = plan->list.views[0].draws[0].pipeline.constants;
    EXPECT_EQ(sc[LANTERN_SC_LIGHT_TYPES], std::uint32_t(LANTERN_LIGHT_BIT_DIRECTIONAL));
    EXPECT_EQ(sc[LANTERN_SC_GL_ATTENUATION], 0u);
    EXPECT_EQ(sc[LANTERN_SC_GL_SPOT], 0u);
    EXPECT_EQ(sc[LANTERN_SC_GLTF_FALLOFF], 0u);
    EXPECT_EQ(sc[LANTERN_SC_SPECULAR], std::uint32_t(LANTERN_SPECULAR_NONE));
    // And the specialised pipeline renders the equation.
    const test::ReferenceComparison c = test::compareWithReference(device(), scene, o);
    EXPECT_LE(c.worst, 1.0 / 255.0) << c.describe("variant_minimal");
}

// The same scene with a GL spot with attenuation and a glTF light: all of it is compiled in.
TEST_F(LightingVariants, CostlyFeaturesAppearWhenUsed) {
    const Scene scene = everyCostlyFeature();
    auto r = renderer().explain(scene, test::optionsFor(48, 48, ShadingMode::Phong));
    ASSERT_TRUE(r) << r.error().describe();
    const std::string all = joined(*r);
    for (const char* present : {"light:spot x1", "light:point x1", "attenuation:gl", "spot-cone:gl",
                                "falloff:gltf", "specular:blinn"})
        EXPECT_TRUE(anyContains(r->features, present)) << present << "\n" << all;
    ASSERT_EQ(r->variants.size(), 1u) << all;
    for (const char* present :
         {"lights=point+spot", "specular=blinn", "attenuation", "gl-spot", "gltf-falloff"})
        EXPECT_NE(r->variants[0].find(present), std::string::npos) << present << "\n" << all;
}

// FeatureMode::AllFeatures turns every costly feature on, and still draws the same picture.
TEST_F(LightingVariants, AllFeaturesVariantDrawsTheSamePicture) {
    const Scene scene = oneDirectionalNoSpecular();
    RenderOptions o = test::optionsFor(48, 48, ShadingMode::Phong);
    auto minimal = renderer().render(scene, o, 0.0);
    o.features = FeatureMode::AllFeatures;
    auto r = renderer().explain(scene, o);
    ASSERT_TRUE(r && minimal);
    ASSERT_EQ(r->variants.size(), 1u);
    for (const char* present : {"lights=directional+point+spot", "attenuation", "gl-spot",
                                "gltf-falloff", "vertex-color", "texture", "alpha-mask"})
        EXPECT_NE(r->variants[0].find(present), std::string::npos) << present << "\n" << joined(*r);
    auto full = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(full);
    for (std::size_t i = 0; i < full->rgba.size(); ++i)
        ASSERT_NEAR(full->rgba[i], minimal->rgba[i], 1e-6) << i;
}

// Variants are created once and reused.
TEST_F(LightingVariants, PipelinesAreCached) {
    const Scene scene = everyCostlyFeature();
    const RenderOptions o = test::optionsFor(32, 32, ShadingMode::Gouraud);
    ASSERT_TRUE(renderer().render(scene, o, 0.0));
    ASSERT_TRUE(renderer().render(scene, o, 0.0));
    EXPECT_EQ(renderer().lastFrameStats().pipelinesCreated, 0u);
}

// The command prints the features and the variants.
class LightingExplainCli : public GpuTest {}; // skips without a device

TEST_F(LightingExplainCli, PrintsFeaturesAndVariants) {
    const auto dir = test::testOutputDir();
    const auto r = test::runLantern({"render", "builtin:spheres", "--width", "32", "--height", "24",
                                     "--explain", "-o", (dir / "explain.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* text :
         {"features:", "light:directional x1", "light:point x1", "attenuation:gl", "specular:blinn",
          "pipeline variants:", "phong: lights=directional+point"})
        EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
}

// The reference is independent of the pipeline variants: it reads the scene's materials and
// the frame's lighting switches, not the specialisation constants. So a variant compiled
// with one term switched off that the scene needs (here the specular term of a shiny sphere,
// or the vertex colours of a coloured one) renders a picture the reference refuses, while
// the right variant agrees to one 8-bit step.
TEST_F(LightingVariants, AWrongSpecialisationFailsAgainstTheReference) {
    struct Row {
        const char* name;
        int constant;
        std::uint32_t wrongValue;
        ShadingMode mode;
    };
    LitScene shiny;
    shiny.objects.push_back(
        {makeSphere(1.0, 32, 16),
         test::phongMaterial({0.1, 0.1, 0.1}, {0.5, 0.5, 0.5, 1}, {1, 1, 1}, 20.0), glm::dmat4(1.0)});
    shiny.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {0.3, -0.3, -1})});
    LitScene coloured = shiny;
    Primitive& p = coloured.objects[0].primitive;
    for (const glm::vec3& v : p.positions) p.colors.push_back(glm::vec4(v * 0.5f + 0.5f, 1.0f));
    for (const Row& row : {Row{"specular_off", LANTERN_SC_SPECULAR, LANTERN_SPECULAR_NONE, ShadingMode::Phong},
                           Row{"specular_off_gouraud", LANTERN_SC_SPECULAR, LANTERN_SPECULAR_NONE,
                               ShadingMode::Gouraud},
                           Row{"vertex_colors_off", LANTERN_SC_VERTEX_COLOR, 0u, ShadingMode::Phong}}) {
        const Scene scene = row.constant == LANTERN_SC_VERTEX_COLOR ? coloured.build() : shiny.build();
        const RenderOptions o = test::optionsFor(64, 64, row.mode);
        test::PixelCheck check;
        check.skipSilhouettes = true;
        const test::ReferenceComparison right = test::compareWithReference(device(), scene, o, check);
        EXPECT_GT(right.compared, 500u) << row.name;
        EXPECT_LE(right.worst, 1.0 / 255.0) << row.name << ": " << right.describe(row.name);
        render::FrameEdits wrong;
        wrong.list = [&](gpu::DrawList& list) {
            for (gpu::ViewCommands& v : list.views)
                for (gpu::DrawCommand& d : v.draws) {
                    ASSERT_NE(d.pipeline.constants[std::size_t(row.constant)], row.wrongValue)
                        << row.name << ": the scene needs this term";
                    d.pipeline.constants[std::size_t(row.constant)] = row.wrongValue;
                }
        };
        const test::ReferenceComparison c =
            test::compareWithReference(device(), scene, o, check, wrong);
        EXPECT_GT(c.worst, 0.1) << row.name << ": the reference did not notice the missing term";
    }
}

} // namespace

